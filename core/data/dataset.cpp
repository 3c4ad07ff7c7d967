// Dataset: the frames of a run indexed from its files, loaded lazily through a bounded cache in
// memory, with the variables derived from motion, and kept in the disk frame cache.
//
// Index of this file:
// [SECTION] Opening: globs, per-processor pieces, the frame index
// [SECTION] Frames in memory
// [SECTION] Derived frames
// [SECTION] Derived frames in the background
// [SECTION] Memory budget and disk cache

#include "core/data/dataset.hpp"

#include "core/data/frame_cache.hpp"
#include "core/io/input_error.hpp"
#include "core/motion/strain_from_motion.hpp"

#include <glob.h>
#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <cstdio>
#include <filesystem>
#include <map>
#include <regex>

namespace faultline::core {

//-----------------------------------------------------------------------------
// [SECTION] Opening: globs, per-processor pieces, the frame index
//-----------------------------------------------------------------------------

std::size_t defaultFrameMemoryBudget() {
    const long pages = ::sysconf(_SC_PHYS_PAGES);
    const long pageSize = ::sysconf(_SC_PAGE_SIZE);
    if (pages <= 0 || pageSize <= 0)
        return std::size_t(2) << 30;
    return static_cast<std::size_t>(pages) / 4 * static_cast<std::size_t>(pageSize);
}

bool naturalLess(const std::string& a, const std::string& b) {
    std::size_t i = 0, j = 0;
    while (i < a.size() && j < b.size()) {
        const bool da = std::isdigit(static_cast<unsigned char>(a[i]));
        const bool db = std::isdigit(static_cast<unsigned char>(b[j]));
        if (da && db) {
            std::size_t ie = i, je = j;
            while (ie < a.size() && std::isdigit(static_cast<unsigned char>(a[ie])))
                ++ie;
            while (je < b.size() && std::isdigit(static_cast<unsigned char>(b[je])))
                ++je;
            std::size_t is = i, js = j; // skip leading zeros
            while (is + 1 < ie && a[is] == '0')
                ++is;
            while (js + 1 < je && b[js] == '0')
                ++js;
            if (ie - is != je - js)
                return ie - is < je - js;
            const int cmp = a.compare(is, ie - is, b, js, je - js);
            if (cmp != 0)
                return cmp < 0;
            i = ie;
            j = je;
        } else {
            if (a[i] != b[j])
                return a[i] < b[j];
            ++i;
            ++j;
        }
    }
    return a.size() - i < b.size() - j;
}

std::vector<std::string> expandGlob(const std::string& pattern) {
    if (pattern.find_first_of("*?[") == std::string::npos)
        return {pattern};
    glob_t g{};
    std::vector<std::string> out;
    if (glob(pattern.c_str(), GLOB_NOSORT, nullptr, &g) == 0)
        for (std::size_t k = 0; k < g.gl_pathc; ++k)
            out.emplace_back(g.gl_pathv[k]);
    globfree(&g);
    std::sort(out.begin(), out.end(), naturalLess);
    return out;
}

namespace {

// Per-processor LAMMPS files: 'dump.%.lammpstrj' -> pieces dump.0..., grouped by what any '*'
// matched (the timestep in 'dump.*.%').
std::vector<FrameLocation> indexPerProcessor(const std::string& pattern) {
    std::string globPattern = pattern;
    std::replace(globPattern.begin(), globPattern.end(), '%', '*');
    std::string re;
    for (char c : pattern) {
        if (c == '*')
            re += "(.*)";
        else if (c == '%')
            re += "([0-9]+)";
        else if (c == '?')
            re += ".";
        else if (std::string_view(".^$|()[]{}+\\").find(c) != std::string_view::npos)
            re += std::string("\\") + c;
        else
            re += c;
    }
    const std::regex matcher(re);
    const int procGroup = [&] {
        int group = 0;
        for (char c : pattern) {
            if (c == '*' || c == '%')
                ++group;
            if (c == '%')
                return group;
        }
        return 0;
    }();
    // key (the '*' parts) -> processor number -> file
    std::map<std::string, std::map<long, std::string>, decltype(&naturalLess)> groups(&naturalLess);
    for (const auto& file : expandGlob(globPattern)) {
        std::smatch m;
        if (!std::regex_match(file, m, matcher))
            continue;
        std::string key;
        for (std::size_t g = 1; g < m.size(); ++g)
            if (static_cast<int>(g) != procGroup)
                key += m[g].str() + "\x1f";
        groups[key][std::stol(m[procGroup].str())] = file;
    }
    if (groups.empty())
        throw InputError(pattern, "no per-processor files match ('%' stands for 0, 1, 2, ...)");
    std::vector<FrameLocation> frames;
    for (const auto& [key, pieces] : groups) {
        std::vector<std::vector<FrameLocation>> perPiece;
        for (const auto& [proc, file] : pieces)
            perPiece.push_back(indexDataFile(file));
        const std::size_t count = perPiece.front().size();
        for (std::size_t p = 1; p < perPiece.size(); ++p)
            if (perPiece[p].size() != count)
                throw InputError(std::next(pieces.begin(), static_cast<long>(p))->second,
                                 "holds " + std::to_string(perPiece[p].size()) +
                                     " frames, but processor 0's file holds " +
                                     std::to_string(count));
        for (std::size_t k = 0; k < count; ++k) {
            FrameLocation loc = perPiece[0][k];
            loc.particleCount = 0;
            for (std::size_t p = 0; p < perPiece.size(); ++p) {
                if (p > 0)
                    loc.pieces.push_back(perPiece[p][k].pieces.front());
                loc.particleCount += perPiece[p][k].particleCount;
            }
            frames.push_back(std::move(loc));
        }
    }
    return frames;
}

} // namespace

std::shared_ptr<Dataset> Dataset::open(const std::vector<std::string>& patterns,
                                       const OpenProgress& progress) {
    auto ds = std::make_shared<Dataset>();
    ds->m_patterns = patterns;
    ds->m_frameCache = FrameCache::processDefault();
    // Every pattern expanded first, so progress counts files.
    std::vector<std::vector<std::string>> expanded;
    // Per pattern: the bounding boxes it matched beside its frames, by folder and number.
    std::vector<std::map<std::pair<std::string, std::int64_t>, std::string>> boxes(patterns.size());
    std::size_t total = 0, done = 0;
    for (const auto& pattern : patterns) {
        if (pattern.find('%') != std::string::npos) {
            expanded.push_back({});
            ++total;
            continue;
        }
        expanded.push_back(expandGlob(pattern));
        if (expanded.back().empty())
            throw InputError(pattern, "no file matches this pattern");
        // LIGGGHTS' dump custom/vtk writes run_boundingBox_N.vtk beside each run_N.vtk: the
        // natural pattern run_*.vtk takes both. The boxes are no frames of spheres: each is
        // its frame's simulation box (the frame file holds none).
        if (expanded.back().size() > 1) {
            std::erase_if(expanded.back(), [&](const std::string& file) {
                if (!isVtkRectilinearGrid(file))
                    return false;
                if (const auto n = numberInFileName(file))
                    boxes[expanded.size() - 1]
                         [{std::filesystem::path(file).parent_path().string(), *n}] = file;
                return true;
            });
            if (expanded.back().empty())
                throw InputError(pattern, "every file this pattern matches is a RECTILINEAR_GRID "
                                          "(a bounding box), none holds spheres");
        }
        total += expanded.back().size();
    }
    auto step = [&] {
        ++done;
        if (progress && !progress(double(done) / double(std::max<std::size_t>(total, 1))))
            throw OpenCancelled();
    };
    for (std::size_t k = 0; k < patterns.size(); ++k) {
        if (patterns[k].find('%') != std::string::npos) {
            auto frames = indexPerProcessor(patterns[k]);
            ds->m_frames.insert(ds->m_frames.end(), frames.begin(), frames.end());
            step();
            continue;
        }
        for (const auto& file : expanded[k]) {
            std::string partial;
            auto frames = indexDataFile(file, &partial);
            if (!partial.empty())
                ds->m_notes.push_back(std::move(partial));
            if (!boxes[k].empty() && frames.size() == 1)
                if (const auto n = numberInFileName(file))
                    if (auto box =
                            boxes[k].find({std::filesystem::path(file).parent_path().string(), *n});
                        box != boxes[k].end())
                        frames.front().boxPath = box->second;
            ds->m_frames.insert(ds->m_frames.end(), frames.begin(), frames.end());
            step();
        }
    }
    if (ds->m_frames.empty())
        throw InputError(patterns.empty() ? std::string("(no path)") : patterns.front(),
                         "no frames found");
    return ds;
}

std::shared_ptr<Dataset> Dataset::fromLoader(std::size_t frameCount,
                                             std::function<Frame(std::size_t)> load) {
    auto ds = std::make_shared<Dataset>();
    ds->m_frames.resize(frameCount);
    for (std::size_t k = 0; k < frameCount; ++k) {
        ds->m_frames[k].timestep = static_cast<std::int64_t>(k);
        ds->m_frames[k].time = static_cast<double>(k);
    }
    ds->m_loader = std::move(load);
    return ds;
}

std::vector<std::string> Dataset::files() const {
    std::vector<std::string> out;
    for (const auto& f : m_frames)
        for (const auto& p : f.pieces)
            if (out.empty() || out.back() != p.path)
                if (std::find(out.begin(), out.end(), p.path) == out.end())
                    out.push_back(p.path);
    return out;
}

//-----------------------------------------------------------------------------
// [SECTION] Frames in memory
//-----------------------------------------------------------------------------

const Dataset::CacheEntry* Dataset::touchLocked(std::size_t index) const {
    const auto it = m_lruIndex.find(index);
    if (it == m_lruIndex.end())
        return nullptr;
    m_lru.splice(m_lru.begin(), m_lru, it->second);
    return &*it->second;
}

std::shared_ptr<const Frame> Dataset::cachedFrame(std::size_t index) const {
    std::lock_guard lock(m_mutex);
    const CacheEntry* e = touchLocked(index);
    return e && currentLocked(*e) ? e->frame : nullptr;
}

bool Dataset::isCached(std::size_t index) const {
    std::lock_guard lock(m_mutex);
    const auto it = m_lruIndex.find(index);
    return it != m_lruIndex.end() && currentLocked(*it->second);
}

void Dataset::setStrains(std::vector<StrainSpec> strains) {
    std::lock_guard lock(m_mutex);
    if (strains == m_strains)
        return;
    m_strains = std::move(strains);
    ++m_strainsVersion;
}

std::shared_ptr<const Frame> Dataset::readFrame(std::size_t index) const {
    return std::make_shared<const Frame>(readFrameValue(index));
}

Frame Dataset::readFrameValue(std::size_t index) const {
    std::shared_ptr<FrameCache> disk;
    {
        std::lock_guard lock(m_mutex);
        disk = m_frameCache;
    }
    if (m_loader)
        return m_loader(index);
    if (disk)
        return disk->fetch(m_frames[index]);
    return loadFrame(m_frames[index]);
}

std::shared_ptr<const Frame> Dataset::baseFrame(std::size_t index) const {
    {
        std::lock_guard lock(m_mutex);
        if (const CacheEntry* e = touchLocked(index))
            return e->frame;
    }
    auto read = readFrame(index);
    std::vector<std::shared_ptr<const Frame>> evicted; // freed after the lock
    std::lock_guard lock(m_mutex);
    if (const CacheEntry* e = touchLocked(index))
        return e->frame; // another thread was quicker
    insertLocked(index, read, kRead, evicted);
    return read;
}

void Dataset::insertLocked(std::size_t index, std::shared_ptr<const Frame> frame,
                           std::uint64_t derived,
                           std::vector<std::shared_ptr<const Frame>>& evicted) const {
    if (auto it = m_lruIndex.find(index); it != m_lruIndex.end()) {
        m_cachedBytes -= it->second->bytes;
        evicted.push_back(std::move(it->second->frame));
        m_lru.erase(it->second);
        m_lruIndex.erase(it);
    }
    const std::size_t bytes = frame->memoryBytes();
    m_lru.push_front({index, std::move(frame), bytes, derived});
    m_lruIndex[index] = m_lru.begin();
    m_cachedBytes += bytes;
    evictLocked(evicted);
}

//-----------------------------------------------------------------------------
// [SECTION] Derived frames
//-----------------------------------------------------------------------------
namespace {

// `base` (frame `index`, taken whole: a copy, or a frame read for this alone, moved) with its
// derived columns replaced by those of `strains` against their references.
std::shared_ptr<const Frame>
deriveFrame(Frame base, std::size_t index, std::size_t count,
            const std::vector<StrainSpec>& strains, std::uint64_t derivation,
            const std::function<std::shared_ptr<const Frame>(std::size_t)>& frameAt) {
    auto out = std::make_shared<Frame>(std::move(base));
    out->attributes.resize(out->attributes.size() - out->derivedColumns);
    out->derivedColumns = 0;
    for (const StrainSpec& spec : strains) {
        std::vector<AttributeColumn> cols;
        if (auto ref = spec.referenceFor(index, count)) {
            // Against itself: the frame's own positions (its new columns come after).
            const auto reference =
                *ref == index ? std::shared_ptr<const Frame>(out) : frameAt(*ref);
            cols = strainFromMotion(*out, *reference, spec.cutoff, spec.prefix);
        } else {
            cols = strainUnavailable(*out, spec.prefix);
        }
        for (auto& c : cols) {
            // A variable of the file's own with the same name keeps its place: the op refuses
            // such names, so this only happens when other data was opened under the spec.
            if (out->attribute(c.name))
                continue;
            out->attributes.push_back(std::move(c));
            ++out->derivedColumns;
        }
    }
    out->derivation = out->derivedColumns > 0 ? derivation : 0;
    return out;
}

// What a derived frame holds, for the disk cache's key: each spec and whether its reference
// exists (the references' own sources are keyed beside it).
std::string derivedVariant(const std::vector<StrainSpec>& strains, std::size_t index,
                           std::size_t count) {
    std::string v = "strain from motion v1";
    char cutoff[32];
    for (const auto& s : strains) {
        std::snprintf(cutoff, sizeof cutoff, "%.17g", s.cutoff);
        v += std::string(";") + (s.relative ? "offset " : "frame ") + std::to_string(s.reference) +
             " cutoff " + cutoff + " prefix " + s.prefix +
             (s.referenceFor(index, count) ? "" : " none");
    }
    return v;
}

// The sources of a frame's references under `strains`, which the disk cache keys a derived
// frame by beside its own.
std::vector<FrameLocation> referenceLocations(const std::vector<StrainSpec>& strains,
                                              std::size_t index,
                                              const std::vector<FrameLocation>& frames) {
    std::vector<FrameLocation> references;
    for (const auto& spec : strains)
        if (auto ref = spec.referenceFor(index, frames.size()))
            references.push_back(frames[*ref]);
    return references;
}

// Frame::derivation for a variant: never 0 (0 is "as read").
std::uint64_t derivationTag(const std::string& variant) {
    std::uint64_t h = 0xcbf29ce484222325ull;
    for (unsigned char c : variant)
        h = (h ^ c) * 0x100000001b3ull;
    return h | 1;
}

// How many of a frame's last columns the specs derive (they come last, in spec order).
std::size_t trailingDerivedColumns(const Frame& frame, const std::vector<StrainSpec>& strains) {
    std::vector<std::string> names;
    for (const auto& s : strains)
        for (auto v : kStrainVariables)
            names.push_back(s.variable(v));
    std::size_t n = 0;
    while (n < frame.attributes.size() &&
           std::find(names.begin(), names.end(),
                     frame.attributes[frame.attributes.size() - 1 - n].name) != names.end())
        ++n;
    return n;
}

} // namespace

std::shared_ptr<const Frame> Dataset::frame(std::size_t index) const { return frame(index, {}); }

std::shared_ptr<const Frame> Dataset::frame(std::size_t index,
                                            const std::function<void()>& ready) const {
    if (index >= m_frames.size())
        throw std::out_of_range("frame " + std::to_string(index) + " of " +
                                std::to_string(m_frames.size()));
    std::promise<std::shared_ptr<const Frame>> promise;
    std::shared_ptr<const Frame> base;
    std::vector<StrainSpec> strains;
    std::uint64_t version = 0;
    {
        std::unique_lock lock(m_mutex);
        if (const CacheEntry* hit = touchLocked(index)) {
            if (currentLocked(*hit)) {
                auto frame = hit->frame;
                lock.unlock();
                if (ready)
                    ready();
                return frame;
            }
            base = hit->frame; // derived for another list: derive again from its columns
        }
        version = m_strains.empty() ? kRead : m_strainsVersion;
        if (auto loading = m_loading.find(index);
            loading != m_loading.end() && loading->second.derived == version) {
            auto future = loading->second.future;
            lock.unlock();
            auto frame = future.get(); // rethrows the loader's error
            if (ready)
                ready();
            return frame;
        }
        m_loading[index] = {version, promise.get_future().share()};
        strains = m_strains;
    }
    std::shared_ptr<const Frame> loaded;
    std::shared_ptr<FrameCache> storeIn; // a frame derived now: written once the view has it
    std::vector<FrameLocation> references;
    std::string variant; // the disk cache's name for it; empty: not stored
    try {
        // A frame derived before (this run or an earlier one) comes from the disk cache whole.
        std::shared_ptr<FrameCache> disk = m_loader ? nullptr : frameCache();
        const std::string described =
            strains.empty() ? std::string() : derivedVariant(strains, index, m_frames.size());
        const std::uint64_t derivation = strains.empty() ? 0 : derivationTag(described);
        if (disk && disk->enabled() && !strains.empty()) {
            variant = described;
            references = referenceLocations(strains, index, m_frames);
            if (auto hit = disk->lookupDerived(m_frames[index], references, variant)) {
                auto frame = std::make_shared<Frame>(std::move(*hit));
                frame->derivedColumns = trailingDerivedColumns(*frame, strains);
                frame->derivation = frame->derivedColumns > 0 ? derivation : 0;
                loaded = std::move(frame);
            }
        }
        if (!loaded) {
            const auto frameAt = [this](std::size_t k) { return baseFrame(k); };
            if (!base && !strains.empty()) {
                // Read for this derivation alone: its columns are moved into the derived frame,
                // not copied (10 MB less written and held for a demo frame).
                loaded = deriveFrame(readFrameValue(index), index, m_frames.size(), strains,
                                     derivation, frameAt);
            } else {
                if (!base)
                    base = readFrame(index);
                loaded = strains.empty() && base->derivedColumns == 0
                             ? base
                             : deriveFrame(Frame(*base), index, m_frames.size(), strains,
                                           derivation, frameAt);
            }
            if (!variant.empty())
                storeIn = disk;
        }
    } catch (...) {
        std::lock_guard lock(m_mutex);
        if (auto it = m_loading.find(index); it != m_loading.end() && it->second.derived == version)
            m_loading.erase(it);
        promise.set_exception(std::current_exception());
        throw;
    }
    {
        std::vector<std::shared_ptr<const Frame>> evicted; // freed after the lock: frees are slow
        std::lock_guard lock(m_mutex);
        insertLocked(index, loaded, version, evicted);
        if (auto it = m_loading.find(index); it != m_loading.end() && it->second.derived == version)
            m_loading.erase(it);
        promise.set_value(loaded);
    }
    if (ready)
        ready();
    // Writing a derived frame (16 MB for a demo frame: 5-7 ms, more with loads writing at once)
    // need not keep the view waiting: after the frame is out. The frame is loaded whatever the
    // write does: a refused one is the cache's to note (FrameCache::problem), and an exception
    // (memory short) is no load error.
    if (storeIn) {
        try {
            storeIn->storeDerived(m_frames[index], references, variant, *loaded);
        } catch (...) {
        }
    }
    return loaded;
}

//-----------------------------------------------------------------------------
// [SECTION] Derived frames in the background
//-----------------------------------------------------------------------------

bool Dataset::storesDerived() const {
    std::shared_ptr<FrameCache> disk;
    {
        std::lock_guard lock(m_mutex);
        if (m_strains.empty())
            return false;
        disk = m_frameCache;
    }
    return !m_loader && disk && !m_frames.empty() && disk->keeps(m_frames.front());
}

std::uint64_t Dataset::strainsVersion() const {
    std::lock_guard lock(m_mutex);
    return m_strainsVersion;
}

bool Dataset::storeDerivedFrame(std::size_t index, BaseFrames& bases,
                                const std::atomic<bool>* cancel) const {
    if (index >= m_frames.size())
        throw std::out_of_range("frame " + std::to_string(index) + " of " +
                                std::to_string(m_frames.size()));
    std::vector<StrainSpec> strains;
    std::shared_ptr<FrameCache> disk;
    std::shared_ptr<const Frame> inMemory; // derived with the current strains
    std::uint64_t version = 0;
    {
        std::lock_guard lock(m_mutex);
        if (m_strains.empty() || m_loader || !m_frameCache)
            return false;
        strains = m_strains;
        disk = m_frameCache;
        version = m_strainsVersion;
        if (const auto it = m_lruIndex.find(index);
            it != m_lruIndex.end() && currentLocked(*it->second))
            inMemory = it->second->frame;
    }
    // Asked to stop, or the strains changed: this frame's work is for nothing.
    auto cancelled = [&] {
        return (cancel && cancel->load(std::memory_order_relaxed)) || strainsVersion() != version;
    };
    const std::size_t count = m_frames.size();
    auto fixedReference = [&](std::size_t k) {
        return std::any_of(strains.begin(), strains.end(), [&](const StrainSpec& s) {
            return !s.relative && static_cast<long long>(k) == s.reference;
        });
    };
    // What a pass in frame order reads again: frames ahead, and the references of frames ahead.
    auto trim = [&] {
        std::erase_if(bases, [&](const auto& entry) {
            const auto k = static_cast<long long>(entry.first);
            const auto at = static_cast<long long>(index), n = static_cast<long long>(count);
            if (k > at || fixedReference(entry.first))
                return false;
            for (const StrainSpec& s : strains)
                if (s.relative && k - s.reference > at && k - s.reference < n)
                    return false;
            return true;
        });
        // Within a quarter of the memory budget (a long offset of large frames): the highest
        // frames go, the last to be needed, to be read again (from the disk cache) then; a
        // since_frame reference, needed by every frame, stays.
        std::size_t bytes = 0;
        for (const auto& [k, f] : bases)
            bytes += f->memoryBytes();
        for (auto it = bases.end(); it != bases.begin() && bytes > m_budget.load() / 4;) {
            --it;
            if (fixedReference(it->first))
                continue;
            bytes -= it->second->memoryBytes();
            it = bases.erase(it);
        }
    };
    if (!disk->keeps(m_frames[index]) || cancelled()) {
        trim();
        return false;
    }
    // A frame as read: the pass's own, else one in memory (any version: the same positions),
    // else read (and kept by the pass, not in memory's cache, where it would push out the
    // frames the views look at).
    auto base = [&](std::size_t k) -> std::shared_ptr<const Frame> {
        if (auto it = bases.find(k); it != bases.end())
            return it->second;
        {
            std::lock_guard lock(m_mutex);
            if (auto it = m_lruIndex.find(k); it != m_lruIndex.end())
                return it->second->frame;
        }
        return bases[k] = readFrame(k);
    };
    const std::string variant = derivedVariant(strains, index, count);
    const std::vector<FrameLocation> references = referenceLocations(strains, index, m_frames);
    bool stored = disk->holdsDerived(m_frames[index], references, variant);
    // Derived for a view and not stored: the disk was short then, or the view's load is
    // writing it now (a second write of the same file is harmless: each goes to a file of its
    // own, renamed into place).
    if (!stored && inMemory)
        stored = disk->storeDerived(m_frames[index], references, variant, *inMemory);
    else if (!stored) {
        const auto own = base(index);
        if (!cancelled()) {
            const auto derived =
                deriveFrame(Frame(*own), index, count, strains, derivationTag(variant), base);
            stored =
                !cancelled() && disk->storeDerived(m_frames[index], references, variant, *derived);
        }
    }
    trim();
    return stored;
}

//-----------------------------------------------------------------------------
// [SECTION] Memory budget and disk cache
//-----------------------------------------------------------------------------

void Dataset::setCacheBudget(std::size_t bytes) {
    std::vector<std::shared_ptr<const Frame>> evicted;
    std::lock_guard lock(m_mutex);
    m_budget = bytes;
    evictLocked(evicted);
}

std::size_t Dataset::cachedBytes() const {
    std::lock_guard lock(m_mutex);
    return m_cachedBytes;
}

std::size_t Dataset::cachedFrameCount() const {
    std::lock_guard lock(m_mutex);
    return m_lru.size();
}

void Dataset::setFrameCache(std::shared_ptr<FrameCache> cache) {
    std::lock_guard lock(m_mutex);
    m_frameCache = std::move(cache);
}

std::shared_ptr<FrameCache> Dataset::frameCache() const {
    std::lock_guard lock(m_mutex);
    return m_frameCache;
}

void Dataset::evictLocked(std::vector<std::shared_ptr<const Frame>>& evicted) const {
    // The most recent frame always stays, even over budget.
    while (m_cachedBytes > m_budget.load() && m_lru.size() > 1) {
        m_cachedBytes -= m_lru.back().bytes;
        evicted.push_back(std::move(m_lru.back().frame));
        m_lruIndex.erase(m_lru.back().index);
        m_lru.pop_back();
    }
}

} // namespace faultline::core
