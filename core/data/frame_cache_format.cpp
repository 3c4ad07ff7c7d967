#include "core/data/frame_cache_format.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <cstddef>
#include <cstring>
#include <limits>
#include <stdexcept>
#include <system_error>
#include <type_traits>
#include <utility>
#include <vector>

#include <tbb/parallel_for.h>

namespace faultline::core {

namespace detail {

namespace {
constexpr std::uint64_t kPrime1 = 0x9E3779B185EBCA87ULL;
constexpr std::uint64_t kPrime2 = 0xC2B2AE3D27D4EB4FULL;
constexpr std::uint64_t kPrime3 = 0x165667B19E3779F9ULL;

inline std::uint64_t rotl(std::uint64_t v, int r) { return (v << r) | (v >> (64 - r)); }
inline std::uint64_t mixLane(std::uint64_t acc, std::uint64_t word) {
    return rotl(acc + word * kPrime2, 31) * kPrime1;
}
inline std::uint64_t load64(const unsigned char* p) {
    std::uint64_t v;
    std::memcpy(&v, p, sizeof v);
    return v;
}
} // namespace

std::uint64_t checksum64(const void* data, std::size_t bytes, std::uint64_t seed) {
    const auto* p = static_cast<const unsigned char*>(data);
    std::uint64_t a = seed + kPrime1 + kPrime2, b = seed + kPrime2, c = seed, d = seed - kPrime1;
    std::size_t i = 0;
    for (; i + 32 <= bytes; i += 32) {
        a = mixLane(a, load64(p + i));
        b = mixLane(b, load64(p + i + 8));
        c = mixLane(c, load64(p + i + 16));
        d = mixLane(d, load64(p + i + 24));
    }
    std::uint64_t h = rotl(a, 1) + rotl(b, 7) + rotl(c, 12) + rotl(d, 18);
    h ^= static_cast<std::uint64_t>(bytes) * kPrime3;
    for (; i + 8 <= bytes; i += 8)
        h = rotl(h ^ mixLane(0, load64(p + i)), 27) * kPrime1 + kPrime3;
    for (; i < bytes; ++i)
        h = rotl(h ^ (p[i] * kPrime3), 11) * kPrime1;
    h ^= h >> 33;
    h *= kPrime2;
    h ^= h >> 29;
    h *= kPrime3;
    h ^= h >> 32;
    return h;
}

} // namespace detail

namespace {

constexpr char kMagic[8] = {'F', 'L', 'T', 'F', 'R', 'A', 'M', 0x1a};
constexpr std::uint32_t kByteOrderMark = 0x01020304;
constexpr std::uint64_t kAlign = 64;
constexpr std::uint32_t kMaxKeyBytes = 1u << 20;
constexpr std::uint32_t kMaxColumns = 1u << 16;
constexpr std::uint32_t kMaxNamesBytes = 1u << 24;
constexpr std::uint64_t kMetaSeed = 0x4d455441ULL;

// Fixed columns come first, in this order, then one entry per attribute.
enum ColumnKind : std::uint32_t { Ids, X, Y, Z, Radius, FloatAttribute, IntAttribute, KindCount };
constexpr std::uint32_t kFixedColumns = 5;

enum Flag : std::uint32_t {
    RadiusIsDefault = 1u << 0,
    IdsAreRowNumbers = 1u << 1,
    BoxTriclinic = 1u << 2,
    BoxKnown = 1u << 3,
    PeriodicX = 1u << 4, // and << 5, << 6 for y and z
    ColumnsAssumed = 1u << 7,
    KnownFlags = (1u << 7) - 1,
};

struct FileHeader {
    char magic[8];
    std::uint32_t version;
    std::uint32_t byteOrder;
    std::uint64_t fileBytes;
    std::uint64_t particleCount;
    std::int64_t timestep;
    std::uint32_t columnCount;
    std::uint32_t flags;
    std::uint32_t keyBytes;
    std::uint32_t namesBytes;
    double box[9];                // lo xyz, hi xyz, xy xz yz
    std::uint64_t metaChecksum;   // of key, column table and names
    std::uint64_t headerChecksum; // of every byte before this field
};
static_assert(std::is_trivially_copyable_v<FileHeader> && sizeof(FileHeader) == 144);

struct ColumnEntry {
    std::uint32_t kind;
    std::uint32_t nameBytes;
    std::uint64_t offset;
    std::uint64_t bytes;
    std::uint64_t checksum;
};
static_assert(std::is_trivially_copyable_v<ColumnEntry> && sizeof(ColumnEntry) == 32);

constexpr std::uint64_t alignUp(std::uint64_t v) { return (v + kAlign - 1) / kAlign * kAlign; }

std::uint64_t headerChecksum(const FileHeader& h) {
    return detail::checksum64(&h, offsetof(FileHeader, headerChecksum), 0x4845414445520001ULL);
}

std::size_t elementBytes(std::uint32_t kind) { return kind == Ids ? 8 : 4; }

// pread until n bytes or the end; false on a short read or an error.
bool readExactly(int fd, void* dst, std::size_t n, std::uint64_t offset) {
    auto* p = static_cast<char*>(dst);
    while (n > 0) {
        const ssize_t got = ::pread(fd, p, n, static_cast<off_t>(offset));
        if (got < 0 && errno == EINTR)
            continue;
        if (got <= 0)
            return false;
        p += got;
        n -= static_cast<std::size_t>(got);
        offset += static_cast<std::uint64_t>(got);
    }
    return true;
}

void writeExactly(int fd, const void* src, std::size_t n, const std::string& path) {
    const auto* p = static_cast<const char*>(src);
    while (n > 0) {
        const ssize_t put = ::write(fd, p, n);
        if (put < 0 && errno == EINTR)
            continue;
        if (put < 0)
            throw std::system_error(errno, std::generic_category(), "cannot write " + path);
        p += put;
        n -= static_cast<std::size_t>(put);
    }
}

class FileDescriptor {
  public:
    explicit FileDescriptor(int fd) : m_fd(fd) {}
    ~FileDescriptor() {
        if (m_fd >= 0)
            ::close(m_fd);
    }
    FileDescriptor(const FileDescriptor&) = delete;
    FileDescriptor& operator=(const FileDescriptor&) = delete;
    FileDescriptor& operator=(FileDescriptor&& other) noexcept {
        if (this != &other) {
            if (m_fd >= 0)
                ::close(m_fd);
            m_fd = std::exchange(other.m_fd, -1);
        }
        return *this;
    }
    int get() const { return m_fd; }
    int release() { return std::exchange(m_fd, -1); }

  private:
    int m_fd;
};

CachedFrameRead reject(CachedFrameStatus status, std::string detail) {
    CachedFrameRead r;
    r.status = status;
    r.detail = std::move(detail);
    return r;
}

// Where a column's values live in the frame being filled.
void* columnStorage(Frame& f, std::uint32_t column, std::size_t n) {
    switch (column) {
    case Ids:
        f.ids.resize(n);
        return f.ids.data();
    case X:
        f.x.resize(n);
        return f.x.data();
    case Y:
        f.y.resize(n);
        return f.y.data();
    case Z:
        f.z.resize(n);
        return f.z.data();
    case Radius:
        f.radius.resize(n);
        return f.radius.data();
    default: {
        AttributeColumn& c = f.attributes[column - kFixedColumns];
        if (c.type == ColumnType::Float32) {
            c.floats.resize(n);
            return c.floats.data();
        }
        c.ints.resize(n);
        return c.ints.data();
    }
    }
}

const void* columnData(const Frame& f, std::uint32_t column) {
    switch (column) {
    case Ids:
        return f.ids.data();
    case X:
        return f.x.data();
    case Y:
        return f.y.data();
    case Z:
        return f.z.data();
    case Radius:
        return f.radius.data();
    default: {
        const AttributeColumn& c = f.attributes[column - kFixedColumns];
        return c.type == ColumnType::Float32 ? static_cast<const void*>(c.floats.data())
                                             : static_cast<const void*>(c.ints.data());
    }
    }
}

// Opens a cache file and checks its header, metadata and key (not the columns): Ok with `fd`,
// `h`, `meta` and `fileBytes` set, or why the file is not used.
CachedFrameRead openChecked(const std::string& path, std::string_view expectedKey,
                            FileDescriptor& fdOut, FileHeader& h, std::vector<char>& meta,
                            std::uint64_t& fileBytes) {
    FileDescriptor fd(::open(path.c_str(), O_RDONLY | O_CLOEXEC));
    if (fd.get() < 0)
        return reject(CachedFrameStatus::Missing, std::strerror(errno));
    struct stat st {};
    if (::fstat(fd.get(), &st) != 0 || !S_ISREG(st.st_mode))
        return reject(CachedFrameStatus::Corrupt, "not a regular file");
    fileBytes = static_cast<std::uint64_t>(st.st_size);

    if (fileBytes < sizeof h || !readExactly(fd.get(), &h, sizeof h, 0))
        return reject(CachedFrameStatus::Corrupt, "shorter than a header");
    if (std::memcmp(h.magic, kMagic, sizeof kMagic) != 0)
        return reject(CachedFrameStatus::Corrupt, "wrong magic");
    if (h.byteOrder != kByteOrderMark)
        return reject(CachedFrameStatus::Corrupt, "written on a machine of another byte order");
    if (h.headerChecksum != headerChecksum(h))
        return reject(CachedFrameStatus::Corrupt, "header checksum mismatch");
    if (h.version != kFrameCacheFormatVersion)
        return reject(CachedFrameStatus::Stale, "format version " + std::to_string(h.version));
    if (h.fileBytes != fileBytes)
        return reject(CachedFrameStatus::Corrupt, "file is " + std::to_string(fileBytes) +
                                                      " bytes, header says " +
                                                      std::to_string(h.fileBytes));
    if (h.keyBytes > kMaxKeyBytes || h.columnCount < kFixedColumns || h.columnCount > kMaxColumns ||
        h.namesBytes > kMaxNamesBytes || (h.flags & ~static_cast<std::uint32_t>(KnownFlags)) != 0)
        return reject(CachedFrameStatus::Corrupt, "header fields out of range");
    const std::uint64_t metaBytes = std::uint64_t(h.keyBytes) +
                                    std::uint64_t(h.columnCount) * sizeof(ColumnEntry) +
                                    h.namesBytes;
    if (sizeof h + metaBytes > fileBytes)
        return reject(CachedFrameStatus::Corrupt, "metadata runs past the end of the file");
    meta.assign(metaBytes, 0);
    if (!readExactly(fd.get(), meta.data(), meta.size(), sizeof h))
        return reject(CachedFrameStatus::Corrupt, "metadata unreadable");
    if (detail::checksum64(meta.data(), meta.size(), kMetaSeed) != h.metaChecksum)
        return reject(CachedFrameStatus::Corrupt, "metadata checksum mismatch");
    if (std::string_view(meta.data(), h.keyBytes) != expectedKey)
        return reject(CachedFrameStatus::Stale, "written for another source state");
    fdOut = std::move(fd);
    CachedFrameRead ok;
    ok.status = CachedFrameStatus::Ok;
    return ok;
}

} // namespace

CachedFrameStatus peekCachedFrame(const std::string& path, std::string_view expectedKey,
                                  std::string* detail) {
    FileDescriptor fd(-1);
    FileHeader h{};
    std::vector<char> meta;
    std::uint64_t fileBytes = 0;
    CachedFrameRead r = openChecked(path, expectedKey, fd, h, meta, fileBytes);
    if (detail)
        *detail = std::move(r.detail);
    return r.status;
}

CachedFrameRead readCachedFrame(const std::string& path, std::string_view expectedKey) {
    FileDescriptor fd(-1);
    FileHeader h{};
    std::vector<char> meta;
    std::uint64_t fileBytes = 0;
    if (CachedFrameRead r = openChecked(path, expectedKey, fd, h, meta, fileBytes);
        r.status != CachedFrameStatus::Ok)
        return r;
    const std::uint64_t metaBytes = meta.size();

    std::vector<ColumnEntry> entries(h.columnCount);
    std::memcpy(entries.data(), meta.data() + h.keyBytes, entries.size() * sizeof(ColumnEntry));
    const char* names = meta.data() + h.keyBytes + entries.size() * sizeof(ColumnEntry);

    // Every column: the kind its position allows, the size the particle count implies, inside
    // the file after the metadata. The particle count itself is bounded by the file size.
    const std::uint64_t n = h.particleCount;
    if (n > fileBytes / 4)
        return reject(CachedFrameStatus::Corrupt, "particle count larger than the file allows");
    Frame f;
    f.timestep = h.timestep;
    f.radiusIsDefault = (h.flags & RadiusIsDefault) != 0;
    f.idsAreRowNumbers = (h.flags & IdsAreRowNumbers) != 0;
    f.columnsAssumed = (h.flags & ColumnsAssumed) != 0;
    f.box.triclinic = (h.flags & BoxTriclinic) != 0;
    f.box.known = (h.flags & BoxKnown) != 0;
    for (int a = 0; a < 3; ++a) {
        f.box.periodic[a] = (h.flags & (PeriodicX << a)) != 0;
        f.box.lo[a] = h.box[a];
        f.box.hi[a] = h.box[3 + a];
    }
    f.box.xy = h.box[6];
    f.box.xz = h.box[7];
    f.box.yz = h.box[8];
    // Columns in file order without overlap: together no larger than the file.
    std::uint64_t dataEnd = alignUp(sizeof h + metaBytes);
    std::uint64_t namesUsed = 0;
    for (std::uint32_t k = 0; k < h.columnCount; ++k) {
        const ColumnEntry& e = entries[k];
        const bool kindOk =
            k < kFixedColumns ? e.kind == k : (e.kind == FloatAttribute || e.kind == IntAttribute);
        if (!kindOk || (k < kFixedColumns && e.nameBytes != 0))
            return reject(CachedFrameStatus::Corrupt,
                          "column " + std::to_string(k) + " of bad kind");
        if (e.bytes != n * elementBytes(e.kind) || e.offset % kAlign != 0 || e.offset < dataEnd ||
            e.offset > fileBytes || e.bytes > fileBytes - e.offset)
            return reject(CachedFrameStatus::Corrupt,
                          "column " + std::to_string(k) + " overlaps another or the file's end");
        dataEnd = e.offset + e.bytes;
        if (e.nameBytes > h.namesBytes - namesUsed)
            return reject(CachedFrameStatus::Corrupt, "column names overrun");
        if (k >= kFixedColumns) {
            AttributeColumn c;
            c.name.assign(names + namesUsed, e.nameBytes);
            c.type = e.kind == IntAttribute ? ColumnType::Int32 : ColumnType::Float32;
            f.attributes.push_back(std::move(c));
        }
        namesUsed += e.nameBytes;
    }
    if (namesUsed != h.namesBytes)
        return reject(CachedFrameStatus::Corrupt, "column names do not add up");

    // Columns straight into the frame's vectors, several at once, each against its checksum.
    std::vector<void*> storage(h.columnCount);
    for (std::uint32_t k = 0; k < h.columnCount; ++k)
        storage[k] = columnStorage(f, k, static_cast<std::size_t>(n));
    std::atomic<int> badColumn{-1};
    tbb::parallel_for(std::uint32_t(0), h.columnCount, [&](std::uint32_t k) {
        const ColumnEntry& e = entries[k];
        const auto bytes = static_cast<std::size_t>(e.bytes);
        if (!readExactly(fd.get(), storage[k], bytes, e.offset) ||
            detail::checksum64(storage[k], bytes, k) != e.checksum)
            badColumn.store(static_cast<int>(k));
    });
    if (badColumn.load() >= 0)
        return reject(CachedFrameStatus::Corrupt,
                      "column " + std::to_string(badColumn.load()) + " checksum mismatch");
    try {
        f.finalize();
    } catch (const std::exception& e) {
        return reject(CachedFrameStatus::Corrupt, e.what());
    }
    CachedFrameRead r;
    r.status = CachedFrameStatus::Ok;
    r.frame.emplace(std::move(f));
    return r;
}

std::uint64_t writeCachedFrame(const std::string& path, std::string_view key, const Frame& frame) {
    if (key.size() > kMaxKeyBytes || frame.attributes.size() + kFixedColumns > kMaxColumns)
        throw std::invalid_argument("frame too unusual to cache: " + path);
    const std::size_t n = frame.size();
    const auto columnCount = static_cast<std::uint32_t>(kFixedColumns + frame.attributes.size());

    std::vector<ColumnEntry> entries(columnCount);
    std::string names;
    for (std::uint32_t k = 0; k < columnCount; ++k) {
        ColumnEntry& e = entries[k];
        e.kind = k;
        e.nameBytes = 0;
        if (k >= kFixedColumns) {
            const AttributeColumn& c = frame.attributes[k - kFixedColumns];
            e.kind = c.type == ColumnType::Int32 ? IntAttribute : FloatAttribute;
            e.nameBytes = static_cast<std::uint32_t>(c.name.size());
            names += c.name;
        }
        e.bytes = n * elementBytes(e.kind);
    }
    if (names.size() > kMaxNamesBytes)
        throw std::invalid_argument("column names too long to cache: " + path);

    FileHeader h{};
    std::memcpy(h.magic, kMagic, sizeof kMagic);
    h.version = kFrameCacheFormatVersion;
    h.byteOrder = kByteOrderMark;
    h.particleCount = n;
    h.timestep = frame.timestep;
    h.columnCount = columnCount;
    h.keyBytes = static_cast<std::uint32_t>(key.size());
    h.namesBytes = static_cast<std::uint32_t>(names.size());
    h.flags = (frame.radiusIsDefault ? RadiusIsDefault : 0u) |
              (frame.idsAreRowNumbers ? IdsAreRowNumbers : 0u) |
              (frame.columnsAssumed ? ColumnsAssumed : 0u) |
              (frame.box.triclinic ? BoxTriclinic : 0u) | (frame.box.known ? BoxKnown : 0u);
    for (int a = 0; a < 3; ++a) {
        if (frame.box.periodic[a])
            h.flags |= PeriodicX << a;
        h.box[a] = frame.box.lo[a];
        h.box[3 + a] = frame.box.hi[a];
    }
    h.box[6] = frame.box.xy;
    h.box[7] = frame.box.xz;
    h.box[8] = frame.box.yz;

    const std::uint64_t metaBytes =
        key.size() + entries.size() * sizeof(ColumnEntry) + names.size();
    std::uint64_t offset = alignUp(sizeof h + metaBytes);
    for (auto& e : entries) {
        e.offset = offset;
        offset = alignUp(offset + e.bytes);
    }
    h.fileBytes = entries.back().offset + entries.back().bytes;
    tbb::parallel_for(std::uint32_t(0), columnCount, [&](std::uint32_t k) {
        entries[k].checksum = detail::checksum64(columnData(frame, k), entries[k].bytes, k);
    });

    std::string meta;
    meta.reserve(metaBytes);
    meta.append(key);
    meta.append(reinterpret_cast<const char*>(entries.data()),
                entries.size() * sizeof(ColumnEntry));
    meta.append(names);
    h.metaChecksum = detail::checksum64(meta.data(), meta.size(), kMetaSeed);
    h.headerChecksum = headerChecksum(h);

    std::string tmp = path + ".tmpXXXXXX";
    FileDescriptor fd(::mkstemp(tmp.data()));
    if (fd.get() < 0)
        throw std::system_error(errno, std::generic_category(), "cannot create " + tmp);
    try {
        static const char kZeros[kAlign] = {};
        std::string head(reinterpret_cast<const char*>(&h), sizeof h);
        head += meta;
        head.resize(static_cast<std::size_t>(entries.front().offset), '\0');
        writeExactly(fd.get(), head.data(), head.size(), tmp);
        std::uint64_t at = head.size();
        for (std::uint32_t k = 0; k < columnCount; ++k) {
            writeExactly(fd.get(), kZeros, static_cast<std::size_t>(entries[k].offset - at), tmp);
            writeExactly(fd.get(), columnData(frame, k), static_cast<std::size_t>(entries[k].bytes),
                         tmp);
            at = entries[k].offset + entries[k].bytes;
        }
        ::fchmod(fd.get(), 0644);
        if (::close(fd.release()) != 0)
            throw std::system_error(errno, std::generic_category(), "cannot close " + tmp);
        if (::rename(tmp.c_str(), path.c_str()) != 0)
            throw std::system_error(errno, std::generic_category(), "cannot rename to " + path);
    } catch (...) {
        ::unlink(tmp.c_str());
        throw;
    }
    return h.fileBytes;
}

} // namespace faultline::core
