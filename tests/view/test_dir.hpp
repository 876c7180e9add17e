#pragma once

// A fresh temporary folder per test (unique, removed when the test process exits).

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "tests/temp_dir.hpp"

namespace casmap::view::test {

inline std::filesystem::path FreshDir(const std::string& name) {
    // Unique per call (mkdtemp): two test runs at once never share it; removed at exit.
    return std::filesystem::canonical(casmap::test::MakeTempDir("view_" + name));
}

inline void WriteText(const std::filesystem::path& path, const std::string& text) {
    std::filesystem::create_directories(path.parent_path());
    std::ofstream(path, std::ios::binary) << text;
}

}  // namespace casmap::view::test
