// Parse speed of the VTK readers on a 525,000-sphere frame (id, radius, velocity, 2 scalars),
// built in memory once per format: legacy ASCII and BINARY, XML ascii, base64, appended, zlib.
#include "core/io/vtk_legacy.hpp"
#include "core/io/vtk_xml.hpp"

#include <benchmark/benchmark.h>
#include <zlib.h>

#include <bit>
#include <cstdio>
#include <cstring>
#include <random>
#include <string>
#include <vector>

using namespace faultline::core;

namespace {

constexpr std::size_t kSpheres = 525000;

struct Columns {
    std::vector<float> pos, vel, strain;
    std::vector<double> radius;
    std::vector<std::int32_t> id, layer;
};

const Columns& columns() {
    static const Columns c = [] {
        Columns c;
        std::mt19937 rng(7);
        std::uniform_real_distribution<float> u(-50.f, 50.f);
        for (std::size_t i = 0; i < kSpheres; ++i) {
            for (int k = 0; k < 3; ++k) {
                c.pos.push_back(u(rng));
                c.vel.push_back(u(rng) * 1e-3f);
            }
            c.radius.push_back(0.4 + 0.001 * static_cast<double>(i % 200));
            c.strain.push_back(u(rng) * 1e-2f);
            c.id.push_back(static_cast<std::int32_t>(i + 1));
            c.layer.push_back(static_cast<std::int32_t>(i % 7));
        }
        return c;
    }();
    return c;
}

template <typename T> void put(std::string& out, T v, bool big) {
    char b[sizeof(T)];
    std::memcpy(b, &v, sizeof(T));
    if (big == (std::endian::native == std::endian::little))
        for (std::size_t i = 0; i < sizeof(T) / 2; ++i)
            std::swap(b[i], b[sizeof(T) - 1 - i]);
    out.append(b, sizeof(T));
}
template <typename T> std::string bytesOf(const std::vector<T>& v, bool big) {
    std::string s;
    s.reserve(v.size() * sizeof(T));
    for (T x : v)
        put(s, x, big);
    return s;
}
template <typename T> std::string textOf(const std::vector<T>& v, std::size_t perLine) {
    std::string s;
    char buf[32];
    for (std::size_t i = 0; i < v.size(); ++i) {
        std::snprintf(buf, sizeof buf, "%.9g", static_cast<double>(v[i]));
        s += buf;
        s += (i + 1) % perLine == 0 ? '\n' : ' ';
    }
    return s + "\n";
}

std::string legacy(bool binary) {
    const Columns& c = columns();
    const std::string n = std::to_string(kSpheres);
    auto data = [&](const auto& v, std::size_t perLine) {
        return binary ? bytesOf(v, true) + "\n" : textOf(v, perLine);
    };
    std::string s = "# vtk DataFile Version 3.0\nbench\n" +
                    std::string(binary ? "BINARY" : "ASCII") + "\nDATASET POLYDATA\nPOINTS " + n +
                    " float\n" + data(c.pos, 3);
    s +=
        "POINT_DATA " + n + "\nSCALARS radius double 1\nLOOKUP_TABLE default\n" + data(c.radius, 9);
    s += "SCALARS id int 1\nLOOKUP_TABLE default\n" + data(c.id, 9);
    s += "VECTORS velocity float\n" + data(c.vel, 3);
    s += "FIELD FieldData 2\nstrain 1 " + n + " float\n" + data(c.strain, 9);
    s += "layer 1 " + n + " int\n" + data(c.layer, 9);
    return s;
}

std::string base64(const std::string& bytes) {
    static const char* k = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    std::string out;
    out.reserve(bytes.size() / 3 * 4 + 4);
    for (std::size_t i = 0; i < bytes.size(); i += 3) {
        const std::size_t n = std::min<std::size_t>(3, bytes.size() - i);
        std::uint32_t v = 0;
        for (std::size_t j = 0; j < 3; ++j)
            v = (v << 8) | (j < n ? static_cast<unsigned char>(bytes[i + j]) : 0u);
        out += k[(v >> 18) & 63];
        out += k[(v >> 12) & 63];
        out += n > 1 ? k[(v >> 6) & 63] : '=';
        out += n > 2 ? k[v & 63] : '=';
    }
    return out;
}

enum class XmlMode { Ascii, Base64, AppendedRaw, AppendedZlib };

std::string xml(XmlMode mode) {
    const Columns& c = columns();
    std::string appended;
    auto block = [&](const std::string& raw) {
        std::string header, body;
        if (mode != XmlMode::AppendedZlib) {
            put<std::uint64_t>(header, raw.size(), false);
            return header + raw;
        }
        const std::size_t bs = 32768, blocks = (raw.size() + bs - 1) / bs;
        put<std::uint64_t>(header, blocks, false);
        put<std::uint64_t>(header, bs, false);
        put<std::uint64_t>(header, raw.size() % bs, false);
        for (std::size_t b = 0; b < blocks; ++b) {
            const std::string in = raw.substr(b * bs, bs);
            uLongf size = compressBound(in.size());
            std::string out(size, '\0');
            compress2(reinterpret_cast<Bytef*>(out.data()), &size,
                      reinterpret_cast<const Bytef*>(in.data()), in.size(), 6);
            out.resize(size);
            put<std::uint64_t>(header, size, false);
            body += out;
        }
        return header + body;
    };
    auto array = [&](const char* type, const char* name, int comps, const auto& v) {
        std::string tag = std::string("<DataArray type=\"") + type + "\" Name=\"" + name +
                          "\" NumberOfComponents=\"" + std::to_string(comps) + "\" format=\"";
        switch (mode) {
        case XmlMode::Ascii:
            return tag + "ascii\">\n" + textOf(v, 9) + "</DataArray>\n";
        case XmlMode::Base64:
            return tag + "binary\">\n" + base64(block(bytesOf(v, false))) + "\n</DataArray>\n";
        default: {
            tag += "appended\" offset=\"" + std::to_string(appended.size()) + "\"/>\n";
            appended += block(bytesOf(v, false));
            return tag;
        }
        }
    };
    std::string s = std::string("<VTKFile type=\"UnstructuredGrid\" version=\"1.0\" "
                                "byte_order=\"LittleEndian\" header_type=\"UInt64\"") +
                    (mode == XmlMode::AppendedZlib ? " compressor=\"vtkZLibDataCompressor\"" : "") +
                    ">\n<UnstructuredGrid>\n<Piece NumberOfPoints=\"" + std::to_string(kSpheres) +
                    "\" NumberOfCells=\"0\">\n<Points>\n" + array("Float32", "Points", 3, c.pos) +
                    "</Points>\n<PointData>\n" + array("Float64", "radius", 1, c.radius) +
                    array("Int32", "id", 1, c.id) + array("Float32", "velocity", 3, c.vel) +
                    array("Float32", "strain", 1, c.strain) + array("Int32", "layer", 1, c.layer) +
                    "</PointData>\n</Piece>\n</UnstructuredGrid>\n";
    if (mode == XmlMode::AppendedRaw || mode == XmlMode::AppendedZlib)
        s += "<AppendedData encoding=\"raw\">\n_" + appended + "\n</AppendedData>\n";
    return s + "</VTKFile>\n";
}

template <typename Parse> void run(benchmark::State& state, const std::string& bytes, Parse parse) {
    for (auto _ : state) {
        Frame f = parse(bytes);
        if (f.size() != kSpheres)
            state.SkipWithError("wrong sphere count");
        benchmark::DoNotOptimize(f);
    }
    state.SetBytesProcessed(static_cast<std::int64_t>(state.iterations() * bytes.size()));
    state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations() * kSpheres));
    state.counters["file_MB"] = static_cast<double>(bytes.size()) / 1e6;
}

void BM_VtkLegacyAscii(benchmark::State& s) {
    static const std::string b = legacy(false);
    run(s, b, [](const std::string& x) { return parseVtkLegacy("bench.vtk", x); });
}
void BM_VtkLegacyBinary(benchmark::State& s) {
    static const std::string b = legacy(true);
    run(s, b, [](const std::string& x) { return parseVtkLegacy("bench.vtk", x); });
}
void BM_VtkXml(benchmark::State& s) {
    static const std::string b[] = {xml(XmlMode::Ascii), xml(XmlMode::Base64),
                                    xml(XmlMode::AppendedRaw), xml(XmlMode::AppendedZlib)};
    static const char* names[] = {"ascii", "inline base64", "appended raw", "appended raw zlib"};
    s.SetLabel(names[s.range(0)]);
    run(s, b[s.range(0)], [](const std::string& x) { return parseVtkXml("bench.vtu", x); });
}

} // namespace

BENCHMARK(BM_VtkLegacyAscii)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_VtkLegacyBinary)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_VtkXml)->DenseRange(0, 3)->Unit(benchmark::kMillisecond);
BENCHMARK_MAIN();
