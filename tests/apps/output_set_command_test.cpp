// A command's outputs are one set (issue #13, item 4): every output path is checked before any
// work, and a command that fails leaves no partial set and no temporaries behind.
#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "tests/apps/cli_runner.hpp"

namespace casmap::test {
namespace {
namespace fs = std::filesystem;
using ::testing::HasSubstr;

fs::path FreshDir(const std::string& name) {
    const fs::path dir =
        fs::path(testing::TempDir()) / ("casmap_outputs_" + std::to_string(getpid()) + "_" + name);
    fs::remove_all(dir);
    fs::create_directories(dir);
    return dir;
}

int Entries(const fs::path& dir) {
    return static_cast<int>(std::distance(fs::directory_iterator(dir), fs::directory_iterator()));
}

bool HaveSimulator() { return Casmap("simulate").output.find("--scene") != std::string::npos; }

const std::string kScene = std::string(CASMAP_SOURCE_DIR) + "/scenes/indoor.yaml";
const std::string kRun = std::string(CASMAP_SOURCE_DIR) + "/tests/data/fuzz/run_file/seed_2x5.h5";

TEST(OutputSetCommand, SimulateWithABlockedConfigNameWritesNoRun) {
    if (!HaveSimulator()) {
        GTEST_SKIP() << "built without the simulator";
    }
    const fs::path dir = FreshDir("simulate");
    fs::create_directories(dir / "r.h5.config.yaml");  // the config cannot be written
    const Result r =
        Casmap("simulate --scene " + kScene + " --motion T --out " + (dir / "r.h5").string());
    EXPECT_EQ(r.code, 2) << r.output;
    EXPECT_THAT(r.output, HasSubstr("r.h5.config.yaml: --out (config) (is a folder"));
    EXPECT_FALSE(fs::exists(dir / "r.h5"));
    EXPECT_EQ(Entries(dir), 1);
}

TEST(OutputSetCommand, TruthWithAPngInAMissingFolderWritesNoTiff) {
    if (!HaveSimulator()) {
        GTEST_SKIP() << "built without the simulator";
    }
    const fs::path dir = FreshDir("truth");
    const Result r =
        Casmap("truth --scene " + kScene + " --grid 0,0,0.1,10,10 --out " +
               (dir / "t.tiff").string() + " --png " + (dir / "missing" / "t.png").string());
    EXPECT_EQ(r.code, 2) << r.output;
    EXPECT_THAT(r.output, HasSubstr("--png"));
    EXPECT_EQ(Entries(dir), 0);
}

TEST(OutputSetCommand, MapWhoseOutputFolderIsAFileLeavesTheRunUntouched) {
    const fs::path dir = FreshDir("map");
    fs::copy_file(kRun, dir / "r.h5");
    const auto size = fs::file_size(dir / "r.h5");
    std::ofstream(dir / "maps") << "a file, not a folder";
    const Result r = Casmap("map " + (dir / "r.h5").string() + " --out " + (dir / "maps").string());
    EXPECT_EQ(r.code, 2) << r.output;
    EXPECT_THAT(r.output, HasSubstr("--out"));
    EXPECT_EQ(fs::file_size(dir / "r.h5"), size);  // no maps added to the run
    EXPECT_EQ(Entries(dir), 2);
}

TEST(OutputSetCommand, MapPublishesTheMapsAndTheRunAndSweepsStaleTemporaries) {
    const fs::path dir = FreshDir("map_ok");
    fs::copy_file(kRun, dir / "r.h5");
    fs::create_directories(dir / "maps");
    // A temporary of a killed earlier run (PID 1 is init and never ours; use a dead PID).
    const std::string stale = ".elevation.tiff.tmp" + std::to_string(0x7ffffffe);
    std::ofstream(dir / "maps" / stale) << "partial";
    const Result r = Casmap("map " + (dir / "r.h5").string() + " --out " + (dir / "maps").string());
    EXPECT_EQ(r.code, 0) << r.output;
    EXPECT_TRUE(fs::exists(dir / "maps" / "elevation.tiff"));
    EXPECT_TRUE(fs::exists(dir / "maps" / "map.yaml"));
    EXPECT_FALSE(fs::exists(dir / "maps" / stale));
    EXPECT_EQ(Entries(dir), 2);  // r.h5 and maps/: no temporary left beside the run
}

TEST(OutputSetCommand, BenchWithABadSetCreatesNothing) {
    if (!HaveSimulator()) {
        GTEST_SKIP() << "built without the simulator";
    }
    const fs::path dir = FreshDir("bench");
    const Result r =
        Casmap("bench --courses 4 --tests T --set nonsense=1 --out " + (dir / "b").string());
    EXPECT_EQ(r.code, 2) << r.output;
    EXPECT_EQ(Entries(dir), 0);
}

TEST(OutputSetCommand, BenchRefusesToReplaceAFolderThatIsNotABenchOutput) {
    if (!HaveSimulator()) {
        GTEST_SKIP() << "built without the simulator";
    }
    const fs::path dir = FreshDir("bench_foreign");
    std::ofstream(dir / "notes.txt") << "mine";
    const Result r = Casmap("bench --courses 4 --tests T --out " + dir.string());
    EXPECT_EQ(r.code, 2) << r.output;
    EXPECT_THAT(r.output, HasSubstr("no bench.json"));
    EXPECT_TRUE(fs::exists(dir / "notes.txt"));
}

}  // namespace
}  // namespace casmap::test
