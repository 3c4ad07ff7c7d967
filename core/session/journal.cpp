#include "core/session/journal.hpp"

#include "core/io/byte_source.hpp"
#include "core/io/input_error.hpp"
#include "core/selection/column_view.hpp"
#include "core/selection/histogram.hpp"
#include "core/session/session_json.hpp"
#include "core/util/image_compare.hpp"

#include <stb/stb_image.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <set>
#include <sstream>

namespace faultline::core {

namespace fs = std::filesystem;

namespace {

const char* kExpectations[] = {"visible_count", "fault_size", "fault_count", "histogram",
                               "file_exists",   "image",      "frame"};

// An image expectation without "min_ssim": renders that pass the mean and pixel limits score
// above 0.98 here; 0.95 catches a changed structure (a missing edge, a shifted shape) the
// byte mean can hide.
constexpr double kDefaultMinSsim = 0.95;

std::string describe(const Json& v) { return v.dump(); }

std::optional<std::string> mismatch(const Json& expected, const Json& actual) {
    if (expected == actual)
        return std::nullopt;
    return "expected " + describe(expected) + ", actual " + describe(actual);
}

// The image at `path` against `reference` (core/util/image_compare.hpp): mean |a - b| over all
// bytes at most maxDiff, with maxPixels at most that many pixels differing by more than 48 of
// 255 in a channel, and an SSIM of at least minSsim.
std::optional<std::string> imageFileMismatch(const std::string& path, const std::string& reference,
                                             double maxDiff, std::optional<long long> maxPixels,
                                             double minSsim) {
    int w1, h1, c1, w2, h2, c2;
    unsigned char* a = stbi_load(path.c_str(), &w1, &h1, &c1, 4);
    if (!a)
        return "cannot read image " + path;
    unsigned char* b = stbi_load(reference.c_str(), &w2, &h2, &c2, 4);
    if (!b) {
        stbi_image_free(a);
        return "cannot read reference image " + reference;
    }
    auto result = imageMismatch({w1, h1, a}, {w2, h2, b}, maxDiff, maxPixels, minSsim);
    stbi_image_free(a);
    stbi_image_free(b);
    return result;
}

} // namespace

bool isKnownExpectation(const std::string& name) {
    for (const char* e : kExpectations)
        if (name == e)
            return true;
    return false;
}

std::vector<JournalLine> parseJournal(const std::string& text, const std::string& path,
                                      const Session& session) {
    std::vector<JournalLine> lines;
    std::size_t pos = 0, number = 0;
    while (pos < text.size()) {
        std::size_t end = text.find('\n', pos);
        if (end == std::string::npos)
            end = text.size();
        std::string_view line(text.data() + pos, end - pos);
        pos = end + 1;
        ++number;
        while (!line.empty() && (line.front() == ' ' || line.front() == '\t'))
            line.remove_prefix(1);
        while (!line.empty() && (line.back() == ' ' || line.back() == '\t' || line.back() == '\r'))
            line.remove_suffix(1);
        if (line.empty() || line.substr(0, 2) == "//")
            continue;
        Json value;
        try {
            value = parseJsonText(std::string(line), path);
        } catch (const InputError& e) {
            throw InputError(path, InputError::Where::Line, number, e.message());
        }
        if (!value.is_object())
            throw InputError(path, InputError::Where::Line, number,
                             "expected a JSON object with \"op\" or \"expect\"");
        const bool isOp = value.contains("op"), isExpect = value.contains("expect");
        if (isOp == isExpect)
            throw InputError(path, InputError::Where::Line, number,
                             "a line needs exactly one of \"op\" or \"expect\"");
        const Json& name = isOp ? value["op"] : value["expect"];
        if (!name.is_string())
            throw InputError(path, InputError::Where::Line, number,
                             std::string("\"") + (isOp ? "op" : "expect") + "\" must be a string");
        if (isOp && !session.knowsOp(name.get<std::string>()))
            throw InputError(path, InputError::Where::Line, number,
                             "unknown op \"" + name.get<std::string>() + "\"");
        if (isExpect && !isKnownExpectation(name.get<std::string>()))
            throw InputError(path, InputError::Where::Line, number,
                             "unknown expectation \"" + name.get<std::string>() + "\"");
        lines.push_back({number, std::move(value), isExpect});
    }
    return lines;
}

std::optional<std::string> checkExpectation(Session& s, const Json& e) {
    const std::string kind = e["expect"].get<std::string>();
    if (kind == "visible_count") {
        args::onlyFields(e, {"expect", "equals"});
        return mismatch(args::require(e, "equals"), s.visibility().visibleCount);
    }
    if (kind == "frame") {
        args::onlyFields(e, {"expect", "equals"});
        return mismatch(args::require(e, "equals"), s.state().frame);
    }
    if (kind == "fault_count") {
        args::onlyFields(e, {"expect", "equals"});
        return mismatch(args::require(e, "equals"), s.state().faults.size());
    }
    if (kind == "fault_size") {
        args::onlyFields(e, {"expect", "name", "equals"});
        const std::string name = args::string(e, "name");
        const Fault* f = s.state().fault(name);
        if (!f)
            return "expected fault \"" + name + "\" to exist, actual: no such fault";
        return mismatch(args::require(e, "equals"), f->ids.size());
    }
    if (kind == "histogram") {
        args::onlyFields(e, {"expect", "variable", "of", "bins", "range", "counts"});
        auto frame = s.currentFrame();
        if (!frame)
            return std::string("expected a histogram, actual: no data open");
        const std::string variable = args::string(e, "variable");
        const std::string of = args::optionalString(e, "of").value_or("all");
        if (of != "all" && of != "visible")
            throw CommandError("histogram: \"of\" must be all or visible");
        HistogramSpec spec;
        spec.bins = static_cast<int>(args::optionalInteger(e, "bins").value_or(0));
        if (e.contains("range")) {
            const Json& r = e["range"];
            if (!r.is_array() || r.size() != 2 || !r[0].is_number() || !r[1].is_number())
                throw CommandError("histogram: \"range\" must be [low, high]");
            spec.range = std::array<double, 2>{r[0].get<double>(), r[1].get<double>()};
        }
        const auto& mask = s.visibility().mask;
        auto h = computeHistogram(*frame, variable, spec, of == "visible" ? &mask : nullptr);
        if (!h)
            return "expected a histogram of \"" + variable +
                   "\", actual: the frame has no such variable";
        const auto& counts = of == "visible" ? h->visible.bins : h->all.bins;
        return mismatch(args::require(e, "counts"), counts);
    }
    if (kind == "file_exists") {
        args::onlyFields(e, {"expect", "path"});
        const std::string p = s.outputPath(args::string(e, "path"));
        std::error_code ec;
        if (fs::exists(p, ec) && fs::file_size(p, ec) > 0)
            return std::nullopt;
        return "expected file " + p +
               " to exist and be non-empty, actual: " + (fs::exists(p, ec) ? "empty" : "missing");
    }
    if (kind == "image") {
        args::onlyFields(e, {"expect", "path", "reference", "max_mean_abs_diff",
                             "max_differing_pixels", "min_ssim"});
        return imageFileMismatch(s.outputPath(args::string(e, "path")),
                                 s.inputPath(args::string(e, "reference")),
                                 args::optionalNumber(e, "max_mean_abs_diff").value_or(2.0),
                                 args::optionalInteger(e, "max_differing_pixels"),
                                 args::optionalNumber(e, "min_ssim").value_or(kDefaultMinSsim));
    }
    throw CommandError("unknown expectation \"" + kind + "\"");
}

namespace {

// What the session's thresholds, colourings and surface colours name that the current frame
// lacks, each said once ("threshold on 'strian': no variable 'strian' in this data; did you
// mean 'strain'?").
std::vector<std::string> missingVariables(Session& session, std::set<std::string>& warned) {
    std::vector<std::string> out;
    const auto frame = session.currentFrame();
    if (!frame)
        return out;
    auto check = [&](const std::string& what, const std::string& variable) {
        if (variable.empty() || variable == "faults" || !warned.insert(variable).second)
            return;
        std::string note = missingVariableNote(*frame, variable);
        if (note.empty())
            warned.erase(variable); // present: say it if it goes missing later
        else
            out.push_back(what + " '" + variable + "': " + note);
    };
    for (const auto& t : session.state().thresholds)
        check("threshold on", t.variable);
    for (const auto& v : session.state().views)
        if (v.difference.mode != ColorDifference::Mode::Displacement)
            check("view " + v.name + " coloured by", v.colorVariable);
    for (const auto& st : session.state().surfaces)
        check("surface of " + st.fault + " coloured by", st.colorBy);
    return out;
}

} // namespace

ReplayReport replayJournal(const std::string& path, const ReplayOptions& options,
                           Session& session) {
    const std::string text = readFileBytes(path);
    const auto lines = parseJournal(text, path, session); // everything checked before running
    const std::string folder = fs::absolute(fs::path(path)).parent_path().string();
    session.setBaseDir(folder);
    if (!options.outDir.empty())
        session.setOutputDir(fs::absolute(options.outDir).string());
    std::vector<std::string> data;
    for (const auto& d : options.data)
        data.push_back(fs::absolute(d).string());
    session.setDataOverride(data);
    session.setFrameSelection(options.frames);

    ReplayReport report;
    std::set<std::string> warned; // each missing variable said once
    for (const auto& line : lines) {
        try {
            if (line.isExpectation) {
                ++report.expectations;
                if (auto failure = checkExpectation(session, line.value))
                    report.failures.push_back(
                        {line.line,
                         "expect " + line.value["expect"].get<std::string>() + ": " + *failure});
            } else {
                ++report.commands;
                session.apply(line.value);
                if (!session.lastNote().empty()) // what the op wants said ("no faults made: ...")
                    report.warnings.push_back({line.line, session.lastNote()});
                for (auto& note : missingVariables(session, warned)) {
                    if (options.strict) {
                        report.failures.push_back({line.line, note + " (--strict)"});
                        report.stopped = true;
                    } else {
                        report.warnings.push_back({line.line, std::move(note)});
                    }
                }
                if (report.stopped)
                    break;
            }
        } catch (const std::exception& e) {
            report.failures.push_back({line.line, e.what()});
            if (!line.isExpectation) {
                report.stopped = true;
                break;
            }
        }
    }
    return report;
}

} // namespace faultline::core
