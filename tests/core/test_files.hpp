// Helpers for tests that write small files: a private temp folder per test, removed after.
#pragma once

#include "core/io/input_error.hpp"

#include <gtest/gtest.h>

#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

namespace faultline::test {

class TempDir {
  public:
    TempDir() {
        const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
        m_path = std::filesystem::temp_directory_path() /
                 ("faultline-test-" + std::string(info->test_suite_name()) + "-" + info->name() +
                  "-" + std::to_string(::getpid()));
        std::filesystem::remove_all(m_path);
        std::filesystem::create_directories(m_path);
    }
    ~TempDir() { std::filesystem::remove_all(m_path); }
    std::string file(const std::string& name) const { return (m_path / name).string(); }
    std::string write(const std::string& name, const std::string& content) const {
        const std::string p = file(name);
        std::filesystem::create_directories(std::filesystem::path(p).parent_path());
        std::ofstream(p, std::ios::binary) << content;
        return p;
    }
    const std::filesystem::path& path() const { return m_path; }

  private:
    std::filesystem::path m_path;
};

// The message of the InputError that `f` throws, or "" when it throws none.
template <typename F> std::string inputErrorOf(F f) {
    try {
        f();
    } catch (const faultline::core::InputError& e) {
        return e.what();
    }
    return "";
}

// The whole content of a file, "" when it cannot be read.
inline std::string slurp(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    std::ostringstream s;
    s << in.rdbuf();
    return s.str();
}

inline std::string dataFile(const std::string& name) {
    return std::string(FAULTLINE_TEST_DATA) + "/" + name;
}

// A real run's fixture (tests/data/real_runs).
inline std::string realRunFile(const std::string& name) { return dataFile("real_runs/" + name); }

} // namespace faultline::test
