// `casmap simulate` (+ `casmap map`): runs the built binary on a small scene (flat floor and
// one box) on the table rig and checks the run file and the maps made from it.
#include <gtest/gtest.h>
#include <sys/wait.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include "casmap/io/run_file.hpp"
#include "tests/apps/cli_runner.hpp"
#include "tests/temp_dir.hpp"

namespace casmap {
namespace {
namespace fs = std::filesystem;

using test::Casmap;
using test::Result;

/// Simulator builds list `simulate` among the subcommands (CLI11 answers `casmap X --help` with
/// the main help and status 0 even when X is unknown, so that cannot tell).
bool HaveSimulator() { return Casmap("--help").output.find("\n  simulate ") != std::string::npos; }

std::string ReadBytes(const fs::path& path) {
    std::ifstream in(path, std::ios::binary);
    return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

// Box top 0.3 m over x in [3.3, 3.7], y in [0.1, 0.5]: rows 92..108, cols 44..60 of the
// course grid (x0 = 1, y0 = -1, 25 mm).
constexpr double kBoxTopM = 0.3;

fs::path MakeScene(const std::string& name) {
    const fs::path dir = casmap::test::MakeTempDir("sim_cmd_" + name);
    std::ofstream(dir / "scene.yaml") << R"(objects:
  - name: floor
    box: {size_m: [14, 8, 0.02]}
    pose: {xyz_m: [3, 0, -0.01], rpy_deg: [0, 0, 0]}
    reflectivity: 0.3
    terrain: true
  - name: box
    box: {size_m: [0.4, 0.4, 0.3]}
    pose: {xyz_m: [3.5, 0.3, 0.15], rpy_deg: [0, 0, 0]}
    reflectivity: 0.6
)";
    return dir;
}

TEST(SimulateCommand, FlatFloorAndBoxMapAndAreByteIdenticalAcrossThreads) {
    if (!HaveSimulator()) {
        GTEST_SKIP() << "built without the simulator";
    }
    const fs::path dir = MakeScene("floor");
    const std::string scene = (dir / "scene.yaml").string();
    Result r = Casmap("simulate --scene " + scene + " --motion T --seed 7 --threads 1 --out " +
                      (dir / "a.h5").string());
    ASSERT_EQ(r.code, 0) << r.output;
    r = Casmap("simulate --scene " + scene + " --motion T --seed 7 --threads 2 --out " +
               (dir / "b.h5").string());
    ASSERT_EQ(r.code, 0) << r.output;
    EXPECT_TRUE(ReadBytes(dir / "a.h5") == ReadBytes(dir / "b.h5"))
        << "same seed, 1 vs 2 threads: run files differ";
    EXPECT_TRUE(fs::exists(dir / "a.h5.config.yaml"));

    const io::RunData run = io::ReadRunFile(dir / "a.h5");
    EXPECT_EQ(run.seed, 7U);
    EXPECT_NE(run.config_yaml.find("motion: T"), std::string::npos);
    ASSERT_GT(run.scans.size(), 300U);  // 75 scans/s over a 5 m course at 1 m/s
    EXPECT_EQ(run.truth.size(), run.scans.size());
    EXPECT_EQ(run.scans[0].beams.size(), 181U);
    ASSERT_TRUE(run.maps.truth_m.has_value());
    EXPECT_EQ(run.maps.grid->rows, 200);
    EXPECT_EQ(run.maps.grid->cols, 80);
    EXPECT_FLOAT_EQ(run.maps.truth_m->at(100, 52), static_cast<float>(kBoxTopM));
    EXPECT_FLOAT_EQ(run.maps.truth_m->at(20, 20), 0.0F);

    r = Casmap("map " + (dir / "a.h5").string() + " --out " + (dir / "maps").string());
    ASSERT_EQ(r.code, 0) << r.output;
    const io::RunMaps maps = io::ReadRunMaps(dir / "a.h5");
    ASSERT_TRUE(maps.elevation_m && maps.certainty);
    const core::MapF& h = *maps.elevation_m;
    const core::MapF& c = *maps.certainty;
    // Floor far from the box: swept cells have certainty; elevations within the noise of 0.
    std::vector<float> floor;
    int seen = 0;
    int cells = 0;
    for (int row = 10; row < 80; ++row) {
        for (int col = 10; col < 70; ++col) {
            ++cells;
            if (c.at(row, col) > 0.0F) {
                ++seen;
                floor.push_back(std::abs(h.at(row, col)));
            }
        }
    }
    EXPECT_GT(seen, cells / 2);
    std::sort(floor.begin(), floor.end());
    ASSERT_FALSE(floor.empty());
    EXPECT_LT(floor[floor.size() / 2], 0.01F) << "median |h| on the floor";
    EXPECT_LT(floor[floor.size() * 95 / 100], 0.04F) << "95th percentile |h| on the floor";
    // Box top inner cells: seen, at the box height.
    std::vector<float> top;
    for (int row = 95; row < 106; ++row) {
        for (int col = 47; col < 58; ++col) {
            if (c.at(row, col) > 0.0F) {
                top.push_back(h.at(row, col));
            }
        }
    }
    ASSERT_GT(top.size(), 40U);
    std::sort(top.begin(), top.end());
    EXPECT_NEAR(top[top.size() / 2], kBoxTopM, 0.01);
}

TEST(SimulateCommand, BadInputExitsTwoNamingIt) {
    if (!HaveSimulator()) {
        GTEST_SKIP() << "built without the simulator";
    }
    const fs::path dir = MakeScene("bad");
    const std::string scene = (dir / "scene.yaml").string();
    const std::string out = " --out " + (dir / "run.h5").string();
    struct Case {
        std::string args;
        std::string needle;
    };
    std::ofstream(dir / "rig.yaml") << "table:\n  speed_m_s: 0.5\n  sped: 1\n";
    std::ofstream(dir / "flat.yaml") << "objects:\n  - name: box\n    box: {size_m: [1, 1, 1]}\n"
                                        "    pose: {xyz_m: [3, 0, 0.5]}\n";
    const std::vector<Case> cases = {
        {"simulate --scene " + scene + " --motion X" + out, "--motion"},
        {"simulate --scene " + scene + " --motion T --speed 1.5" + out, "--speed"},
        {"simulate --scene " + scene + " --motion T --rig " + (dir / "rig.yaml").string() + out,
         "sped"},
        {"simulate --scene " + (dir / "flat.yaml").string() + " --motion vehicle" + out, "terrain"},
        {"simulate --scene " + scene + " --motion T --pose-error jitter=1" + out, "--pose-error"},
        {"simulate --scene " + scene + " --motion T --out /nonexistent_dir/run.h5",
         "/nonexistent_dir"},
        {"simulate --scene " + (dir / "none.yaml").string() + " --motion T" + out, "none.yaml"},
    };
    for (const Case& c : cases) {
        const Result r = Casmap(c.args);
        EXPECT_EQ(r.code, 2) << c.args << "\n" << r.output;
        EXPECT_NE(r.output.find(c.needle), std::string::npos) << c.args << "\n" << r.output;
    }
    EXPECT_FALSE(fs::exists(dir / "run.h5"));
}

// An error inside a file names the file's field, never the flag of the options field with the
// same name (`speed_m_s` is also the field --speed sets).
TEST(SimulateCommand, RigFileErrorNamesTheYamlFieldNotAFlag) {
    if (!HaveSimulator()) {
        GTEST_SKIP() << "built without the simulator";
    }
    const fs::path dir = MakeScene("dup");
    const std::string rig = (dir / "rig.yaml").string();
    std::ofstream(rig) << "table:\n  speed_m_s: 0.5\n  speed_m_s: 0.6\n";
    const Result r = Casmap("simulate --scene " + (dir / "scene.yaml").string() +
                            " --motion T --rig " + rig + " --out " + (dir / "run.h5").string());
    EXPECT_EQ(r.code, 2) << r.output;
    EXPECT_NE(r.output.find(rig + ":3:3: speed_m_s (duplicate key)"), std::string::npos)
        << r.output;
    EXPECT_EQ(r.output.find("--speed"), std::string::npos) << r.output;
}

TEST(SimulateCommand, KilledRunLeavesNoTruncatedFile) {
    if (!HaveSimulator()) {
        GTEST_SKIP() << "built without the simulator";
    }
    const fs::path dir = MakeScene("killed");
    const fs::path run = dir / "run.h5";
    // Killed at some point of its work: either no file under the final name, or a complete one.
    const std::string cmd = "timeout -s KILL 0.3 " + std::string(CASMAP_EXE) +
                            " simulate --scene " + (dir / "scene.yaml").string() +
                            " --motion TRP --threads 1 --out " + run.string() + " >/dev/null 2>&1";
    (void)std::system(cmd.c_str());
    if (fs::exists(run)) {
        EXPECT_NO_THROW((void)io::ReadRunFile(run));
    }
    SUCCEED() << (fs::exists(run) ? "finished before the kill" : "killed: no run file");
}

}  // namespace
}  // namespace casmap
