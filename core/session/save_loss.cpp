#include "core/session/save_loss.hpp"

#include "core/io/input_error.hpp"
#include "core/session/session_json.hpp"

#include <algorithm>
#include <filesystem>

namespace faultline::core {

namespace {

std::string withThousands(std::size_t n) {
    std::string digits = std::to_string(n), out;
    for (std::size_t i = 0; i < digits.size(); ++i) {
        if (i > 0 && (digits.size() - i) % 3 == 0)
            out += ',';
        out += digits[i];
    }
    return out;
}

std::string spheres(std::size_t n) { return withThousands(n) + (n == 1 ? " sphere" : " spheres"); }

std::string counted(std::size_t n, const char* one, const char* many) {
    return std::to_string(n) + " " + (n == 1 ? one : many);
}

} // namespace

std::vector<std::string> saveLoss(const SessionState& onDisk, const SessionState& next) {
    std::vector<std::string> lost;
    if (!onDisk.dataPaths.empty() && next.dataPaths.empty())
        lost.push_back("the data (" +
                       std::filesystem::path(onDisk.dataPaths.front()).filename().string() +
                       (onDisk.dataPaths.size() > 1 ? " and more" : "") + ")");
    std::vector<std::string> goneFaults;
    std::size_t goneMembers = 0, fewerMembers = 0;
    for (const Fault& old : onDisk.faults) {
        const Fault* now = next.fault(old.name);
        if (!now) {
            goneFaults.push_back(old.name);
            goneMembers += old.ids.size();
            continue;
        }
        for (std::int64_t id : old.ids)
            fewerMembers += now->contains(id) ? 0 : 1;
    }
    if (goneFaults.size() == 1)
        lost.push_back("fault " + goneFaults.front() + " (" + spheres(goneMembers) + ")");
    else if (goneFaults.size() > 1)
        lost.push_back(std::to_string(goneFaults.size()) + " faults (" + spheres(goneMembers) +
                       ")");
    if (fewerMembers > 0)
        lost.push_back(spheres(fewerMembers) + " of the remaining faults");
    auto missing = [](const auto& then, const auto& now, auto key) {
        std::size_t n = 0;
        for (const auto& a : then)
            n += std::none_of(now.begin(), now.end(),
                              [&](const auto& b) { return key(a) == key(b); })
                     ? 1
                     : 0;
        return n;
    };
    if (auto n = missing(onDisk.boxes, next.boxes, [](const CuttingBox& b) { return b.name; }))
        lost.push_back(counted(n, "cutting box", "cutting boxes"));
    if (auto n = missing(onDisk.thresholds, next.thresholds,
                         [](const VariableThreshold& t) { return t.variable; }))
        lost.push_back(counted(n, "threshold", "thresholds"));
    return lost;
}

std::vector<std::string> saveLossOverFile(const std::string& path, const SessionState& next) {
    std::error_code ec;
    if (!std::filesystem::exists(path, ec))
        return {};
    try {
        return saveLoss(loadSessionFile(path), next);
    } catch (const InputError& e) {
        return {"a file that is not a readable session (" + std::string(e.what()) + ")"};
    }
}

} // namespace faultline::core
