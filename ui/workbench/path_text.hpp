// Small path and file-name helpers the workbench's parts share.
#pragma once

#include <ctime>
#include <filesystem>
#include <string>

namespace faultline::ui {

// "20261129-163257": for file names made up for the user (screenshots, journals).
inline std::string timestampForFile() {
    const std::time_t t = std::time(nullptr);
    char buf[32];
    std::strftime(buf, sizeof buf, "%Y%m%d-%H%M%S", std::localtime(&t));
    return buf;
}

// The folder of `path` ("" for ""): where a file dialog opens.
inline std::string folderOf(const std::string& path) {
    if (path.empty())
        return {};
    return std::filesystem::path(path).parent_path().string();
}

// `path` made absolute and normal (unchanged when that fails).
inline std::string absolutePath(const std::string& path) {
    std::error_code ec;
    auto p = std::filesystem::absolute(path, ec);
    return ec ? path : p.lexically_normal().string();
}

} // namespace faultline::ui
