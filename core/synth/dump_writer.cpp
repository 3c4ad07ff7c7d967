#include "core/synth/dump_writer.hpp"

#include <tbb/parallel_for.h>
#include <zlib.h>

#include <algorithm>
#include <cassert>
#include <charconv>
#include <cstdio>
#include <stdexcept>

namespace faultline::core {

namespace {

enum class Source { Id, X, Y, Z, Radius, Attribute };

struct ColumnRef {
    Source source = Source::Attribute;
    const AttributeColumn* attribute = nullptr;
};

template <typename T> void append(std::string& out, T value) {
    char buf[64];
    auto r = std::to_chars(buf, buf + sizeof buf, value);
    assert(r.ec == std::errc());
    out.append(buf, r.ptr);
}

} // namespace

LammpsDumpWriter::LammpsDumpWriter(std::string path, int gzipLevel) : m_path(std::move(path)) {
    if (gzipLevel > 0) {
        const std::string mode = "wb" + std::to_string(std::min(gzipLevel, 9));
        m_gz = gzopen(m_path.c_str(), mode.c_str());
        if (!m_gz)
            throw std::runtime_error(m_path + ": cannot open for writing");
        gzbuffer(static_cast<gzFile>(m_gz), 1 << 20);
    } else {
        m_file = std::fopen(m_path.c_str(), "wb");
        if (!m_file)
            throw std::runtime_error(m_path + ": cannot open for writing");
    }
}

LammpsDumpWriter::~LammpsDumpWriter() {
    if (m_gz)
        gzclose(static_cast<gzFile>(m_gz));
    if (m_file)
        std::fclose(m_file);
}

void LammpsDumpWriter::put(const std::string& text) {
    if (text.empty() || m_failed)
        return;
    if (m_gz) {
        // gzwrite takes an unsigned count: write in pieces well below its limit.
        std::size_t done = 0;
        while (done < text.size()) {
            const unsigned piece =
                static_cast<unsigned>(std::min<std::size_t>(text.size() - done, 1u << 30));
            if (gzwrite(static_cast<gzFile>(m_gz), text.data() + done, piece) !=
                static_cast<int>(piece)) {
                m_failed = true;
                return;
            }
            done += piece;
        }
    } else if (std::fwrite(text.data(), 1, text.size(), m_file) != text.size()) {
        m_failed = true;
    }
}

void LammpsDumpWriter::write(const Frame& frame, const std::vector<std::string>& columns) {
    assert(m_gz || m_file);
    std::vector<ColumnRef> refs;
    for (const auto& name : columns) {
        ColumnRef ref;
        if (name == "id")
            ref.source = Source::Id;
        else if (name == "x")
            ref.source = Source::X;
        else if (name == "y")
            ref.source = Source::Y;
        else if (name == "z")
            ref.source = Source::Z;
        else if (name == "radius")
            ref.source = Source::Radius;
        else {
            ref.attribute = frame.attribute(name);
            assert(ref.attribute && "LammpsDumpWriter: the frame has no such attribute");
            assert(ref.attribute->size() == frame.size());
        }
        refs.push_back(ref);
    }

    std::string head = "ITEM: TIMESTEP\n";
    append(head, frame.timestep);
    head += "\nITEM: NUMBER OF ATOMS\n";
    append(head, static_cast<std::uint64_t>(frame.size()));
    head += "\nITEM: BOX BOUNDS";
    for (int a = 0; a < 3; ++a)
        head += frame.box.periodic[a] ? " pp" : " ff";
    head += '\n';
    for (int a = 0; a < 3; ++a) {
        append(head, frame.box.lo[a]);
        head += ' ';
        append(head, frame.box.hi[a]);
        head += '\n';
    }
    head += "ITEM: ATOMS";
    for (const auto& name : columns)
        head += ' ' + name;
    head += '\n';
    put(head);

    // Rows are formatted in parallel chunks and written in order: the bytes do not depend on
    // the thread count.
    constexpr std::size_t kChunk = 8192;
    const std::size_t n = frame.size();
    const std::size_t chunks = (n + kChunk - 1) / kChunk;
    std::vector<std::string> text(chunks);
    tbb::parallel_for(std::size_t(0), chunks, [&](std::size_t c) {
        std::string& out = text[c];
        const std::size_t begin = c * kChunk, end = std::min(n, begin + kChunk);
        out.reserve((end - begin) * 16 * refs.size());
        for (std::size_t i = begin; i < end; ++i) {
            for (std::size_t k = 0; k < refs.size(); ++k) {
                if (k)
                    out += ' ';
                const ColumnRef& ref = refs[k];
                switch (ref.source) {
                case Source::Id:
                    append(out, frame.ids[i]);
                    break;
                case Source::X:
                    append(out, frame.x[i]);
                    break;
                case Source::Y:
                    append(out, frame.y[i]);
                    break;
                case Source::Z:
                    append(out, frame.z[i]);
                    break;
                case Source::Radius:
                    append(out, frame.radius[i]);
                    break;
                case Source::Attribute:
                    if (ref.attribute->isInteger())
                        append(out, ref.attribute->ints[i]);
                    else
                        append(out, ref.attribute->floats[i]);
                    break;
                }
            }
            out += '\n';
        }
    });
    for (const auto& t : text)
        put(t);
    if (m_failed)
        throw std::runtime_error(m_path + ": write failed (disk full?)");
}

void LammpsDumpWriter::close() {
    bool ok = !m_failed;
    if (m_gz) {
        ok = gzclose(static_cast<gzFile>(m_gz)) == Z_OK && ok;
        m_gz = nullptr;
    }
    if (m_file) {
        ok = std::fclose(m_file) == 0 && ok;
        m_file = nullptr;
    }
    if (!ok)
        throw std::runtime_error(m_path + ": write failed (disk full?)");
}

} // namespace faultline::core
