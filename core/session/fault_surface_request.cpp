#include "core/session/fault_surface_request.hpp"

#include "core/color/colormap.hpp"
#include "core/selection/column_view.hpp"
#include "core/session/session.hpp"
#include "core/surface/fault_surface.hpp"
#include "core/surface/metaball_reference.hpp"
#include "core/surface/surface_export.hpp"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <functional>
#include <limits>
#include <stdexcept>

namespace faultline::core {

FaultSpheres gatherFaultSpheres(const Frame& frame, const Fault& fault) {
    FaultSpheres s;
    for (std::int64_t id : fault.ids)
        if (auto row = frame.rowOf(id)) {
            s.x.push_back(frame.x[*row]);
            s.y.push_back(frame.y[*row]);
            s.z.push_back(frame.z[*row]);
            s.radius.push_back(frame.radius[*row]);
            s.rgb.insert(s.rgb.end(), fault.color.begin(), fault.color.end());
        }
    return s;
}

Fault faultAsFormed(const Frame& frame, const Fault& fault,
                    std::span<const VariableThreshold> thresholds) {
    if (std::none_of(thresholds.begin(), thresholds.end(),
                     [](const VariableThreshold& t) { return t.enabled; }))
        return fault;
    const VisibilityResult passing = computeVisibility(frame, {}, thresholds);
    Fault formed = fault;
    formed.ids.clear();
    for (std::int64_t id : fault.ids)
        if (auto row = frame.rowOf(id); row && passing.mask[*row])
            formed.ids.push_back(id);
    return formed;
}

Fault visibleSpheresFault(const Frame& frame, const VisibilityResult& visibility) {
    Fault f;
    f.name = "visible spheres"; // in exports (grid and node names) and messages
    f.color = kVisibleSpheresColor;
    const std::size_t rows = std::min(frame.size(), visibility.mask.size());
    f.ids.reserve(visibility.visibleCount);
    for (std::size_t row = 0; row < rows; ++row)
        if (visibility.mask[row])
            f.ids.push_back(frame.ids[row]);
    if (!std::is_sorted(f.ids.begin(), f.ids.end()))
        std::sort(f.ids.begin(), f.ids.end());
    return f;
}

namespace {
// The one colour of a surface without colorBy: the setting's, else the fault's.
std::array<float, 3> plainColour(const SurfaceSettings& settings, const Fault& fault) {
    if (!settings.color || !settings.colorBy.empty())
        return fault.color;
    return {static_cast<float>((*settings.color)[0]), static_cast<float>((*settings.color)[1]),
            static_cast<float>((*settings.color)[2])};
}
} // namespace

FaultSpheres gatherSurfaceSpheres(const Frame& frame, const FaultSurfaceRequest& request) {
    const SurfaceSettings& st = request.settings;
    FaultSpheres s = gatherFaultSpheres(frame, request.fault);
    if (st.colorBy.empty()) {
        const std::array<float, 3> c = plainColour(st, request.fault);
        for (std::size_t k = 0; k + 2 < s.rgb.size(); k += 3)
            s.rgb[k] = c[0], s.rgb[k + 1] = c[1], s.rgb[k + 2] = c[2];
        return s;
    }
    // An attribute, or one of the built-in columns (as a view colours by them).
    const auto column = findColumn(frame, st.colorBy);
    if (!column)
        throw CommandError("no variable \"" + st.colorBy + "\" to colour by in this frame");
    const ColorMapSpec* map = &st.colorMap;
    ValueRange range{0.0, 1.0};
    if (st.colorRange) {
        range = {(*st.colorRange)[0], (*st.colorRange)[1]};
    } else if (const AttributeColumn* attribute = frame.attribute(st.colorBy)) {
        range = {attribute->min, attribute->max}; // cached by the frame
    } else {
        range = {std::numeric_limits<double>::infinity(), -std::numeric_limits<double>::infinity()};
        for (std::size_t row = 0; row < column->size; ++row)
            if (const double v = column->value(row); std::isfinite(v))
                range = {std::min(range.low, v), std::max(range.high, v)};
    }
    range = widenDegenerate(range);
    std::size_t k = 0;
    for (std::int64_t id : request.fault.ids)
        if (auto row = frame.rowOf(id)) {
            const double v = column->value(*row);
            const glm::vec3 c =
                std::isnan(v)
                    ? nanColor(*map)
                    : sampleColorMap(*map, std::clamp(normalizeValue(v, range), 0.0, 1.0));
            s.rgb[3 * k] = c.r, s.rgb[3 * k + 1] = c.g, s.rgb[3 * k + 2] = c.b;
            ++k;
        }
    return s;
}

SurfaceParams surfaceParamsOf(const SurfaceSettings& settings, const Fault& fault) {
    SurfaceParams params;
    params.kernel = settings.kernel;
    params.iso = static_cast<float>(settings.iso);
    params.voxelSize = static_cast<float>(settings.voxel);
    // (Clamped into float's range: validation refuses what is far too large.)
    params.colorReach = static_cast<float>(std::min(settings.colorReach.value_or(0.0), 1e30));
    params.initialColor = plainColour(settings, fault);
    if (settings.initialColor) {
        for (int k = 0; k < 3; ++k)
            params.initialColor[k] = static_cast<float>((*settings.initialColor)[k]);
    } else if (!settings.colorBy.empty()) {
        params.initialColor = {1.0f, 1.0f, 1.0f};
    }
    return params;
}

SurfaceKey surfaceKeyOf(std::size_t frameIndex, const Frame* frame, const Fault& fault,
                        const SurfaceSettings& settings, const SurfaceParams& params) {
    std::uint64_t members = hashMemberIds(fault.ids);
    auto mix = [&](std::uint64_t v) { members = (members ^ v) * 0x100000001b3ull; };
    for (float c : plainColour(settings, fault))
        mix(std::bit_cast<std::uint32_t>(c));
    mix(settings.colorReach ? 1 : 0); // none: from the mean radius (params hold 0)
    if (!settings.colorBy.empty()) {
        mix(std::hash<std::string>{}(settings.colorBy));
        mix(std::hash<std::string>{}(colorMapName(settings.colorMap)));
        if (settings.colorRange)
            for (double r : *settings.colorRange)
                mix(std::bit_cast<std::uint64_t>(r));
        if (frame && frame->derivedColumns > 0) {
            const auto& columns = frame->attributes;
            const bool derived = std::any_of(
                columns.end() - static_cast<std::ptrdiff_t>(frame->derivedColumns), columns.end(),
                [&](const AttributeColumn& c) { return c.name == settings.colorBy; });
            if (derived)
                mix(frame->derivation);
        }
    }
    return {static_cast<std::int64_t>(frameIndex), members, fieldParamsHash(params)};
}

std::optional<double> faultWrappingIso(const Frame& frame, const Fault& fault,
                                       const SurfaceSettings& settings) {
    const FaultSpheres spheres = gatherFaultSpheres(frame, fault);
    if (spheres.size() == 0)
        return std::nullopt;
    const double iso = wrappingIso(spheres.set(), surfaceParamsOf(settings, fault));
    if (!(iso > 0) || !std::isfinite(iso))
        return std::nullopt;
    const double unit = std::pow(10.0, std::floor(std::log10(iso)) - 2);
    return std::round(iso / unit) * unit;
}

namespace {

void makeFolder(const std::string& path) {
    const auto folder = std::filesystem::path(path).parent_path();
    if (!folder.empty())
        std::filesystem::create_directories(folder);
}

} // namespace

SurfaceReuse surfaceReuseFor(Session& s, std::size_t frameIndex) {
    return {&s.surfaceCacheFor(frameIndex), frameIndex};
}

SurfaceResult buildFaultSurface(const Frame& frame, const FaultSurfaceRequest& r,
                                Interrupter* interrupter, SurfaceReuse reuse) {
    try {
        const FaultSpheres spheres = gatherSurfaceSpheres(frame, r);
        const SurfaceParams params = surfaceParamsOf(r.settings, r.fault);
        // No colour reach set: twice the spheres' mean radius (the key's members and frame fix
        // it) when a variable colours them; one colour needs none.
        SurfaceParams built = params;
        if (!r.settings.colorReach && !r.settings.colorBy.empty() && spheres.size() > 0)
            built.colorReach = static_cast<float>(2.0 * meanRadius(spheres.set()));
        if (reuse.cache)
            return reuse.cache->get(
                surfaceKeyOf(reuse.frameIndex, &frame, r.fault, r.settings, params), built,
                [&] { return spheres.set(); }, interrupter, reuse.keepOnly);
        return buildSurface(spheres.set(), built, interrupter);
    } catch (const SurfaceCancelled&) {
        throw;
    } catch (const std::exception& e) {
        throw std::runtime_error("fault \"" + r.fault.name + "\": " + e.what());
    }
}

void writeFaultVdb(const Frame& frame, const FaultSurfaceRequest& request, const std::string& path,
                   Interrupter* interrupter, SurfaceReuse reuse) {
    const SurfaceResult result = buildFaultSurface(frame, request, interrupter, reuse);
    VdbSurface surface{request.fault.name, result.field.get(), result.iso, {}};
    // What the colour grid's colours mean.
    const SurfaceSettings& st = request.settings;
    if (st.colorBy.empty()) {
        surface.notes.push_back({"color_by", "one colour"});
    } else {
        char range[64] = "the frame's min to max";
        if (st.colorRange)
            std::snprintf(range, sizeof range, "%.9g %.9g", (*st.colorRange)[0],
                          (*st.colorRange)[1]);
        surface.notes.push_back({"color_by", st.colorBy});
        surface.notes.push_back({"color_map", colorMapName(st.colorMap)});
        surface.notes.push_back({"color_range", range});
    }
    makeFolder(path);
    exportVdb(path, std::span<const VdbSurface>(&surface, 1));
}

void writeFaultsGlb(const Frame& frame, std::span<const FaultSurfaceRequest> requests,
                    const std::string& path, bool glyphs, Interrupter* interrupter,
                    SurfaceReuse reuse) {
    std::vector<SurfaceResult> results;
    for (const auto& r : requests)
        results.push_back(buildFaultSurface(frame, r, interrupter, reuse));
    std::vector<GltfSurface> surfaces;
    for (std::size_t k = 0; k < requests.size(); ++k)
        surfaces.push_back(
            {requests[k].fault.name, &results[k].mesh, requests[k].settings.opacity});
    // Optionally the member spheres as instanced glyphs, in the colours their surface gives them.
    FaultSpheres all;
    if (glyphs)
        for (const auto& r : requests) {
            const FaultSpheres f = gatherSurfaceSpheres(frame, r);
            for (auto [dst, src] : {std::pair{&all.x, &f.x},
                                    {&all.y, &f.y},
                                    {&all.z, &f.z},
                                    {&all.radius, &f.radius},
                                    {&all.rgb, &f.rgb}})
                dst->insert(dst->end(), src->begin(), src->end());
        }
    makeFolder(path);
    exportGlb(path, surfaces, all.set());
}

} // namespace faultline::core
