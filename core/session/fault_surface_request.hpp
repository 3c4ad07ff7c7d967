// FaultSurfaceRequest: what one fault surface is built from (the fault's member spheres in a frame,
// in the fault's colour, and the session's surface settings as field parameters). The journal's
// surface ops, the workbench's background builds and figures share it, so all three agree.
#pragma once

#include "core/surface/metaball_reference.hpp"

#include "core/faults/fault.hpp"
#include "core/model/frame.hpp"
#include "core/selection/visibility.hpp"
#include "core/session/session_state.hpp"
#include "core/surface/interrupter.hpp"
#include "core/surface/sphere_set.hpp"
#include "core/surface/surface_cache.hpp"
#include "core/surface/surface_params.hpp"

#include <array>
#include <cstddef>
#include <optional>
#include <span>
#include <string>
#include <vector>

namespace faultline::core {

// A fault's members present in a frame, gathered as columns (ids absent from the frame are
// skipped), each in the fault's colour.
struct FaultSpheres {
    std::vector<float> x, y, z, radius, rgb;
    SphereSet set() const { return {x, y, z, radius, rgb}; }
    std::size_t size() const { return x.size(); }
};
FaultSpheres gatherFaultSpheres(const Frame& frame, const Fault& fault);

// The part of a fault formed in a frame: its members whose row passes every enabled threshold
// there (a NaN value passes none; a threshold on a variable the frame lacks is ignored, as
// everywhere), with the fault's name and colour; the whole fault when no threshold is enabled.
// Surfaces are built from it, so a fault's surface grows with the fault through time and is not
// drawn at frames before any of its spheres passed (issue 41). Boxes do not cut it.
Fault faultAsFormed(const Frame& frame, const Fault& fault,
                    std::span<const VariableThreshold> thresholds);

// The surface source kVisibleSpheres (session_state.hpp) in a frame: the visible rows' ids as a
// fault in a neutral colour, named "visible spheres" in exports and messages, so that builds,
// caches and exports take it as they take a fault.
Fault visibleSpheresFault(const Frame& frame, const VisibilityResult& visibility);
inline constexpr std::array<float, 3> kVisibleSpheresColor{0.78f, 0.8f, 0.84f};

// The field parameters of a fault's surface setting. Throws CommandError for an unknown kernel.
// Figure 4's initial colour is the setting's, else the fault's colour (so a plain surface is
// known by its fault's colour in the views and in exports), else with a variable's colours white
// (the map's low end would read as a low value); a voxel takes the colour of the spheres within
// their radius + colorReach.
SurfaceParams surfaceParamsOf(const SurfaceSettings& settings, const Fault& fault);

// wrappingIso (core/surface/metaball_reference.hpp) for a fault's spheres in a frame with these
// settings, to three significant digits (what the Surfaces panel writes into a surface.set); none
// when no member is in the frame.
std::optional<double> faultWrappingIso(const Frame& frame, const Fault& fault,
                                       const SurfaceSettings& settings);

// The SurfaceCache key of a fault's surface in frame `frameIndex`: members and their colours (the
// fault's, or a variable's through a map and range: the colour grid depends on them) and every
// field parameter except iso. A colour variable derived from motion also keys by the strain list
// that derived it (Frame::derivation of `frame`; null: none), since deriving again under the
// same names gives the frame other values.
SurfaceKey surfaceKeyOf(std::size_t frameIndex, const Frame* frame, const Fault& fault,
                        const SurfaceSettings& settings, const SurfaceParams& params);

// One fault's surface as an export wants it: the fault and its surface settings.
struct FaultSurfaceRequest {
    Fault fault;
    SurfaceSettings settings;
};

class Session;
// A fault's surface request as the session's exports build it: the fault as formed in the
// current frame (or the visible spheres) with its surface settings (the defaults when it has
// none). Throws CommandError, prefixed with `op`, for a name that is no fault.
FaultSurfaceRequest surfaceRequestFor(Session& s, const std::string& fault, const char* op);

// The members present in a frame in the colours their surface gives them (Figure 4): the
// fault's, or the setting's colour map of its colorBy variable. Throws CommandError when the
// frame has no such variable.
FaultSpheres gatherSurfaceSpheres(const Frame& frame, const FaultSurfaceRequest& request);

// Where a build may reuse earlier work: a SurfaceCache and the frame's index in its dataset.
struct SurfaceReuse {
    SurfaceCache* cache = nullptr;
    std::size_t frameIndex = 0;
    bool keepOnly = false; // with a cache: keep the surface there, return no mesh (no copy)
};

// The session's surfaces of frame `frameIndex` of its data as a reuse: a surface surface.build
// made there is taken, not built again (Session::surfaceCacheFor).
SurfaceReuse surfaceReuseFor(Session& s, std::size_t frameIndex);

// The fault's surface in `frame`: built, or taken from (and kept in) reuse.cache. Throws what
// buildSurface throws, with the fault named in the message (SurfaceCancelled as it is).
SurfaceResult buildFaultSurface(const Frame& frame, const FaultSurfaceRequest& request,
                                Interrupter* interrupter = nullptr, SurfaceReuse reuse = {});

// Build the surfaces in `frame` and write them: a .vdb with one fault's density and colour
// grids; a .glb with one node per fault and, with `glyphs`, the members as instanced spheres.
// Folders are made as needed. Throws what buildSurface throws (the message names the fault)
// and std::runtime_error when writing fails. Safe on a worker thread (it touches no session).
void writeFaultVdb(const Frame& frame, const FaultSurfaceRequest& request, const std::string& path,
                   Interrupter* interrupter = nullptr, SurfaceReuse reuse = {});
void writeFaultsGlb(const Frame& frame, std::span<const FaultSurfaceRequest> requests,
                    const std::string& path, bool glyphs, Interrupter* interrupter = nullptr,
                    SurfaceReuse reuse = {});

} // namespace faultline::core
