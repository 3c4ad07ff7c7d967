#include "core/io/frame_source.hpp"
#include "core/util/enum_names.hpp"

#include "core/io/byte_source.hpp"
#include "core/io/extxyz.hpp"
#include "core/io/input_error.hpp"
#include "core/io/lammps_dump.hpp"
#include "core/io/mercury_data.hpp"
#include "core/io/table_reader.hpp"
#include "core/io/vtk_legacy.hpp"
#include "core/io/vtk_xml.hpp"

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <filesystem>
#include <fstream>

namespace faultline::core {

namespace {
constexpr EnumName<FileFormat> kFormats[] = {{FileFormat::LammpsDump, "LAMMPS dump"},
                                             {FileFormat::VtkLegacy, "VTK legacy"},
                                             {FileFormat::VtkXml, "VTK XML"},
                                             {FileFormat::VtkCollection, "VTK collection (.pvd)"},
                                             {FileFormat::Table, "CSV / text table"},
                                             {FileFormat::Xyz, "XYZ / extended XYZ"},
                                             {FileFormat::MercuryData, "MercuryDPM .data"}};
} // namespace

std::string_view formatName(FileFormat format) { return nameIn(kFormats, format); }

namespace {
// The file's name without a compressor's extension: "dump.lammpstrj" for "run/dump.lammpstrj.gz".
std::filesystem::path uncompressedName(const std::string& path) {
    std::filesystem::path file = std::filesystem::path(path).filename();
    const std::string ext = file.extension().string();
    return ext == ".gz" || ext == ".bz2" || ext == ".xz" ? file.stem() : file;
}
} // namespace

FileFormat detectFormat(const std::string& path) {
    ByteSource probe(path); // throws a clear error for a missing or unreadable file
    std::string head(4096, '\0');
    head.resize(probe.read(head.data(), head.size()));
    if (head.empty())
        throw InputError(path, "empty file");
    if (looksLikeLammpsDump(head))
        return FileFormat::LammpsDump;
    if (looksLikeVtkLegacy(head))
        return FileFormat::VtkLegacy;
    if (looksLikeVtkCollection(head))
        return FileFormat::VtkCollection;
    if (looksLikeVtkXml(head))
        return FileFormat::VtkXml;
    if (looksLikeXyz(head))
        return FileFormat::Xyz;
    if (looksLikeMercuryData(head))
        return FileFormat::MercuryData;
    // A file named as a LAMMPS trajectory that does not read as one gets the dump reader's
    // error ("expected ITEM: TIMESTEP ..."), not a table's (walkthrough of issue 41).
    if (uncompressedName(path).extension() == ".lammpstrj")
        return FileFormat::LammpsDump;
    // A table needs a text header naming x, y and z: parseTable checks that precisely.
    for (unsigned char c : head)
        if (c == 0 || (c < 32 && c != '\n' && c != '\r' && c != '\t'))
            throw InputError(
                path, "binary data of no known format (expected a LAMMPS dump, "
                      "VTK legacy or XML file, (extended) XYZ, MercuryDPM .data, or a CSV table)");
    return FileFormat::Table;
}

namespace {

// A frame that is one byte range of a multi-frame file (as its index found it).
template <class Index>
FrameLocation pieceOfFile(const std::string& path, FileFormat format, std::int64_t timestep,
                          double time, std::uint64_t particles, const Index& f) {
    FrameLocation loc;
    loc.format = format;
    loc.timestep = timestep;
    loc.time = time;
    loc.particleCount = particles;
    loc.pieces.push_back({path, f.offset, f.length, f.firstLine});
    return loc;
}

} // namespace

std::optional<std::int64_t> numberInFileName(const std::string& path) {
    // Without its extension (and a compressor's): "run_100.vtk", "data.0012.vtu", "t_5.csv.gz".
    std::string name = uncompressedName(path).stem().string();
    std::size_t end = name.size();
    while (end > 0 && !std::isdigit(static_cast<unsigned char>(name[end - 1])))
        --end;
    std::size_t begin = end;
    while (begin > 0 && std::isdigit(static_cast<unsigned char>(name[begin - 1])))
        --begin;
    if (begin == end || end - begin > 18)
        return std::nullopt;
    return std::stoll(name.substr(begin, end - begin));
}

bool isVtkRectilinearGrid(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    char head[512] = {};
    in.read(head, sizeof head - 1);
    const std::string_view text(head, static_cast<std::size_t>(in.gcount()));
    return text.rfind("# vtk DataFile", 0) == 0 &&
           text.find("DATASET RECTILINEAR_GRID") != std::string_view::npos;
}

SimulationBox readVtkRectilinearBox(const std::string& path) {
    // A few hundred bytes as LIGGGHTS writes them; a megabyte is not a box.
    constexpr std::size_t kMostBytes = 1 << 20;
    const std::string head = peekFileBytes(path, kMostBytes + 1);
    if (head.size() > kMostBytes)
        throw InputError(path, "over a megabyte: expected a bounding box of a few hundred bytes");
    // The words with their line numbers.
    std::vector<std::pair<std::string_view, std::uint64_t>> words;
    std::uint64_t line = 1;
    for (std::size_t i = 0; i < head.size();) {
        const char c = head[i];
        if (c == '\n') {
            ++line, ++i;
        } else if (std::isspace(static_cast<unsigned char>(c))) {
            ++i;
        } else {
            const std::size_t from = i;
            while (i < head.size() && !std::isspace(static_cast<unsigned char>(head[i])))
                ++i;
            words.push_back({std::string_view(head).substr(from, i - from), line});
        }
    }
    auto fail = [&](std::uint64_t at, const std::string& what) -> void {
        throw InputError(path, InputError::Where::Line, at, what);
    };
    if (head.rfind("# vtk DataFile", 0) != 0)
        fail(1, "expected '# vtk DataFile Version ...' (a legacy VTK file)");
    SimulationBox box;
    bool grid = false, seen[3] = {false, false, false};
    static constexpr std::string_view kAxes[3] = {"X_COORDINATES", "Y_COORDINATES",
                                                  "Z_COORDINATES"};
    for (std::size_t w = 0; w < words.size(); ++w) {
        const auto [word, at] = words[w];
        if (at == 1 || at == 2)
            continue; // the version line and the title
        if (word == "BINARY")
            fail(at, "expected ASCII (a binary bounding box is not read)");
        if (word == "DATASET") {
            if (w + 1 >= words.size() || words[w + 1].first != "RECTILINEAR_GRID")
                fail(at, "expected DATASET RECTILINEAR_GRID");
            grid = true;
            continue;
        }
        const auto axis = std::find(std::begin(kAxes), std::end(kAxes), word) - std::begin(kAxes);
        if (axis == 3)
            continue;
        if (!grid)
            fail(at, "expected DATASET RECTILINEAR_GRID before " + std::string(word));
        long long n = 0;
        const std::string_view count = w + 1 < words.size() ? words[w + 1].first : "";
        const auto counted = std::from_chars(count.data(), count.data() + count.size(), n);
        if (w + 2 >= words.size() || counted.ec != std::errc() ||
            counted.ptr != count.data() + count.size() || n < 1 ||
            n > static_cast<long long>(words.size() - w - 3))
            fail(at, "expected " + std::string(word) + " <count> <type> and that many numbers");
        double lo = INFINITY, hi = -INFINITY;
        for (long long k = 0; k < n; ++k) {
            auto [number, where] = words[w + 3 + std::size_t(k)];
            if (number.size() > 1 && number.front() == '+')
                number.remove_prefix(1); // from_chars takes no '+'
            double v = 0;
            const auto r = std::from_chars(number.data(), number.data() + number.size(), v);
            if (r.ec != std::errc() || r.ptr != number.data() + number.size() || !std::isfinite(v))
                fail(where,
                     "expected a coordinate, found '" + std::string(number.substr(0, 40)) + "'");
            lo = std::min(lo, v), hi = std::max(hi, v);
        }
        box.lo[std::size_t(axis)] = lo, box.hi[std::size_t(axis)] = hi;
        seen[axis] = true;
        w += 2 + std::size_t(n);
    }
    for (int a = 0; a < 3; ++a)
        if (!seen[a])
            throw InputError(path, grid ? "no " + std::string(kAxes[a]) + ": expected all three"
                                        : "expected DATASET RECTILINEAR_GRID (a bounding box)");
    box.known = true;
    return box;
}

std::vector<FrameLocation> indexDataFile(const std::string& path, std::string* partial) {
    const FileFormat format = detectFormat(path);
    std::vector<FrameLocation> frames;
    switch (format) {
    case FileFormat::LammpsDump:
        for (const auto& f : indexLammpsDump(path, partial))
            frames.push_back(pieceOfFile(path, format, f.timestep, double(f.timestep), f.atoms, f));
        break;
    case FileFormat::Xyz:
        for (const auto& f : indexXyz(path, partial))
            frames.push_back(pieceOfFile(path, format, f.timestep, double(f.timestep), f.atoms, f));
        break;
    case FileFormat::MercuryData: {
        std::int64_t step = 0;
        for (const auto& f : indexMercuryData(path, partial))
            frames.push_back(pieceOfFile(path, format, step++, f.time, f.particles, f));
        break;
    }
    case FileFormat::VtkCollection: {
        const auto folder = std::filesystem::path(path).parent_path();
        const std::string bytes = readFileBytes(path);
        std::int64_t index = 0;
        for (const auto& entry : parseVtkCollection(path, bytes)) {
            std::filesystem::path file(entry.file);
            if (file.is_relative())
                file = folder / file;
            FrameLocation loc;
            loc.format = detectFormat(file.string());
            if (loc.format == FileFormat::VtkCollection || loc.format == FileFormat::LammpsDump ||
                loc.format == FileFormat::Xyz || loc.format == FileFormat::MercuryData)
                throw InputError(path, "collection entry '" + entry.file +
                                           "' must be a single-frame VTK file");
            loc.timestep = index++;
            loc.time = entry.time;
            loc.pieces.push_back({file.string(), 0, 0, 1});
            frames.push_back(std::move(loc));
        }
        if (frames.empty())
            throw InputError(path, "collection lists no DataSet files");
        break;
    }
    default: {
        // One frame a file, which holds no time (Yade's VTKExporter, LIGGGHTS' custom/vtk, CSV
        // series): the last number in the file's name is its timestep ("run_49600.vtk").
        FrameLocation loc;
        loc.format = format;
        if (auto step = numberInFileName(path)) {
            loc.timestep = *step;
            loc.time = static_cast<double>(*step);
        }
        loc.pieces.push_back({path, 0, 0, 1});
        frames.push_back(std::move(loc));
    }
    }
    return frames;
}

namespace {
Frame loadPiece(FileFormat format, const FramePiece& piece) {
    const std::string bytes = readFileBytes(piece.path, piece.offset, piece.length);
    switch (format) {
    case FileFormat::LammpsDump:
        return parseLammpsDumpFrame(piece.path, bytes, piece.firstLine);
    case FileFormat::VtkLegacy:
        return parseVtkLegacy(piece.path, bytes);
    case FileFormat::VtkXml:
        return parseVtkXml(piece.path, bytes);
    case FileFormat::Table:
        return parseTable(piece.path, bytes);
    case FileFormat::Xyz:
        return parseXyzFrame(piece.path, bytes, piece.firstLine);
    case FileFormat::MercuryData:
        return parseMercuryDataFrame(piece.path, bytes, piece.firstLine);
    case FileFormat::VtkCollection:
        break;
    }
    throw InputError(piece.path, "a collection is not a frame");
}
} // namespace

Frame loadFrame(const FrameLocation& location) {
    if (location.pieces.size() == 1) {
        Frame f = loadPiece(location.format, location.pieces.front());
        if (location.format != FileFormat::LammpsDump)
            f.timestep = location.timestep;
        if (!location.boxPath.empty() && !f.box.known)
            f.box = readVtkRectilinearBox(location.boxPath);
        return f;
    }
    std::vector<Frame> pieces;
    pieces.reserve(location.pieces.size());
    for (const auto& piece : location.pieces)
        pieces.push_back(loadPiece(location.format, piece));
    return mergeFrames(std::move(pieces), location.pieces.front().path);
}

Frame mergeFrames(std::vector<Frame>&& pieces, const std::string& pathForErrors) {
    if (pieces.empty())
        throw InputError(pathForErrors, "no pieces to merge");
    Frame out = std::move(pieces.front());
    for (std::size_t p = 1; p < pieces.size(); ++p) {
        Frame& f = pieces[p];
        if (f.timestep != out.timestep)
            throw InputError(pathForErrors, "per-processor pieces disagree on the timestep (" +
                                                std::to_string(out.timestep) + " vs " +
                                                std::to_string(f.timestep) + ")");
        if (f.attributes.size() != out.attributes.size())
            throw InputError(pathForErrors, "per-processor pieces have different columns");
        auto append = [](auto& dst, const auto& src) {
            dst.insert(dst.end(), src.begin(), src.end());
        };
        append(out.ids, f.ids);
        append(out.x, f.x);
        append(out.y, f.y);
        append(out.z, f.z);
        append(out.radius, f.radius);
        for (std::size_t c = 0; c < out.attributes.size(); ++c) {
            AttributeColumn& dst = out.attributes[c];
            const AttributeColumn* src = f.attribute(dst.name);
            if (!src)
                throw InputError(pathForErrors,
                                 "piece " + std::to_string(p) + " lacks column '" + dst.name + "'");
            if (dst.type == src->type) {
                append(dst.floats, src->floats);
                append(dst.ints, src->ints);
            } else {
                // One piece saw only integers: widen both to float.
                if (dst.type == ColumnType::Int32) {
                    dst.floats.assign(dst.ints.begin(), dst.ints.end());
                    dst.ints.clear();
                    dst.type = ColumnType::Float32;
                }
                if (src->type == ColumnType::Int32)
                    dst.floats.insert(dst.floats.end(), src->ints.begin(), src->ints.end());
                else
                    append(dst.floats, src->floats);
            }
        }
        f = Frame(); // release memory as we go
    }
    try {
        out.finalize();
    } catch (const std::invalid_argument& e) {
        throw InputError(pathForErrors, e.what());
    }
    return out;
}

} // namespace faultline::core
