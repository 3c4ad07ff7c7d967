#include "core/io/byte_source.hpp"

#include "core/io/gzip_reader.hpp"
#include "core/io/input_error.hpp"

#include <zlib.h>

#include <algorithm>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <limits>

namespace faultline::core {

namespace {
gzFile gz(void* p) { return static_cast<gzFile>(p); }
} // namespace

ByteSource::ByteSource(const std::string& path) : m_path(path) {
    std::error_code ec;
    if (std::filesystem::is_directory(path, ec))
        throw InputError(path, "is a folder, expected a data file");
    m_fileSize = std::filesystem::file_size(path, ec);
    if (ec)
        throw InputError(path, "cannot open: " + ec.message());
    // The gzip magic, as zlib tells plain from compressed: a gzip file goes to GzipReader (its
    // seeks use access points), a plain one to zlib's direct reads.
    unsigned char magic[2] = {0, 0};
    if (std::FILE* probe = std::fopen(path.c_str(), "rb")) {
        m_compressed = std::fread(magic, 1, 2, probe) == 2 && magic[0] == 0x1f && magic[1] == 0x8b;
        std::fclose(probe);
    }
    if (m_compressed) {
        m_reader = std::make_unique<GzipReader>(path, m_fileSize);
        return;
    }
    gzFile f = gzopen(path.c_str(), "rb");
    if (!f)
        throw InputError(path, std::string("cannot open: ") + std::strerror(errno));
    gzbuffer(f, 1u << 18);
    m_gz = f;
}

ByteSource::~ByteSource() {
    if (m_gz)
        gzclose(gz(m_gz));
}

std::uint64_t ByteSource::maxUncompressedSize() const {
    if (!m_compressed)
        return m_fileSize;
    return m_fileSize * 1032ull + 65536ull;
}

std::size_t ByteSource::read(char* dst, std::size_t n) {
    if (m_reader) {
        const std::size_t got = m_reader->read(dst, n);
        m_position += got;
        return got;
    }
    std::size_t total = 0;
    while (total < n) {
        const unsigned ask = static_cast<unsigned>(std::min<std::size_t>(n - total, 1u << 30));
        const int got = gzread(gz(m_gz), dst + total, ask);
        int err = Z_OK;
        const char* msg = got <= 0 ? gzerror(gz(m_gz), &err) : nullptr;
        if (got < 0 || (err != Z_OK && err != Z_BUF_ERROR)) // a plain file: a read error
            throw InputError(m_path, InputError::Where::Byte, m_position + total,
                             std::string("cannot read the file: ") + (msg ? msg : "?"));
        if (got == 0)
            break;
        total += static_cast<std::size_t>(got);
    }
    m_position += total;
    return total;
}

void ByteSource::seek(std::uint64_t offset) {
    if (m_reader) {
        m_reader->seek(offset);
        m_position = offset;
        return;
    }
    if (offset > static_cast<std::uint64_t>(std::numeric_limits<z_off_t>::max()) ||
        gzseek(gz(m_gz), static_cast<z_off_t>(offset), SEEK_SET) < 0)
        throw InputError(m_path, InputError::Where::Byte, offset, "cannot seek to this offset");
    m_position = offset;
}

std::string readFileBytes(const std::string& path, std::uint64_t offset, std::uint64_t length) {
    ByteSource source(path);
    const std::uint64_t limit = source.maxUncompressedSize();
    if (offset > limit || (length > 0 && offset + length > limit))
        throw InputError(path, InputError::Where::Byte, offset,
                         "range of " + std::to_string(length) +
                             " bytes lies beyond the file's end");
    if (offset > 0)
        source.seek(offset);
    std::string bytes;
    if (!source.compressed()) {
        const std::uint64_t available = source.fileSize() - offset;
        const std::uint64_t want = length ? std::min(length, available) : available;
        bytes.resize(want);
        bytes.resize(source.read(bytes.data(), want));
    } else {
        // Grow as we inflate; never beyond what the compressed size can hold.
        std::size_t used = 0;
        std::size_t capacity = static_cast<std::size_t>(
            std::min<std::uint64_t>(length ? length : source.fileSize() * 4 + 4096, limit));
        bytes.resize(capacity);
        for (;;) {
            if (used == bytes.size()) {
                if (length && used >= length)
                    break;
                std::uint64_t next = std::min<std::uint64_t>(bytes.size() * 2, limit);
                if (length)
                    next = std::min<std::uint64_t>(next, length);
                if (next <= used)
                    break;
                bytes.resize(next);
            }
            const std::size_t got = source.read(bytes.data() + used, bytes.size() - used);
            if (got == 0)
                break;
            used += got;
        }
        bytes.resize(used);
    }
    if (length && bytes.size() < length)
        throw InputError(path, InputError::Where::Byte, offset + bytes.size(),
                         "file is shorter than its index says (changed on disk?)");
    return bytes;
}

std::string peekFileBytes(const std::string& path, std::size_t n) {
    try {
        ByteSource source(path);
        std::string bytes(n, '\0');
        bytes.resize(source.read(bytes.data(), n));
        return bytes;
    } catch (const InputError&) {
        return {};
    }
}

} // namespace faultline::core
