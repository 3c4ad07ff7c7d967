// Ops on faults: fault.create/add/remove/set/delete/restore/merge/filter (JOURNAL.md).
#include "core/session/session_ops.hpp"

#include "core/faults/candidates.hpp"
#include "core/session/commands.hpp"
#include "core/session/fault_surface_request.hpp"
#include "core/session/items/item_codecs.hpp"

#include <algorithm>
#include <cmath>
#include <optional>

namespace faultline::core::detail {

namespace {

// Distinct, legible colours for new faults, in order (Tableau 10, with a dark teal for its grey;
// issue 41: the old palette's pink and magenta looked alike side by side).
constexpr std::array<std::array<float, 3>, 10> kFaultPalette{{{0.882f, 0.341f, 0.349f},
                                                              {0.306f, 0.475f, 0.655f},
                                                              {0.949f, 0.557f, 0.169f},
                                                              {0.349f, 0.631f, 0.310f},
                                                              {0.690f, 0.478f, 0.631f},
                                                              {0.929f, 0.788f, 0.282f},
                                                              {0.463f, 0.718f, 0.698f},
                                                              {0.612f, 0.459f, 0.373f},
                                                              {1.000f, 0.616f, 0.655f},
                                                              {0.106f, 0.400f, 0.400f}}};

Fault& faultOf(Session& s, const Json& cmd, const char* op) {
    const std::string name = args::string(cmd, "name");
    Fault* f = s.mutableState().fault(name);
    if (!f)
        throw CommandError(std::string(op) + ": no fault named \"" + name + "\"");
    return *f;
}

std::vector<std::int64_t> visibleIds(Session& s, const char* op) {
    auto frame = s.currentFrame();
    if (!frame)
        throw CommandError(std::string(op) + ": \"from\": \"visible\" needs open data");
    const auto& vis = s.visibility();
    std::vector<std::int64_t> ids;
    ids.reserve(vis.visibleCount);
    for (std::size_t row = 0; row < vis.mask.size(); ++row)
        if (vis.mask[row])
            ids.push_back(frame->ids[row]);
    return ids;
}

} // namespace

CandidateOptions candidateOptionsFrom(const Json& cmd, const char* op) {
    CandidateOptions options;
    options.link = args::optionalNumber(cmd, "link").value_or(kDefaultCandidateLink);
    const long long minSize = args::optionalInteger(cmd, "min_size")
                                  .value_or(static_cast<long long>(kDefaultCandidateMinSize));
    if (!(options.link > 0) || minSize < 1)
        throw CommandError(std::string(op) + ": \"link\" must be > 0 and \"min_size\" >= 1");
    options.minSize = static_cast<std::size_t>(minSize);
    if (auto method = args::optionalString(cmd, "method")) {
        try {
            options.method = parseCandidateMethod(*method);
        } catch (const std::invalid_argument& e) {
            throw CommandError(std::string(op) + ": \"method\" " + e.what());
        }
    }
    options.angle = args::optionalNumber(cmd, "angle").value_or(kDefaultCandidateAngle);
    options.radius = args::optionalNumber(cmd, "radius").value_or(0.0);
    if (!(options.angle > 0 && options.angle < 90))
        throw CommandError(std::string(op) + ": \"angle\" must lie between 0 and 90 degrees");
    if (!(options.radius >= 0))
        throw CommandError(std::string(op) + ": \"radius\" must be >= 0 (0: automatic)");
    if (options.method == CandidateMethod::Connected &&
        (cmd.contains("angle") || cmd.contains("radius")))
        throw CommandError(std::string(op) +
                           ": \"angle\" and \"radius\" belong to the network method");
    return options;
}

void registerFaultOps(OpRegistry& ops) {
    // A sphere belongs to at most one fault (issue 41): putting spheres into `keep` takes
    // them out of every other fault. Returns the commands that give them back, and says what
    // moved ("moved 37 from C2 to F1") in the session's note.
    auto takeFromOthers = [](Session& s, const std::string& keep,
                             const std::vector<std::int64_t>& ids) {
        std::vector<Json> giveBack;
        std::string moved;
        for (Fault& other : s.mutableState().faults) {
            if (other.name == keep)
                continue;
            const auto taken = other.remove(ids);
            if (taken.empty())
                continue;
            giveBack.push_back({{"op", "fault.add"}, {"name", other.name}, {"ids", taken}});
            moved +=
                (moved.empty() ? "" : ", ") + std::to_string(taken.size()) + " from " + other.name;
        }
        if (!moved.empty())
            s.noteMoved(moved, keep);
        return giveBack;
    };
    // The inverse of an op that put spheres in a fault, with what it took from others after it.
    auto withGiveBack = [](Json inverse, std::vector<Json> giveBack) -> Json {
        if (giveBack.empty())
            return inverse;
        giveBack.insert(giveBack.begin(), std::move(inverse));
        return {{"op", "batch"}, {"commands", giveBack}};
    };
    addStateOp(ops, "fault.create", [=](Session& s, const Json& cmd) -> Json {
        args::onlyFields(cmd, {"name", "from", "ids", "color", "notes", "index"});
        Fault f;
        f.name = args::string(cmd, "name");
        if (f.name.empty() || s.state().fault(f.name))
            throw CommandError("fault.create: a fault named \"" + f.name + "\" exists already");
        if (isVisibleSpheres(f.name))
            throw CommandError("fault.create: \"" + f.name +
                               "\" names the visible spheres' surface; choose another name");
        if (cmd.contains("from") == cmd.contains("ids"))
            throw CommandError("fault.create: give either \"from\": \"visible\" or \"ids\"");
        if (cmd.contains("from")) {
            if (args::string(cmd, "from") != "visible")
                throw CommandError("fault.create: \"from\" must be \"visible\"");
            f.ids = visibleIds(s, "fault.create");
        } else {
            f.ids = args::ids(cmd, "ids");
        }
        normalizeIds(f.ids);
        auto& faults = s.mutableState().faults;
        f.color = kFaultPalette[faults.size() % kFaultPalette.size()];
        // The fields beside the members (colour, notes) as any fault's.
        Json fields = cmd;
        fields.erase("ids");
        f = items::patched("fault.create", f, fields);
        const long long index =
            args::optionalInteger(cmd, "index").value_or(static_cast<long long>(faults.size()));
        const std::vector<std::int64_t> members = f.ids;
        faults.insert(faults.begin() +
                          std::clamp(index, 0LL, static_cast<long long>(faults.size())),
                      std::move(f));
        auto giveBack = takeFromOthers(s, args::string(cmd, "name"), members);
        return withGiveBack({{"op", "fault.delete"}, {"name", args::string(cmd, "name")}},
                            std::move(giveBack));
    });
    addStateOp(ops, "fault.add", [=](Session& s, const Json& cmd) -> Json {
        args::onlyFields(cmd, {"name", "ids", "from"});
        Fault& f = faultOf(s, cmd, "fault.add");
        if (cmd.contains("from") == cmd.contains("ids"))
            throw CommandError("fault.add: give either \"from\": \"visible\" or \"ids\"");
        std::vector<std::int64_t> ids;
        if (cmd.contains("from")) {
            if (args::string(cmd, "from") != "visible")
                throw CommandError("fault.add: \"from\" must be \"visible\"");
            ids = visibleIds(s, "fault.add");
        } else {
            ids = args::ids(cmd, "ids");
        }
        const auto added = f.add(std::move(ids));
        const std::string name = f.name; // `f` may move when others change
        auto giveBack = takeFromOthers(s, name, added);
        return withGiveBack({{"op", "fault.remove"}, {"name", name}, {"ids", added}},
                            std::move(giveBack));
    });
    addStateOp(ops, "fault.remove", [](Session& s, const Json& cmd) -> Json {
        args::onlyFields(cmd, {"name", "ids"});
        Fault& f = faultOf(s, cmd, "fault.remove");
        const auto removed = f.remove(args::ids(cmd, "ids"));
        return {{"op", "fault.add"}, {"name", f.name}, {"ids", removed}};
    });
    addStateOp(ops, "fault.set", [](Session& s, const Json& cmd) -> Json {
        args::onlyFields(cmd, {"name", "color", "notes", "visible", "rename"});
        Fault& f = faultOf(s, cmd, "fault.set");
        Fault next = items::patched("fault.set", f, cmd);
        if (auto rename = args::optionalString(cmd, "rename")) {
            if (rename->empty() || (*rename != f.name && s.state().fault(*rename)) ||
                isVisibleSpheres(*rename))
                throw CommandError("fault.set: cannot rename to \"" + *rename + "\"");
            next.name = *rename;
        }
        Json inverse = {{"op", "fault.set"},
                        {"name", next.name},
                        {"color", f.color},
                        {"notes", f.notes},
                        {"visible", f.visible}};
        if (next.name != f.name) {
            inverse["rename"] = f.name;
            auto& state = s.mutableState();
            for (auto& surface : state.surfaces)
                if (surface.fault == f.name)
                    surface.fault = next.name;
            if (state.faultFilter.fault == f.name)
                state.faultFilter.fault = next.name;
        }
        f = std::move(next);
        return inverse;
    });
    addStateOp(ops, "fault.delete", [](Session& s, const Json& cmd) -> Json {
        args::onlyFields(cmd, {"name"});
        const std::string name = args::string(cmd, "name");
        auto& state = s.mutableState();
        auto it = std::find_if(state.faults.begin(), state.faults.end(),
                               [&](const Fault& f) { return f.name == name; });
        if (it == state.faults.end())
            throw CommandError("fault.delete: no fault named \"" + name + "\"");
        Json inverse = {{"op", "fault.restore"},
                        {"fault", items::toJson(*it)},
                        {"index", it - state.faults.begin()}};
        if (SurfaceSettings* surface = state.surface(name)) {
            // Back where it was among the surfaces (issue 42: undo put it last, so a refused
            // batch that deleted and restored a fault reordered the surfaces).
            const auto at = surface - state.surfaces.data();
            inverse["surface"] = items::toJson(*surface);
            inverse["surface_index"] = at;
            state.surfaces.erase(state.surfaces.begin() + at);
        }
        if (state.faultFilter.mode == FaultFilter::Mode::Only && state.faultFilter.fault == name) {
            inverse = {{"op", "batch"},
                       {"commands", {inverse, core::cmd::faultFilter(state.faultFilter)}}};
            state.faultFilter = FaultFilter{};
        }
        state.faults.erase(it);
        return inverse;
    });
    addStateOp(ops, "fault.restore", [](Session& s, const Json& cmd) -> Json {
        args::onlyFields(cmd, {"fault", "index", "surface", "surface_index"});
        Fault f = items::patchedField("fault.restore", Fault{}, cmd, "fault", {"name"});
        auto& state = s.mutableState();
        if (state.fault(f.name) || isVisibleSpheres(f.name))
            throw CommandError("fault.restore: a fault named \"" + f.name + "\" exists already");
        if (cmd.contains("surface")) {
            SurfaceSettings st;
            st.fault = f.name;
            st = items::patchedField("fault.restore", st, cmd, "surface");
            const long long at = args::optionalInteger(cmd, "surface_index")
                                     .value_or(static_cast<long long>(state.surfaces.size()));
            state.surfaces.insert(
                state.surfaces.begin() +
                    std::clamp(at, 0LL, static_cast<long long>(state.surfaces.size())),
                st);
        }
        const long long index = args::optionalInteger(cmd, "index")
                                    .value_or(static_cast<long long>(state.faults.size()));
        const std::string name = f.name;
        state.faults.insert(state.faults.begin() +
                                std::clamp(index, 0LL, static_cast<long long>(state.faults.size())),
                            std::move(f));
        return {{"op", "fault.delete"}, {"name", name}};
    });
    addStateOp(ops, "fault.merge", [](Session& s, const Json& cmd) -> Json {
        // Members of every named fault join `into` (created when new); the others are deleted.
        args::onlyFields(cmd, {"names", "into"});
        const auto names = args::strings(cmd, "names");
        const std::string into = args::string(cmd, "into");
        if (names.size() < 2)
            throw CommandError("fault.merge: \"names\" needs at least two faults");
        for (std::size_t k = 0; k < names.size(); ++k)
            if (std::find(names.begin(), names.begin() + std::ptrdiff_t(k), names[k]) !=
                names.begin() + std::ptrdiff_t(k))
                throw CommandError("fault.merge: \"names\" lists \"" + names[k] + "\" twice");
        std::vector<std::int64_t> ids;
        for (const auto& n : names) {
            const Fault* f = s.state().fault(n);
            if (!f)
                throw CommandError("fault.merge: no fault named \"" + n + "\"");
            ids.insert(ids.end(), f->ids.begin(), f->ids.end());
        }
        Json batch = Json::array();
        if (!s.state().fault(into))
            batch.push_back({{"op", "fault.create"}, {"name", into}, {"ids", Json::array()}});
        batch.push_back({{"op", "fault.add"}, {"name", into}, {"ids", ids}});
        for (const auto& n : names)
            if (n != into)
                batch.push_back({{"op", "fault.delete"}, {"name", n}});
        // One batch: a failure leaves nothing half-merged, and undo restores every fault.
        return s.execute({{"op", "batch"}, {"commands", batch}});
    });
    addStateOp(ops, "fault.filter", [](Session& s, const Json& cmd) -> Json {
        args::onlyFields(cmd, {"mode", "fault"});
        const auto mode = parseFaultFilterMode(args::string(cmd, "mode"));
        if (!mode)
            throw CommandError("fault.filter: \"mode\" must be " + faultFilterModeNames());
        FaultFilter next;
        next.mode = *mode;
        if (next.mode == FaultFilter::Mode::Only) {
            next.fault = args::string(cmd, "fault");
            if (!s.state().fault(next.fault))
                throw CommandError("fault.filter: no fault named \"" + next.fault + "\"");
        }
        Json inverse = core::cmd::faultFilter(s.state().faultFilter);
        s.mutableState().faultFilter = next;
        return inverse;
    });
    addStateOp(ops, "fault.candidates", [](Session& s, const Json& cmd) -> Json {
        // Candidates of the visible spheres (network by default, or connected components),
        // each accepted as a fault, largest first.
        args::onlyFields(cmd, {"link", "min_size", "prefix", "method", "angle", "radius"});
        const CandidateOptions options = candidateOptionsFrom(cmd, "fault.candidates");
        const std::string prefix =
            args::optionalString(cmd, "prefix").value_or(std::string(kDefaultCandidatePrefix));
        auto frame = s.currentFrame();
        if (!frame)
            throw CommandError("fault.candidates: no data is open");
        const CandidateSet set = findCandidates(*frame, s.visibility().mask, options);
        if (set.candidates.empty()) {
            // Nothing found is an answer, not an error: a loop over frames (or a journal re-run
            // on other data) goes on, and the note says so (the status line, replay's output).
            // The empty batch is still one undo step, so an undo after it undoes nothing else.
            s.addNote("no faults made: no group of at least " + std::to_string(options.minSize) +
                      " visible spheres" +
                      (options.method == CandidateMethod::Network
                           ? " that follows a fault in frame " + std::to_string(s.state().frame) +
                                 " (try \"method\": \"connected\")"
                           : " linked in frame " + std::to_string(s.state().frame)));
            return s.execute({{"op", "batch"}, {"commands", Json::array()}});
        }
        Json batch = Json::array();
        for (const Fault& f : faultsFromCandidates(set.candidates, prefix)) {
            if (s.state().fault(f.name))
                throw CommandError("fault.candidates: a fault named \"" + f.name +
                                   "\" exists already (choose another \"prefix\")");
            Json create = {
                {"op", "fault.create"}, {"name", f.name}, {"ids", f.ids}, {"color", f.color}};
            // Distributed damage (issue 41) and sub-horizontal layers (issue 37) are accepted
            // too, but say what they are.
            if (std::string note = shapeNote(candidateShape(*frame, f.ids)); !note.empty())
                create["notes"] = note;
            batch.push_back(std::move(create));
        }
        return s.execute({{"op", "batch"}, {"commands", batch}});
    });
    addStateOp(ops, "fault.split", [](Session& s, const Json& cmd) -> Json {
        // A fault's members in the current frame, split into pieces: the faults it holds (as
        // fault.candidates' network method sees them: apart at junctions), or its connected
        // pieces with "method": "connected". name.1 (largest, in the fault's colour), name.2, ...
        // Pieces under "min_size" spheres (the candidates' default) are not made: their members,
        // members absent from this frame and members that follow no fault stay with the largest
        // piece. A fault with surface settings passes them to every piece; with an inverse kernel
        // each piece's iso-value keeps the parent's ratio to the iso that wraps its spheres (those
        // values grow with the number of spheres).
        args::onlyFields(cmd, {"name", "link", "method", "angle", "radius", "min_size"});
        const Fault& fault = faultOf(s, cmd, "fault.split");
        auto frame = s.currentFrame();
        if (!frame)
            throw CommandError("fault.split: no data is open");
        const CandidateOptions options = candidateOptionsFrom(cmd, "fault.split");
        std::vector<std::uint8_t> members(frame->size(), 0);
        std::vector<std::int64_t> absent;
        for (std::int64_t id : fault.ids) {
            if (auto row = frame->rowOf(id))
                members[*row] = 1;
            else
                absent.push_back(id);
        }
        const CandidateSet set = findCandidates(*frame, members, options);
        if (set.candidates.size() < 2)
            throw CommandError("fault.split: \"" + fault.name + "\" is one " +
                               (options.method == CandidateMethod::Network
                                    ? std::string("fault (no junction splits it)")
                                    : "connected piece at link " + std::to_string(options.link)) +
                               (options.minSize > 1
                                    ? " of at least " + std::to_string(options.minSize) + " spheres"
                                    : std::string()));
        for (std::int64_t id : fault.ids)
            if (auto row = frame->rowOf(id); row && set.rowLabel[*row] < 0)
                absent.push_back(id);
        const std::string name = fault.name;
        const Fault parent = fault;
        std::optional<SurfaceSettings> surface;
        if (const SurfaceSettings* st = s.state().surface(name))
            surface = *st;
        std::optional<double> parentWrap;
        if (surface && surface->kernel != MetaballKernel::Compact)
            parentWrap = faultWrappingIso(*frame, parent, *surface);
        Json batch = Json::array({{{"op", "fault.delete"}, {"name", name}}});
        Json surfaces = Json::array();
        for (std::size_t k = 0; k < set.candidates.size(); ++k) {
            std::vector<std::int64_t> ids = set.candidates[k].ids;
            if (k == 0)
                ids.insert(ids.end(), absent.begin(), absent.end());
            const std::string piece = name + "." + std::to_string(k + 1);
            if (s.state().fault(piece))
                throw CommandError("fault.split: a fault named \"" + piece + "\" exists already");
            const auto color = k == 0 ? Json(parent.color) : Json(candidateColor(k));
            batch.push_back(
                {{"op", "fault.create"}, {"name", piece}, {"ids", ids}, {"color", color}});
            if (!surface)
                continue;
            SurfaceSettings st = *surface;
            st.fault = piece;
            if (parentWrap) {
                Fault f;
                f.name = piece;
                f.ids = ids;
                if (const auto wrap = faultWrappingIso(*frame, f, st)) {
                    const double iso = surface->iso * (*wrap / *parentWrap);
                    const double unit = std::pow(10.0, std::floor(std::log10(iso)) - 2);
                    st.iso = std::round(iso / unit) * unit;
                }
            }
            Json set = items::toJson(st);
            set["op"] = "surface.set";
            set["fault"] = piece;
            surfaces.push_back(std::move(set));
        }
        for (auto& c : surfaces)
            batch.push_back(std::move(c));
        return s.execute({{"op", "batch"}, {"commands", batch}});
    });
}

} // namespace faultline::core::detail
