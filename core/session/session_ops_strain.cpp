// Ops on variables derived from motion: strain.add / strain.remove (JOURNAL.md, "Strain from
// motion"). The session's strains[] reach the dataset through Session::syncDerived, which makes
// every frame carry their columns.
#include "core/session/session_ops.hpp"

#include "core/motion/strain_from_motion.hpp"
#include "core/session/items/item_codecs.hpp"

#include <algorithm>
#include <cstdio>

namespace faultline::core::detail {

void registerStrainOps(OpRegistry& ops) {
    addStateOp(ops, "strain.add", [](Session& s, const Json& cmd) -> Json {
        args::onlyFields(cmd, {"since_frame", "since_offset", "cutoff", "prefix", "index"});
        if (!cmd.contains("since_frame") && !cmd.contains("since_offset"))
            throw CommandError("strain.add: give \"since_frame\" (a frame) or \"since_offset\" "
                               "(frames before each frame, e.g. -4)");
        const StrainSpec spec = items::patched("strain.add", StrainSpec{}, cmd);
        auto& strains = s.mutableState().strains;
        if (std::any_of(strains.begin(), strains.end(),
                        [&](const StrainSpec& o) { return o.prefix == spec.prefix; }))
            throw CommandError("strain.add: strain variables with prefix \"" + spec.prefix +
                               "\" exist already: strain.remove them first, or give another "
                               "\"prefix\"");
        if (auto ds = s.dataset()) {
            const long long count = static_cast<long long>(ds->frameCount());
            if (!spec.relative && spec.reference >= count)
                throw CommandError("strain.add: \"since_frame\" " + std::to_string(spec.reference) +
                                   " is out of range 0.." + std::to_string(count - 1));
            if (spec.relative && (spec.reference <= -count || spec.reference >= count))
                throw CommandError("strain.add: \"since_offset\" " +
                                   std::to_string(spec.reference) + " reaches past all " +
                                   std::to_string(count) + " frames");
            // The names must not hide a variable the file has.
            if (auto frame = s.currentFrame()) {
                // A neighbourhood of thousands of spheres is no local strain, and would take
                // hours: at most 20 times the automatic cutoff, or where radii far smaller than
                // the centres' spacing make that one tiny, 20 times 1.5 x the spacing (what the
                // refusal below suggests).
                const double automatic = defaultStrainCutoff(*frame);
                const double spacing = packingStrainCutoff(*frame);
                if (spec.cutoff > 20 * std::max(automatic, spacing)) {
                    char text[200];
                    if (automatic >= spacing)
                        std::snprintf(text, sizeof text,
                                      "strain.add: \"cutoff\" %g is more than 20 times the "
                                      "automatic one (%g) for this data",
                                      spec.cutoff, automatic);
                    else
                        std::snprintf(text, sizeof text,
                                      "strain.add: \"cutoff\" %g is more than 20 times 1.5 x "
                                      "the centres' spacing (%.3g) in this data",
                                      spec.cutoff, spacing);
                    throw CommandError(text);
                }
                // Radii far larger than the centres' spacing (another unit, or not radii at
                // all) make the automatic cutoff take in most of the model: no local strain, and
                // hours of work on a large model (the whole of 27,000 spheres takes a second).
                // Radii far smaller (metres beside millimetres) leave every sphere without a
                // neighbour, and every value NaN.
                if (spec.cutoff == 0) {
                    if (const double around = strainNeighboursWithin(*frame, automatic);
                        around > kMaxAutomaticStrainNeighbours ||
                        around < kMinAutomaticStrainNeighbours) {
                        char text[400];
                        // What to do first: a status line shows the start of it.
                        std::snprintf(
                            text, sizeof text,
                            "strain.add: give \"cutoff\", e.g. %.3g (1.5 x the centres' "
                            "spacing): the automatic one, %g (1.5 x the median diameter), takes "
                            "in about %.0f spheres around each, where a packing's takes about "
                            "%.0f; are the radii in another unit than the centres?",
                            spacing, automatic, around, strainNeighboursWithin(*frame, spacing));
                        throw CommandError(text);
                    }
                }
                const std::size_t own = frame->attributes.size() - frame->derivedColumns;
                for (std::size_t k = 0; k < own; ++k)
                    for (auto v : kStrainVariables)
                        if (frame->attributes[k].name == spec.variable(v))
                            throw CommandError("strain.add: the data has a variable \"" +
                                               frame->attributes[k].name +
                                               "\" already: give a \"prefix\"");
            }
        }
        const long long at =
            args::optionalInteger(cmd, "index").value_or(static_cast<long long>(strains.size()));
        strains.insert(
            strains.begin() + std::clamp(at, 0LL, static_cast<long long>(strains.size())), spec);
        return {{"op", "strain.remove"}, {"prefix", spec.prefix}};
    });
    addStateOp(ops, "strain.remove", [](Session& s, const Json& cmd) -> Json {
        args::onlyFields(cmd, {"prefix"});
        const std::string prefix = args::optionalString(cmd, "prefix").value_or("");
        auto& strains = s.mutableState().strains;
        auto it = std::find_if(strains.begin(), strains.end(),
                               [&](const StrainSpec& o) { return o.prefix == prefix; });
        if (it == strains.end()) {
            std::string known;
            for (const auto& o : strains)
                known += (known.empty() ? "" : ", ") + ("\"" + o.prefix + "\"");
            throw CommandError("strain.remove: no strain variables with prefix \"" + prefix +
                               "\" (" + (known.empty() ? "none were added" : "there are " + known) +
                               ")");
        }
        Json inverse = items::toJson(*it);
        inverse["op"] = "strain.add";
        inverse["index"] = it - strains.begin();
        strains.erase(it);
        return inverse;
    });
}

} // namespace faultline::core::detail
