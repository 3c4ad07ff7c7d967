#include "core/synth/demo_model.hpp"

#include "core/synth/dump_writer.hpp"

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <system_error>

#include <unistd.h>

namespace faultline::core {

namespace {

namespace fs = std::filesystem;

// Bump when the demo's options change, so older demos are rebuilt.
constexpr const char* kDumpName = "block-v2.lammpstrj.gz";
constexpr const char* kInfoName = "block-v2.json";

fs::path dataHome() {
    if (const char* xdg = std::getenv("XDG_DATA_HOME"); xdg && *xdg && fs::path(xdg).is_absolute())
        return fs::path(xdg);
    if (const char* home = std::getenv("HOME"); home && *home)
        return fs::path(home) / ".local" / "share";
    throw std::runtime_error("cannot find the data folder: neither XDG_DATA_HOME nor HOME is set");
}

} // namespace

std::string demoModelFolder() { return (dataHome() / "faultline" / "demo").string(); }

std::optional<std::string> existingDemoModel() {
    const fs::path folder = demoModelFolder();
    std::error_code ec;
    // The info file is written last, so its presence marks a complete demo.
    if (fs::is_regular_file(folder / kInfoName, ec) && fs::is_regular_file(folder / kDumpName, ec))
        return (folder / kDumpName).string();
    return std::nullopt;
}

std::string ensureDemoModel(const ProgressCallback& progress) {
    if (auto path = existingDemoModel())
        return *path;
    const fs::path folder = demoModelFolder();
    const fs::path parent = folder.parent_path();
    fs::create_directories(parent);
    const fs::path temp = parent / ("demo.partial-" + std::to_string(::getpid()));
    std::error_code ec;
    fs::remove_all(temp, ec);
    fs::create_directories(temp);
    try {
        const ExtensionModelOptions options = extensionDemoOptions();
        LammpsDumpWriter writer((temp / kDumpName).string(), 1);
        const ExtensionRunStats stats = runExtensionModel(
            options, [&](const Frame& f, int) { writer.write(f, extensionDumpColumns()); },
            progress);
        writer.close();
        std::ofstream info(temp / kInfoName, std::ios::binary);
        info << describeExtensionRun(options, stats) << '\n';
        info.close();
        if (!info)
            throw std::runtime_error((temp / kInfoName).string() + ": write failed");
    } catch (...) {
        fs::remove_all(temp, ec);
        throw;
    }
    // An older or incomplete demo moves aside first; rename() then puts ours in place at once.
    if (fs::exists(folder, ec)) {
        const fs::path old = parent / ("demo.old-" + std::to_string(::getpid()));
        fs::remove_all(old, ec);
        fs::rename(folder, old, ec);
        if (ec) {
            // Another process may have just finished its demo: use it when it is complete.
            fs::remove_all(temp, ec);
            if (auto path = existingDemoModel())
                return *path;
            throw std::runtime_error("cannot replace " + folder.string());
        }
        fs::remove_all(old, ec);
    }
    fs::rename(temp, folder, ec);
    if (ec) {
        fs::remove_all(temp, ec);
        if (auto path = existingDemoModel())
            return *path;
        throw std::runtime_error("cannot move the demo into " + folder.string() + ": " +
                                 ec.message());
    }
    return (folder / kDumpName).string();
}

} // namespace faultline::core
