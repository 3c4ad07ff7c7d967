#include "core/faults/fault_export.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <limits>

namespace faultline::core {

namespace {

void appendField(std::string& out, std::string_view text) {
    if (text.find_first_of(",\"\r\n") == std::string_view::npos) {
        out += text;
        return;
    }
    out += '"';
    for (char ch : text) {
        if (ch == '"')
            out += '"';
        out += ch;
    }
    out += '"';
}

void appendReal(std::string& out, double v) {
    if (std::isnan(v)) {
        out += "NaN";
        return;
    }
    char buf[64];
    const auto r = std::to_chars(buf, buf + sizeof buf, v, std::chars_format::general, 9);
    out.append(buf, r.ptr);
}

void appendCount(std::string& out, std::size_t v) { out += std::to_string(v); }

void appendVec(std::string& out, const Vec3d& v) {
    for (int a = 0; a < 3; ++a) {
        out += ',';
        appendReal(out, v[a]);
    }
}

nlohmann::json jsonReal(double v) {
    if (!std::isfinite(v))
        return nullptr;
    return v;
}

nlohmann::json jsonVec(const Vec3d& v) {
    return nlohmann::json::array({jsonReal(v[0]), jsonReal(v[1]), jsonReal(v[2])});
}

constexpr Vec3d kNaN3{std::numeric_limits<double>::quiet_NaN(),
                      std::numeric_limits<double>::quiet_NaN(),
                      std::numeric_limits<double>::quiet_NaN()};

} // namespace

std::string faultsCsv(std::span<const Fault> faults) {
    std::string out = "id,fault\n";
    for (const Fault& f : faults)
        for (std::int64_t id : f.ids) {
            out += std::to_string(id);
            out += ',';
            appendField(out, f.name);
            out += '\n';
        }
    return out;
}

std::string faultTracksCsv(std::span<const Fault> faults, std::span<const FaultTrack> tracks) {
    std::string out =
        "frame,fault,present,candidate,candidate_size,shared,jaccard,precision,recall\n";
    // Frame-major, as the metrics: shards' rows merge back by frame.
    std::size_t points = 0;
    for (std::size_t f = 0; f < tracks.size() && f < faults.size(); ++f)
        points = std::max(points, tracks[f].points.size());
    for (std::size_t i = 0; i < points; ++i)
        for (std::size_t f = 0; f < tracks.size() && f < faults.size(); ++f) {
            if (i >= tracks[f].points.size())
                continue;
            const FaultTrackPoint& p = tracks[f].points[i];
            const CandidateMatch& m = p.match;
            out += std::to_string(p.frame) + ',';
            appendField(out, faults[f].name);
            out += ',' + std::to_string(m.present) + ',' + std::to_string(m.candidate) + ',' +
                   std::to_string(m.candidateSize) + ',' + std::to_string(m.shared);
            for (double v : {m.jaccard, m.precision, m.recall}) {
                out += ',';
                appendReal(out, v);
            }
            out += '\n';
        }
    return out;
}

std::string faultEventsCsv(std::span<const Fault> faults, std::span<const FaultEvent> events) {
    std::string out = "frame,kind,faults\n";
    for (const FaultEvent& e : events) {
        out += std::to_string(e.frame) + ',' + std::string(faultEventKindName(e.kind)) + ',';
        std::string names;
        for (std::size_t k : e.faults)
            if (k < faults.size())
                names += (names.empty() ? "" : ";") + faults[k].name;
        appendField(out, names);
        out += '\n';
    }
    return out;
}

std::string faultMetricsCsvHeader() {
    return "frame,fault,count,dip,dip_direction,strike,thickness,area,throw,net_slip,dip_slip,"
           "strike_slip,throw_status,hw_samples,fw_samples,centroid_x,centroid_y,centroid_z,"
           "min_x,min_y,min_z,max_x,max_y,max_z,normal_x,normal_y,normal_z,eigen_0,eigen_1,"
           "eigen_2,mean_radius,broken,seed_frame,seed_x,seed_y,seed_z,length,height";
}

std::string faultMetricsCsv(const FaultMetricsSeries& series) {
    std::string out = faultMetricsCsvHeader();
    out += '\n';
    for (const FaultFrameMetrics& m : series.rows) {
        if (!series.selection.contains(m.frame))
            continue; // read for a seed only
        appendCount(out, m.frame);
        out += ',';
        appendField(out, m.name);
        out += ',';
        appendCount(out, m.count);
        for (double v : {m.dip, m.dipDirection, m.strike, m.thickness, m.area, m.throwVertical,
                         m.netSlip, m.dipSlip, m.strikeSlip}) {
            out += ',';
            appendReal(out, v);
        }
        out += ',';
        out += throwStatusName(m.throwStatus);
        out += ',';
        appendCount(out, m.hangingWallSamples);
        out += ',';
        appendCount(out, m.footwallSamples);
        appendVec(out, m.centroid);
        appendVec(out, m.min);
        appendVec(out, m.max);
        appendVec(out, m.normal);
        appendVec(out, m.eigenvalues);
        out += ',';
        appendReal(out, m.meanRadius);
        out += ',';
        appendCount(out, m.broken);
        out += ',';
        const FaultSeed* seed = m.fault < series.seeds.size() ? &series.seeds[m.fault] : nullptr;
        if (seed && seed->found) {
            appendCount(out, seed->frame);
            appendVec(out, seed->point);
        } else {
            appendVec(out, kNaN3);
        }
        for (double v : {m.length, m.height}) {
            out += ',';
            appendReal(out, v);
        }
        out += '\n';
    }
    return out;
}

nlohmann::json faultMetricsJson(const FaultMetricsSeries& series) {
    nlohmann::json faults = nlohmann::json::array();
    for (std::size_t k = 0; k < series.faultCount; ++k) {
        nlohmann::json frames = nlohmann::json::array();
        std::string name;
        for (std::size_t f = 0; f < series.frameCount; ++f) {
            const FaultFrameMetrics& m = series.at(f, k);
            name = m.name;
            frames.push_back({
                {"frame", m.frame},
                {"count", m.count},
                {"dip", jsonReal(m.dip)},
                {"dip_direction", jsonReal(m.dipDirection)},
                {"strike", jsonReal(m.strike)},
                {"thickness", jsonReal(m.thickness)},
                {"area", jsonReal(m.area)},
                {"length", jsonReal(m.length)},
                {"height", jsonReal(m.height)},
                {"throw", jsonReal(m.throwVertical)},
                {"net_slip", jsonReal(m.netSlip)},
                {"dip_slip", jsonReal(m.dipSlip)},
                {"strike_slip", jsonReal(m.strikeSlip)},
                {"throw_status", throwStatusName(m.throwStatus)},
                {"hw_samples", m.hangingWallSamples},
                {"fw_samples", m.footwallSamples},
                {"centroid", jsonVec(m.centroid)},
                {"min", jsonVec(m.min)},
                {"max", jsonVec(m.max)},
                {"normal", jsonVec(m.normal)},
                {"eigen", jsonVec(m.eigenvalues)},
                {"mean_radius", jsonReal(m.meanRadius)},
                {"broken", m.broken},
            });
        }
        nlohmann::json seed = nullptr;
        if (k < series.seeds.size() && series.seeds[k].found)
            seed = {{"frame", series.seeds[k].frame},
                    {"count", series.seeds[k].count},
                    {"point", jsonVec(series.seeds[k].point)}};
        faults.push_back({{"name", name}, {"seed", seed}, {"frames", std::move(frames)}});
    }
    return {{"frames", series.frameCount}, {"faults", std::move(faults)}};
}

nlohmann::json faultTracksJson(std::span<const Fault> faults, std::span<const FaultTrack> tracks) {
    nlohmann::json out = nlohmann::json::array();
    for (std::size_t k = 0; k < tracks.size() && k < faults.size(); ++k) {
        nlohmann::json frames = nlohmann::json::array();
        for (const FaultTrackPoint& p : tracks[k].points)
            frames.push_back({{"frame", p.frame},
                              {"present", p.match.present},
                              {"candidate", p.match.candidate},
                              {"candidate_size", p.match.candidateSize},
                              {"shared", p.match.shared},
                              {"jaccard", p.match.jaccard},
                              {"precision", p.match.precision},
                              {"recall", p.match.recall}});
        out.push_back({{"name", faults[k].name}, {"frames", std::move(frames)}});
    }
    return out;
}

} // namespace faultline::core
