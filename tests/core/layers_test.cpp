// Layers of the source tree: the folders of core/ (and of ui/) include each other one way only,
// never round a circle, and core/ includes no GL, GLFW or ImGui. Read from the sources
// themselves, so a wrong-way include fails here, naming the file and line that brought it.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <functional>
#include <map>
#include <regex>
#include <set>
#include <string>
#include <vector>

namespace {

namespace fs = std::filesystem;

fs::path sourceRoot() { return fs::path(FAULTLINE_TEST_DATA).parent_path().parent_path(); }

struct Include {
    std::string file;
    int line = 0;
};

// Folder -> folder it includes -> the first include that does it.
using FolderGraph = std::map<std::string, std::map<std::string, Include>>;

FolderGraph folderGraph(const std::string& top, std::vector<Include>* forbidden = nullptr) {
    FolderGraph graph;
    const std::regex include("#\\s*include\\s*[\"<]([^\">]+)[\">]");
    const std::regex gui("^(GL/|GLFW/|epoxy/|imgui)");
    for (const auto& entry : fs::recursive_directory_iterator(sourceRoot() / top)) {
        const std::string ext = entry.path().extension().string();
        if (!entry.is_regular_file() || (ext != ".cpp" && ext != ".hpp" && ext != ".h"))
            continue;
        const fs::path rel = fs::relative(entry.path(), sourceRoot() / top);
        if (rel.begin() == rel.end() || std::next(rel.begin()) == rel.end())
            continue; // a file directly in top/
        const std::string folder = rel.begin()->string();
        std::ifstream in(entry.path());
        std::string text;
        int number = 0;
        while (std::getline(in, text)) {
            ++number;
            std::smatch m;
            if (!std::regex_search(text, m, include))
                continue;
            const std::string target = m[1];
            const std::string where = (fs::path(top) / rel).string();
            if (forbidden && std::regex_search(target, gui))
                forbidden->push_back({where + " includes " + target, number});
            const std::string prefix = top + "/";
            if (target.rfind(prefix, 0) != 0)
                continue;
            const std::string rest = target.substr(prefix.size());
            const std::size_t slash = rest.find('/');
            if (slash == std::string::npos)
                continue;
            const std::string other = rest.substr(0, slash);
            if (other != folder && !graph[folder].count(other))
                graph[folder][other] = {where, number};
        }
    }
    return graph;
}

// Pairs of folders that reach each other ("a<->b", a < b), each with one include of each way.
std::map<std::string, std::string> cycles(const FolderGraph& graph) {
    auto reaches = [&](const std::string& from, const std::string& to) {
        std::set<std::string> seen;
        std::vector<std::string> stack{from};
        while (!stack.empty()) {
            const std::string at = stack.back();
            stack.pop_back();
            auto it = graph.find(at);
            if (it == graph.end())
                continue;
            for (const auto& [next, where] : it->second) {
                if (next == to)
                    return true;
                if (seen.insert(next).second)
                    stack.push_back(next);
            }
        }
        return false;
    };
    std::map<std::string, std::string> found;
    for (const auto& [a, targets] : graph)
        for (const auto& [b, where] : targets)
            if (reaches(b, a)) {
                const std::string key = a < b ? a + "<->" + b : b + "<->" + a;
                found[key] +=
                    where.file + ":" + std::to_string(where.line) + " (" + a + " -> " + b + ") ";
            }
    return found;
}

} // namespace

TEST(Layers, CoreFoldersIncludeEachOtherOneWayOnly) {
    std::vector<Include> gui;
    const FolderGraph graph = folderGraph("core", &gui);
    ASSERT_GT(graph.size(), 5u) << "no sources found under " << (sourceRoot() / "core");
    for (const auto& [pair, where] : cycles(graph))
        ADD_FAILURE() << "core/ folders include each other: " << pair << ": " << where;
    for (const Include& g : gui)
        ADD_FAILURE() << "core/ must stay free of GL, GLFW and ImGui: " << g.file << ":" << g.line;
}

TEST(Layers, UiFoldersIncludeEachOtherOneWayOnly) {
    // widgets, render < dock, viewport < context < panels < workbench < app: panels draw with
    // the PanelContext interface, which the workbench implements (README, "Code map").
    const FolderGraph graph = folderGraph("ui");
    ASSERT_GT(graph.size(), 3u);
    for (const auto& [pair, where] : cycles(graph))
        ADD_FAILURE() << "ui/ folders include each other: " << pair << ": " << where;
}

// Files of more than 500 lines open with an index of their sections ("// Index of this file:"
// then a "// [SECTION] title" line per section, as imgui_demo.cpp does) and carry a marker per
// section in that order, so a reader can jump between them (issue 39).
TEST(Layers, LongFilesOpenWithAnIndexOfTheirSections) {
    std::vector<std::string> problems;
    for (const char* top : {"app", "core", "ui"})
        for (const auto& entry : fs::recursive_directory_iterator(sourceRoot() / top)) {
            if (!entry.is_regular_file() || entry.path().extension() != ".cpp")
                continue;
            std::ifstream in(entry.path());
            std::vector<std::string> lines;
            for (std::string text; std::getline(in, text);)
                lines.push_back(text);
            if (lines.size() <= 500)
                continue;
            const std::string name = fs::relative(entry.path(), sourceRoot()).string();
            std::vector<std::string> index, markers;
            bool inIndex = false;
            const std::string tag = "// [SECTION] ";
            for (std::size_t i = 0; i < lines.size(); ++i) {
                const std::string& l = lines[i];
                const std::size_t at = l.find(tag);
                if (l.rfind("// Index of this file:", 0) == 0) {
                    inIndex = true;
                } else if (inIndex && l.rfind(tag, 0) == 0) {
                    index.push_back(l.substr(tag.size()));
                } else {
                    inIndex = false;
                    if (at != std::string::npos && l.find_first_not_of(' ') == at)
                        markers.push_back(l.substr(at + tag.size()));
                }
            }
            if (index.size() < 2)
                problems.push_back(name + ": " + std::to_string(lines.size()) +
                                   " lines and no index of at least two sections");
            else if (index != markers)
                problems.push_back(name + ": its index and its [SECTION] markers differ");
        }
    EXPECT_TRUE(problems.empty()) << [&] {
        std::string all;
        for (const auto& p : problems)
            all += p + "\n";
        return all;
    }();
}
