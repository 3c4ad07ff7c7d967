// Typed builders of journal commands (issue 39): the workbench, the CLI and tests write
// `cmd::BoxSet(name).enabled(true)` instead of `{{"op", "box.set"}, {"name", name},
// {"enabled", true}}`, so a misspelt op or field, or a value of the wrong type, is a compile
// error rather than a command the op refuses at run time. Each builder converts to the
// command's JSON (what the journal records, ../shared/design/JOURNAL.md); enum values are
// written with their journal names (core/util/enum_names.hpp). Builders only build: the op
// still checks every field (tests/core/commands_test.cpp applies each builder's command).
#pragma once

#include "core/color/colormap.hpp"
#include "core/faults/candidates.hpp"
#include "core/selection/cutting_box.hpp"
#include "core/session/command_args.hpp"
#include "core/session/session_state.hpp"
#include "core/surface/surface_params.hpp"
#include "core/view/camera.hpp"

#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace faultline::core::cmd {

// A command under construction; converts to its JSON.
class Command {
  public:
    operator Json() const& { return m_json; }
    operator Json() && { return std::move(m_json); }

  protected:
    explicit Command(const char* op) : m_json{{"op", op}} {}
    Command(const char* op, const char* key, Json value) : m_json{{"op", op}} {
        m_json[key] = std::move(value);
    }
    Json m_json;
};

// Setters shared by the builders: each returns the builder itself, so they chain.
#define FAULTLINE_CMD_FIELD(Builder, setter, field, ...)                                           \
    Builder& setter(__VA_ARGS__ v) {                                                               \
        m_json[field] = std::move(v);                                                              \
        return *this;                                                                              \
    }

// --- history, frames, data and sessions ---------------------------------------------------
Json undo();
Json redo();
// `commands` as one step: the single command itself when there is one, else a batch.
Json batch(std::vector<Json> commands);
Json frameSet(std::size_t frame);
Json dataOpen(const std::vector<std::string>& paths);
Json dataClose();
Json sessionSave(const std::string& path);
// `data`: the data's paths when they moved (empty: as the session names them).
Json sessionOpen(const std::string& path, const std::vector<std::string>& data = {});
Json layoutSet(Json layout);

// --- cutting boxes ------------------------------------------------------------------------
Json boxAdd(const std::string& name, const std::array<double, 3>& min,
            const std::array<double, 3>& max, BoxMode mode);
// A copy of `box` (every field of the box codec's, its name included).
Json boxAdd(const CuttingBox& box);
Json boxRemove(const std::string& name);
class BoxSet : public Command {
  public:
    explicit BoxSet(const std::string& name) : Command("box.set", "name", name) {}
    FAULTLINE_CMD_FIELD(BoxSet, enabled, "enabled", bool)
    FAULTLINE_CMD_FIELD(BoxSet, rename, "rename", std::string)
    FAULTLINE_CMD_FIELD(BoxSet, min, "min", std::array<double, 3>)
    FAULTLINE_CMD_FIELD(BoxSet, max, "max", std::array<double, 3>)
    BoxSet& mode(BoxMode m);
};

// --- thresholds ---------------------------------------------------------------------------
class ThresholdAdd : public Command {
  public:
    explicit ThresholdAdd(const std::string& variable)
        : Command("threshold.add", "variable", variable) {}
    FAULTLINE_CMD_FIELD(ThresholdAdd, low, "low", double)
    FAULTLINE_CMD_FIELD(ThresholdAdd, high, "high", double)
};
class ThresholdSet : public Command {
  public:
    explicit ThresholdSet(const std::string& variable)
        : Command("threshold.set", "variable", variable) {}
    FAULTLINE_CMD_FIELD(ThresholdSet, enabled, "enabled", bool)
    FAULTLINE_CMD_FIELD(ThresholdSet, low, "low", double)
    FAULTLINE_CMD_FIELD(ThresholdSet, high, "high", double)
};
Json thresholdRemove(const std::string& variable);

// --- views, cameras and colours -----------------------------------------------------------
class ViewAdd : public Command {
  public:
    explicit ViewAdd(const std::string& name) : Command("view.add", "name", name) {}
    FAULTLINE_CMD_FIELD(ViewAdd, frame, "frame", long long)
    FAULTLINE_CMD_FIELD(ViewAdd, offset, "offset", long long)
};
class ViewSet : public Command {
  public:
    explicit ViewSet(const std::string& name) : Command("view.set", "name", name) {}
    FAULTLINE_CMD_FIELD(ViewSet, frame, "frame", long long)
    FAULTLINE_CMD_FIELD(ViewSet, offset, "offset", long long)
    FAULTLINE_CMD_FIELD(ViewSet, linkedCamera, "linked_camera", bool)
    FAULTLINE_CMD_FIELD(ViewSet, contextPoints, "context_points", bool)
};
Json viewRemove(const std::string& name);
class CameraSet : public Command {
  public:
    explicit CameraSet(const std::string& view) : Command("camera.set", "view", view) {}
    // Every field of `camera` (the camera codec's), as a drag or a wheel commits it.
    CameraSet& all(const CameraState& camera);
    FAULTLINE_CMD_FIELD(CameraSet, distance, "distance", double)
    FAULTLINE_CMD_FIELD(CameraSet, azimuth, "azimuth", double)
    FAULTLINE_CMD_FIELD(CameraSet, elevation, "elevation", double)
    FAULTLINE_CMD_FIELD(CameraSet, target, "target", std::array<double, 3>)
    FAULTLINE_CMD_FIELD(CameraSet, orthographic, "orthographic", bool)
};
class ColorSet : public Command {
  public:
    explicit ColorSet(const std::string& view) : Command("color.set", "view", view) {}
    FAULTLINE_CMD_FIELD(ColorSet, variable, "variable", std::string)
    FAULTLINE_CMD_FIELD(ColorSet, map, "map", std::string)
    ColorSet& range(double low, double high);
    ColorSet& rangeMode(RangeMode mode);
    ColorSet& difference(ColorDifference::Mode mode);
    FAULTLINE_CMD_FIELD(ColorSet, sinceFrame, "since_frame", long long)
    FAULTLINE_CMD_FIELD(ColorSet, sinceOffset, "since_offset", long long)
};

// --- strain from motion -------------------------------------------------------------------
class StrainAdd : public Command {
  public:
    StrainAdd() : Command("strain.add") {}
    FAULTLINE_CMD_FIELD(StrainAdd, sinceFrame, "since_frame", long long)
    FAULTLINE_CMD_FIELD(StrainAdd, sinceOffset, "since_offset", long long)
    FAULTLINE_CMD_FIELD(StrainAdd, cutoff, "cutoff", double)
    FAULTLINE_CMD_FIELD(StrainAdd, prefix, "prefix", std::string)
};
Json strainRemove(const std::string& prefix);

// --- faults -------------------------------------------------------------------------------
class FaultCreate : public Command {
  public:
    FaultCreate(const std::string& name, std::vector<std::int64_t> ids)
        : Command("fault.create", "name", name) {
        m_json["ids"] = std::move(ids);
    }
    FAULTLINE_CMD_FIELD(FaultCreate, color, "color", std::array<float, 3>)
    FAULTLINE_CMD_FIELD(FaultCreate, notes, "notes", std::string)
};
class FaultSet : public Command {
  public:
    explicit FaultSet(const std::string& name) : Command("fault.set", "name", name) {}
    FAULTLINE_CMD_FIELD(FaultSet, visible, "visible", bool)
    FAULTLINE_CMD_FIELD(FaultSet, rename, "rename", std::string)
    FAULTLINE_CMD_FIELD(FaultSet, color, "color", std::array<float, 3>)
    FAULTLINE_CMD_FIELD(FaultSet, notes, "notes", std::string)
};
Json faultCreateVisible(const std::string& name); // its spheres: the visible ones
Json faultAdd(const std::string& name, std::vector<std::int64_t> ids);
Json faultAddVisible(const std::string& name); // "from": "visible"
Json faultRemove(const std::string& name, std::vector<std::int64_t> ids);
Json faultDelete(const std::string& name);
Json faultMerge(const std::vector<std::string>& names, const std::string& into);
Json faultSplit(const std::string& name);
// The filter's mode, and its fault when the mode is Only.
Json faultFilter(const FaultFilter& filter);
class FaultCandidates : public Command {
  public:
    FaultCandidates() : Command("fault.candidates") {}
    FAULTLINE_CMD_FIELD(FaultCandidates, link, "link", double)
    FAULTLINE_CMD_FIELD(FaultCandidates, minSize, "min_size", long long)
    FAULTLINE_CMD_FIELD(FaultCandidates, prefix, "prefix", std::string)
    FAULTLINE_CMD_FIELD(FaultCandidates, angle, "angle", double)
    FaultCandidates& method(CandidateMethod m);
};

// --- surfaces -----------------------------------------------------------------------------
class SurfaceSet : public Command {
  public:
    explicit SurfaceSet(const std::string& fault) : Command("surface.set", "fault", fault) {}
    FAULTLINE_CMD_FIELD(SurfaceSet, visible, "visible", bool)
    FAULTLINE_CMD_FIELD(SurfaceSet, iso, "iso", double)
    FAULTLINE_CMD_FIELD(SurfaceSet, opacity, "opacity", double)
    FAULTLINE_CMD_FIELD(SurfaceSet, voxel, "voxel", double)
    FAULTLINE_CMD_FIELD(SurfaceSet, colorBy, "color_by", std::string)
    FAULTLINE_CMD_FIELD(SurfaceSet, map, "map", std::string)
    SurfaceSet& range(double low, double high);
    SurfaceSet& kernel(MetaballKernel k);
    // Its own colour; nullopt clears it ("color": null).
    SurfaceSet& color(const std::optional<std::array<double, 3>>& c);
    // How far a voxel takes a sphere's colour; nullopt: automatic ("color_reach": null).
    SurfaceSet& colorReach(std::optional<double> reach);
    SurfaceSet& clearRange(); // "range": null, the colour range follows the values
};
Json surfaceRemove(const std::string& fault);

// --- output -------------------------------------------------------------------------------
class Render : public Command {
  public:
    Render(const std::string& view, const std::string& path, int width, int height);
    FAULTLINE_CMD_FIELD(Render, transparent, "transparent", bool)
    Render& frames(long long first, long long last);
    FAULTLINE_CMD_FIELD(Render, step, "step", long long)
    FAULTLINE_CMD_FIELD(Render, fps, "fps", long long)
};
// `what`: "spheres" | "faults" | "fault_metrics" | "fault_tracks" | ... (export.csv).
Json exportCsv(const std::string& what, const std::string& path);
Json exportVdb(const std::string& fault, const std::string& path);
Json exportGltf(const std::vector<std::string>& faults, const std::string& path, bool glyphs);

#undef FAULTLINE_CMD_FIELD

} // namespace faultline::core::cmd
