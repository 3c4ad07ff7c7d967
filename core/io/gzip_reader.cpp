#include "core/io/gzip_reader.hpp"

#include "core/io/input_error.hpp"

#include <zlib.h>

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <filesystem>
#include <limits>
#include <list>
#include <map>
#include <mutex>
#include <sys/types.h>

namespace faultline::core {

namespace {
constexpr std::size_t kWindow = 32768; // deflate's largest back-reference
constexpr std::size_t kInput = 1u << 18;
constexpr std::uint64_t kDefaultSpacing = 4ull << 20;
// Access points' windows kept for all files together; the least recently opened files' go first.
constexpr std::size_t kRegistryBytes = 256u << 20;
// At most about this many points a file: a larger file gets a wider spacing.
constexpr std::uint64_t kPointsPerFile = 2048;

z_stream* zs(void* p) { return static_cast<z_stream*>(p); }
} // namespace

namespace detail {

struct GzipAccessPoint {
    std::uint64_t out = 0; // uncompressed offset
    std::uint64_t in = 0;  // file offset of the first byte not wholly consumed before it
    int bits = 0;          // bits of the byte before `in` that belong to the block (0-7)
    std::vector<unsigned char> window; // the output before it (up to 32 KB, within its member)
};

struct GzipIndex {
    std::uint64_t spacing = kDefaultSpacing;
    std::mutex mutex;
    std::map<std::uint64_t, std::shared_ptr<const GzipAccessPoint>> points; // by `out`

    // `out` when a point there is wanted; else the next output offset worth asking about.
    std::uint64_t wantedFrom(std::uint64_t out) {
        std::lock_guard lock(mutex);
        auto after = points.upper_bound(out);
        if (after != points.begin()) {
            const std::uint64_t before = std::prev(after)->first;
            if (out - before < spacing)
                return before + spacing;
        }
        if (after != points.end() && after->first - out < spacing)
            return after->first + spacing;
        return out;
    }
    void add(std::shared_ptr<const GzipAccessPoint> point) {
        std::lock_guard lock(mutex);
        points.emplace(point->out, std::move(point));
    }
    std::shared_ptr<const GzipAccessPoint> before(std::uint64_t offset) {
        std::lock_guard lock(mutex);
        auto after = points.upper_bound(offset);
        return after == points.begin() ? nullptr : std::prev(after)->second;
    }
    std::size_t bytes() {
        std::lock_guard lock(mutex);
        return points.size() * (kWindow + sizeof(GzipAccessPoint));
    }
};

namespace {
struct Registry {
    std::mutex mutex;
    std::list<std::pair<std::string, std::shared_ptr<GzipIndex>>> files; // most recent first
    std::uint64_t minSpacing = 0;
};
Registry& registry() {
    static Registry r;
    return r;
}

// Path (absolute), size and modification time: a file rewritten gets a new index.
std::string fileKey(const std::string& path, std::uint64_t size) {
    std::error_code ec;
    const auto absolute = std::filesystem::absolute(path, ec);
    const auto modified = std::filesystem::last_write_time(path, ec);
    return (ec ? path : absolute.string()) + '\n' + std::to_string(size) + '\n' +
           std::to_string(ec ? 0 : modified.time_since_epoch().count());
}

std::shared_ptr<GzipIndex> indexFor(const std::string& path, std::uint64_t fileSize) {
    const std::string key = fileKey(path, fileSize);
    Registry& r = registry();
    std::lock_guard lock(r.mutex);
    for (auto it = r.files.begin(); it != r.files.end(); ++it)
        if (it->first == key) {
            r.files.splice(r.files.begin(), r.files, it);
            return it->second;
        }
    auto index = std::make_shared<GzipIndex>();
    // Text compresses about 3-10 times: a spacing that keeps a file to about kPointsPerFile.
    index->spacing =
        std::max(r.minSpacing ? r.minSpacing : kDefaultSpacing, fileSize / kPointsPerFile * 10);
    r.files.emplace_front(key, index);
    std::size_t total = 0;
    for (auto it = r.files.begin(); it != r.files.end();) {
        total += it->second->bytes();
        if (total > kRegistryBytes && it != r.files.begin())
            it = r.files.erase(it); // readers that hold it keep it
        else
            ++it;
    }
    return index;
}
} // namespace

void setGzipIndexSpacing(std::uint64_t bytes) {
    std::lock_guard lock(registry().mutex);
    registry().minSpacing = bytes;
}

void clearGzipIndexes() {
    std::lock_guard lock(registry().mutex);
    registry().files.clear();
}

std::size_t gzipAccessPoints(const std::string& path) {
    std::error_code ec;
    const std::uint64_t size = std::filesystem::file_size(path, ec);
    const std::string key = fileKey(path, ec ? 0 : size);
    std::shared_ptr<GzipIndex> index;
    {
        std::lock_guard lock(registry().mutex);
        for (const auto& [k, i] : registry().files)
            if (k == key)
                index = i;
    }
    if (!index)
        return 0;
    std::lock_guard lock(index->mutex);
    return index->points.size();
}

} // namespace detail

GzipReader::GzipReader(const std::string& path, std::uint64_t fileSize)
    : m_path(path), m_in(kInput), m_ring(kWindow) {
    m_file = std::fopen(path.c_str(), "rb");
    if (!m_file)
        throw InputError(path, std::string("cannot open: ") + std::strerror(errno));
    std::setvbuf(m_file, nullptr, _IONBF, 0); // reads are large: no second buffer
    auto* s = new z_stream{};
    if (inflateInit2(s, 15 + 32) != Z_OK) { // 15 + 32: a gzip or zlib header, the largest window
        delete s;
        std::fclose(m_file);
        throw InputError(path, "cannot inflate: out of memory");
    }
    m_stream = s;
    s->next_in = m_in.data();
    s->avail_in = 0;
    m_index = detail::indexFor(path, fileSize);
}

GzipReader::~GzipReader() {
    inflateEnd(zs(m_stream));
    delete zs(m_stream);
    std::fclose(m_file);
}

void GzipReader::fail(const std::string& what) const {
    throw InputError(m_path, InputError::Where::Byte, m_out, what);
}

void GzipReader::failTruncated() const {
    throw TruncatedInput(m_path, InputError::Where::Byte, m_out, "compressed stream is truncated");
}

void GzipReader::openAt(std::uint64_t fileOffset) {
    if (fileOffset > std::uint64_t(std::numeric_limits<off_t>::max()) ||
        fseeko(m_file, static_cast<off_t>(fileOffset), SEEK_SET) != 0)
        fail("cannot seek in the compressed file");
    m_inOffset = fileOffset;
    zs(m_stream)->next_in = m_in.data();
    zs(m_stream)->avail_in = 0;
    m_fileEnd = false;
}

bool GzipReader::ensureInput(std::size_t bytes) {
    z_stream* s = zs(m_stream);
    if (s->avail_in >= bytes)
        return true;
    const std::size_t consumed = std::size_t(s->next_in - m_in.data());
    std::memmove(m_in.data(), s->next_in, s->avail_in);
    m_inOffset += consumed;
    s->next_in = m_in.data();
    while (s->avail_in < bytes && !m_fileEnd) {
        const std::size_t got =
            std::fread(m_in.data() + s->avail_in, 1, m_in.size() - s->avail_in, m_file);
        if (got == 0) {
            if (std::ferror(m_file))
                fail(std::string("cannot read the file: ") + std::strerror(errno));
            m_fileEnd = true;
        }
        s->avail_in += static_cast<uInt>(got);
    }
    return s->avail_in >= bytes;
}

void GzipReader::restart() {
    inflateReset2(zs(m_stream), 15 + 32);
    m_mode = Mode::Gzip;
    openAt(0);
    m_out = m_memberStart = m_nextPoint = 0;
    m_end = m_truncated = false;
}

void GzipReader::restore(const detail::GzipAccessPoint& point) {
    z_stream* s = zs(m_stream);
    inflateReset2(s, -15); // raw deflate: the member's header lies behind
    m_mode = Mode::Raw;
    m_out = point.out;
    m_end = m_truncated = false;
    openAt(point.in - (point.bits ? 1 : 0));
    if (point.bits) {
        if (!ensureInput(1))
            failTruncated();
        const int byte = *s->next_in;
        ++s->next_in;
        --s->avail_in;
        inflatePrime(s, point.bits, byte >> (8 - point.bits));
    }
    if (!point.window.empty())
        inflateSetDictionary(s, point.window.data(), static_cast<uInt>(point.window.size()));
    m_memberStart = point.out - point.window.size();
    m_out = m_memberStart;
    note(point.window.data(), point.window.size());
    m_out = point.out;
    m_nextPoint = point.out + 1;
}

bool GzipReader::endOfMember() {
    z_stream* s = zs(m_stream);
    if (m_mode == Mode::Raw) { // the member's trailer (CRC-32 and size), checked only in order
        if (!ensureInput(8))
            return false;
        s->next_in += 8;
        s->avail_in -= 8;
    }
    // Another member follows, or the stream ends (anything else after it is ignored).
    if (!ensureInput(2) || s->next_in[0] != 0x1f || s->next_in[1] != 0x8b) {
        m_end = true;
        return true;
    }
    inflateReset2(s, 15 + 32);
    m_mode = Mode::Gzip;
    m_memberStart = m_out;
    return true;
}

void GzipReader::note(const unsigned char* out, std::size_t produced) {
    std::size_t keep = std::min(produced, kWindow);
    const unsigned char* from = out + produced - keep;
    std::uint64_t at = m_out + produced - keep;
    while (keep > 0) {
        const std::size_t slot = std::size_t(at % kWindow);
        const std::size_t n = std::min(keep, kWindow - slot);
        std::memcpy(m_ring.data() + slot, from, n);
        from += n;
        at += n;
        keep -= n;
    }
}

void GzipReader::remember() {
    const z_stream* s = zs(m_stream);
    // At the end of a block that is not the member's last (or just after a member's header).
    if (m_out < m_nextPoint || !(s->data_type & 128) || (s->data_type & 64))
        return;
    const std::uint64_t wanted = m_index->wantedFrom(m_out);
    if (wanted > m_out) {
        m_nextPoint = wanted;
        return;
    }
    auto point = std::make_shared<detail::GzipAccessPoint>();
    point->out = m_out;
    point->in = m_inOffset + std::uint64_t(s->next_in - m_in.data());
    point->bits = s->data_type & 7;
    const std::size_t length = std::size_t(std::min<std::uint64_t>(kWindow, m_out - m_memberStart));
    point->window.resize(length);
    for (std::size_t k = 0; k < length; ++k)
        point->window[k] = m_ring[std::size_t((m_out - length + k) % kWindow)];
    m_index->add(std::move(point));
    m_nextPoint = m_out + 1;
}

std::size_t GzipReader::read(char* dst, std::size_t n) {
    z_stream* s = zs(m_stream);
    std::size_t total = 0;
    // The stream stops short: what came before it is returned first, the error on the next read
    // (a reader reading ahead still gets the whole frames before the cut).
    auto truncated = [&] {
        if (total == 0)
            failTruncated();
        m_truncated = true;
    };
    if (m_truncated)
        failTruncated();
    while (total < n && !m_end && !m_truncated) {
        if (s->avail_in == 0 && !ensureInput(1)) {
            truncated();
            break;
        }
        auto* out = reinterpret_cast<unsigned char*>(dst + total);
        s->next_out = out;
        s->avail_out = static_cast<uInt>(std::min<std::size_t>(n - total, 1u << 30));
        const uInt outBefore = s->avail_out, inBefore = s->avail_in;
        // Z_BLOCK: back at each block's end, where an access point may be remembered.
        const int status = inflate(s, Z_BLOCK);
        const std::size_t produced = outBefore - s->avail_out;
        note(out, produced);
        m_out += produced;
        total += produced;
        if (status == Z_STREAM_END) {
            if (!endOfMember())
                truncated();
        } else if (status == Z_OK) {
            remember();
        } else if (status == Z_BUF_ERROR && produced == 0 && inBefore == s->avail_in) {
            if (!ensureInput(std::size_t(s->avail_in) + 1)) // needs more than there is
                truncated();
        } else {
            fail(std::string("corrupt compressed data: ") + (s->msg ? s->msg : "?"));
        }
    }
    return total;
}

void GzipReader::skip(std::uint64_t bytes) {
    std::vector<char> scratch(std::size_t(std::min<std::uint64_t>(bytes, 1u << 18)));
    while (bytes > 0) {
        const std::size_t got =
            read(scratch.data(), std::size_t(std::min<std::uint64_t>(bytes, scratch.size())));
        if (got == 0)
            break;
        bytes -= got;
    }
}

void GzipReader::seek(std::uint64_t offset) {
    if (offset == m_out)
        return;
    const auto point = m_index->before(offset);
    if (offset < m_out || (point && point->out > m_out)) {
        if (point)
            restore(*point);
        else
            restart();
    }
    skip(offset - m_out);
}

} // namespace faultline::core
