#include "casmap/pipeline/data_dir.hpp"

#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>

#include "casmap/core/input_error.hpp"
#include "tests/temp_dir.hpp"

namespace casmap::pipeline {
namespace {
namespace fs = std::filesystem;

/// Sets CASMAP_DATA_DIR for one test and restores the previous state.
class ScopedDataDirEnv {
public:
    explicit ScopedDataDirEnv(const std::string& value) {
        if (const char* old = std::getenv("CASMAP_DATA_DIR")) {
            old_ = old;
            had_ = true;
        }
        setenv("CASMAP_DATA_DIR", value.c_str(), 1);
    }
    ~ScopedDataDirEnv() {
        if (had_) {
            setenv("CASMAP_DATA_DIR", old_.c_str(), 1);
        } else {
            unsetenv("CASMAP_DATA_DIR");
        }
    }

private:
    std::string old_;
    bool had_ = false;
};

TEST(DataDir, InTreeBuildFindsTheSourceTree) {
    unsetenv("CASMAP_DATA_DIR");
    // The test binary is not installed, so the source tree is the answer.
    EXPECT_EQ(fs::canonical(DataDir()), fs::canonical(CASMAP_SOURCE_DIR));
    EXPECT_TRUE(fs::is_regular_file(CoursesDir() / "course01.yaml"));
}

TEST(DataDir, EnvironmentWins) {
    const casmap::test::TempDir tmp("data_dir_test");
    const fs::path& dir = tmp.Path();
    fs::create_directories(dir / "scenes" / "courses");
    const ScopedDataDirEnv env(dir.string());
    EXPECT_EQ(DataDir(), dir);
    EXPECT_EQ(CoursesDir(), dir / "scenes" / "courses");
}

TEST(DataDir, EnvironmentWithoutScenesIsAnInputErrorNamingIt) {
    const ScopedDataDirEnv env("/nonexistent/casmap");
    EXPECT_FALSE(FindDataDir().has_value());
    try {
        (void)DataDir();
        FAIL() << "expected InputError";
    } catch (const InputError& e) {
        EXPECT_EQ(e.field(), "CASMAP_DATA_DIR");
        EXPECT_NE(std::string(e.what()).find("/nonexistent/casmap"), std::string::npos);
    }
}

}  // namespace
}  // namespace casmap::pipeline
