#include "core/data/frame_cache.hpp"

#include "core/data/frame_cache_format.hpp"
#include "core/util/ascii.hpp"

#include <fcntl.h>
#include <pwd.h>
#include <sys/stat.h>
#include <sys/statvfs.h>
#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <system_error>
#include <vector>

namespace faultline::core {

namespace fs = std::filesystem;
using detail::SourceState;

namespace {

constexpr std::string_view kExtension = ".flframe";

std::optional<SourceState> sourceState(const FrameLocation& location) {
    SourceState s;
    const std::string head = "faultline frame cache v" + std::to_string(kFrameCacheFormatVersion) +
                             "\nformat " + std::to_string(static_cast<int>(location.format)) +
                             " timestep " + std::to_string(location.timestep) + "\n";
    s.identity = head;
    s.key = head;
    // The pieces, then a LIGGGHTS bounding box read with them (a changed box is a changed frame).
    std::vector<FramePiece> sources = location.pieces;
    if (!location.boxPath.empty())
        sources.push_back({location.boxPath, 0, 0, 0});
    for (const auto& piece : sources) {
        std::error_code ec;
        const fs::path absolute = fs::absolute(piece.path, ec).lexically_normal();
        if (ec)
            return std::nullopt;
        struct stat st {};
        if (::stat(absolute.c_str(), &st) != 0 || !S_ISREG(st.st_mode))
            return std::nullopt;
        const std::string where = absolute.string() + "\t" + std::to_string(piece.offset) + "\t" +
                                  std::to_string(piece.length) + "\t" +
                                  std::to_string(piece.firstLine);
        const long long mtimeNs =
            static_cast<long long>(st.st_mtim.tv_sec) * 1000000000LL + st.st_mtim.tv_nsec;
        s.identity += where + "\n";
        s.key += where + "\tsize " + std::to_string(st.st_size) + "\tmtime " +
                 std::to_string(mtimeNs) + "\tinode " + std::to_string(st.st_dev) + ":" +
                 std::to_string(st.st_ino) + "\n";
        s.sourceBytes += piece.length ? piece.length : static_cast<std::uint64_t>(st.st_size);
    }
    return s;
}

std::string fileNameFor(const std::string& identity) {
    const std::uint64_t h = detail::checksum64(identity.data(), identity.size(), 0x464c43ULL);
    char name[32];
    std::snprintf(name, sizeof name, "%016llx", static_cast<unsigned long long>(h));
    return std::string(name) + std::string(kExtension);
}

bool isOurFile(const fs::directory_entry& e) {
    const std::string name = e.path().filename().string();
    return name.size() > kExtension.size() &&
           (name.ends_with(kExtension) ||
            name.find(std::string(kExtension) + ".tmp") != std::string::npos);
}

bool envSaysOff(const char* value) {
    if (!value)
        return false;
    const std::string v = asciiLower(value);
    return v == "0" || v == "off" || v == "no" || v == "false";
}

std::mutex& defaultMutex() {
    static std::mutex m;
    return m;
}
std::shared_ptr<FrameCache>& defaultSlot() {
    static std::shared_ptr<FrameCache> slot;
    return slot;
}
bool& defaultChosen() {
    static bool chosen = false;
    return chosen;
}

} // namespace

std::string defaultFrameCacheFolder() {
    if (const char* xdg = std::getenv("XDG_CACHE_HOME"); xdg && xdg[0] == '/')
        return (fs::path(xdg) / "faultline" / "frames").string();
    std::string home;
    if (const char* h = std::getenv("HOME"); h && h[0] == '/')
        home = h;
    else if (const passwd* pw = ::getpwuid(::getuid()); pw && pw->pw_dir && pw->pw_dir[0] == '/')
        home = pw->pw_dir;
    if (home.empty())
        return {};
    return (fs::path(home) / ".cache" / "faultline" / "frames").string();
}

std::optional<std::string> frameCacheKey(const FrameLocation& location) {
    auto s = sourceState(location);
    if (!s)
        return std::nullopt;
    return std::move(s->key);
}

FrameCache::FrameCache(FrameCacheSettings settings) : m_settings(std::move(settings)) {
    if (m_settings.folder.empty())
        m_settings.folder = defaultFrameCacheFolder();
}

std::shared_ptr<FrameCache> FrameCache::processDefault() {
    std::lock_guard lock(defaultMutex());
    if (!defaultChosen()) {
        defaultChosen() = true;
        FrameCacheSettings settings;
        settings.enabled = !envSaysOff(std::getenv("FAULTLINE_FRAME_CACHE"));
        defaultSlot() = std::make_shared<FrameCache>(settings);
    }
    return defaultSlot();
}

void FrameCache::setProcessDefault(std::shared_ptr<FrameCache> cache) {
    std::lock_guard lock(defaultMutex());
    defaultChosen() = true;
    defaultSlot() = std::move(cache);
}

std::string FrameCache::pathFor(const FrameLocation& location) const {
    if (!enabled())
        return {};
    auto s = sourceState(location);
    if (!s)
        return {};
    return (fs::path(m_settings.folder) / fileNameFor(s->identity)).string();
}

Frame FrameCache::fetch(const FrameLocation& location) {
    const auto before = enabled() ? sourceState(location) : std::nullopt;
    if (!before || before->sourceBytes < m_settings.minSourceBytes)
        return loadFrame(location);
    if (auto hit = lookup(location))
        return std::move(*hit);
    Frame frame = loadFrame(location);
    // Only when the sources did not change while they were parsed.
    const auto after = sourceState(location);
    if (after && after->key == before->key)
        store(location, frame);
    return frame;
}

namespace {

// The state of a frame derived from `location` and `others` under `variant`.
std::optional<SourceState> derivedState(const FrameLocation& location,
                                        const std::vector<FrameLocation>& others,
                                        const std::string& variant) {
    auto s = sourceState(location);
    if (!s)
        return std::nullopt;
    s->identity += "derived " + variant + "\n";
    s->key += "derived " + variant + "\n";
    for (const auto& other : others) {
        const auto o = sourceState(other);
        if (!o)
            return std::nullopt;
        s->identity += "from " + o->identity;
        s->key += "from " + o->key;
    }
    return s;
}

} // namespace

std::optional<Frame> FrameCache::lookup(const FrameLocation& location) {
    if (!enabled())
        return std::nullopt;
    return lookupState(sourceState(location));
}

std::optional<Frame> FrameCache::lookupDerived(const FrameLocation& location,
                                               const std::vector<FrameLocation>& others,
                                               const std::string& variant) {
    if (!enabled())
        return std::nullopt;
    return lookupState(derivedState(location, others, variant));
}

bool FrameCache::holdsDerived(const FrameLocation& location,
                              const std::vector<FrameLocation>& others,
                              const std::string& variant) {
    if (!enabled())
        return false;
    const auto s = derivedState(location, others, variant);
    if (!s)
        return false;
    const std::string path = (fs::path(m_settings.folder) / fileNameFor(s->identity)).string();
    std::string detail;
    const CachedFrameStatus status = peekCachedFrame(path, s->key, &detail);
    if (status == CachedFrameStatus::Ok) {
        ::utimensat(AT_FDCWD, path.c_str(), nullptr, 0); // most recently used: evicted last
        return true;
    }
    if (status == CachedFrameStatus::Corrupt)
        dropCorrupt(path, detail);
    return false;
}

bool FrameCache::keeps(const FrameLocation& location) const {
    return enabled() && keepsState(sourceState(location));
}

bool FrameCache::keepsState(const std::optional<SourceState>& s) const {
    return !writesRefused() && s && s->sourceBytes >= m_settings.minSourceBytes;
}

bool FrameCache::writesRefused() const {
    std::lock_guard lock(m_mutex);
    return m_writesDisabled;
}

bool FrameCache::storeDerived(const FrameLocation& location,
                              const std::vector<FrameLocation>& others, const std::string& variant,
                              const Frame& frame) {
    return enabled() && storeState(derivedState(location, others, variant), frame);
}

std::optional<Frame> FrameCache::lookupState(const std::optional<SourceState>& s) {
    if (!s)
        return std::nullopt;
    const std::string path = (fs::path(m_settings.folder) / fileNameFor(s->identity)).string();
    CachedFrameRead read = readCachedFrame(path, s->key);
    if (read.status == CachedFrameStatus::Ok) {
        ::utimensat(AT_FDCWD, path.c_str(), nullptr, 0); // most recently used: evicted last
        std::lock_guard lock(m_mutex);
        ++m_stats.hits;
        return std::move(read.frame);
    }
    if (read.status == CachedFrameStatus::Corrupt) {
        dropCorrupt(path, read.detail);
        return std::nullopt;
    }
    std::lock_guard lock(m_mutex);
    ++m_stats.misses;
    return std::nullopt;
}

bool FrameCache::store(const FrameLocation& location, const Frame& frame) {
    return enabled() && storeState(sourceState(location), frame);
}

bool FrameCache::storeState(const std::optional<SourceState>& s, const Frame& frame) {
    if (!keepsState(s))
        return false;
    std::error_code ec;
    fs::create_directories(m_settings.folder, ec);
    if (ec) {
        noteProblem("cannot create " + m_settings.folder + ": " + ec.message(), true);
        return false;
    }
    struct statvfs vfs {};
    if (::statvfs(m_settings.folder.c_str(), &vfs) == 0) {
        const std::uint64_t freeBytes = std::uint64_t(vfs.f_bavail) * vfs.f_frsize;
        if (freeBytes < m_settings.minFreeDiskBytes + frame.memoryBytes()) {
            noteProblem("less than " + std::to_string(m_settings.minFreeDiskBytes >> 20) +
                            " MiB free in " + m_settings.folder + "; not caching frames",
                        false);
            return false;
        }
    }
    const std::string path = (fs::path(m_settings.folder) / fileNameFor(s->identity)).string();
    std::uint64_t written = 0;
    try {
        written = writeCachedFrame(path, s->key, frame);
    } catch (const std::system_error& e) {
        const int err = e.code().value();
        const bool forGood = err == EROFS || err == EACCES || err == EPERM || err == ENOSPC ||
                             err == EDQUOT || err == ENOTDIR;
        noteProblem(e.what(), forGood);
        std::lock_guard lock(m_mutex);
        ++m_stats.writeFailures;
        return false;
    } catch (const std::exception& e) {
        noteProblem(e.what(), false);
        std::lock_guard lock(m_mutex);
        ++m_stats.writeFailures;
        return false;
    }
    bool scan = false;
    {
        std::lock_guard lock(m_mutex);
        ++m_stats.writes;
        if (!m_folderBytes)
            scan = true;
        else
            scan = (*m_folderBytes += written) > m_settings.budgetBytes;
    }
    if (scan)
        evictOverBudget(path);
    return true;
}

void FrameCache::evictOverBudget(const std::string& keep) {
    struct Entry {
        fs::path path;
        std::uint64_t bytes;
        fs::file_time_type time;
    };
    std::vector<Entry> files;
    std::uint64_t total = 0;
    std::error_code ec;
    const auto now = fs::file_time_type::clock::now();
    for (fs::directory_iterator it(m_settings.folder, ec), end; !ec && it != end;
         it.increment(ec)) {
        if (!isOurFile(*it) || !it->is_regular_file(ec))
            continue;
        Entry e{it->path(), it->file_size(ec), it->last_write_time(ec)};
        if (ec)
            continue;
        const bool leftover = e.path.filename().string().find(".tmp") != std::string::npos;
        if (leftover) { // a temporary file a crashed writer left behind
            if (now - e.time > std::chrono::hours(1))
                fs::remove(e.path, ec);
            continue;
        }
        total += e.bytes;
        files.push_back(std::move(e));
    }
    if (total > m_settings.budgetBytes) {
        std::sort(files.begin(), files.end(),
                  [](const Entry& a, const Entry& b) { return a.time < b.time; });
        const std::uint64_t target = m_settings.budgetBytes / 10 * 9;
        for (const auto& e : files) {
            if (total <= target)
                break;
            if (e.path.string() == keep)
                continue;
            if (fs::remove(e.path, ec))
                total -= e.bytes;
        }
    }
    std::lock_guard lock(m_mutex);
    m_folderBytes = total;
}

void FrameCache::clear() {
    std::error_code ec;
    for (fs::directory_iterator it(m_settings.folder, ec), end; !ec && it != end; it.increment(ec))
        if (isOurFile(*it))
            fs::remove(it->path(), ec);
    std::lock_guard lock(m_mutex);
    m_folderBytes = 0;
}

std::string FrameCache::problem() const {
    std::lock_guard lock(m_mutex);
    return m_problem;
}

FrameCache::Stats FrameCache::stats() const {
    std::lock_guard lock(m_mutex);
    return m_stats;
}

void FrameCache::dropCorrupt(const std::string& path, const std::string& detail) {
    ::unlink(path.c_str());
    noteProblem("ignored a corrupt cache file " + path + " (" + detail + ")", false);
    std::lock_guard lock(m_mutex);
    ++m_stats.rejected;
}

void FrameCache::noteProblem(const std::string& message, bool disableWrites) {
    std::lock_guard lock(m_mutex);
    m_problem = message;
    if (disableWrites)
        m_writesDisabled = true;
    if (!m_warned) {
        m_warned = true;
        std::fprintf(stderr, "faultline: frame cache: %s (frames still load from their files)\n",
                     message.c_str());
    }
}

} // namespace faultline::core
