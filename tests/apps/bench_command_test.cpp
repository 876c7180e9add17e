// `casmap bench` and `casmap sweep`: run the built binary on obstacle course 4 and check the
// outputs' shape (h5py-free: the JSON is checked with /usr/bin/python3's json module),
// determinism across thread counts and the bad-input contract.
#include <gtest/gtest.h>
#include <sys/wait.h>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include "tests/apps/cli_runner.hpp"
#include "tests/temp_dir.hpp"

namespace casmap {
namespace {
namespace fs = std::filesystem;

using test::Result;
using test::Shell;

Result Casmap(const std::string& args) {
    return Shell(std::string(CASMAP_EXE) + " " + args + " --courses-dir " + CASMAP_SOURCE_DIR +
                 "/scenes/courses");
}

/// Simulator builds list `bench` among the subcommands (CLI11 answers `casmap X --help` with the
/// main help and status 0 even when X is unknown, so that cannot tell).
bool HaveSimulator() {
    return Shell(std::string(CASMAP_EXE) + " --help").output.find("\n  bench ") !=
           std::string::npos;
}

std::string ReadText(const fs::path& path) {
    std::ifstream in(path, std::ios::binary);
    return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

fs::path FreshDir(const std::string& name) {
    // A unique folder (mkdtemp), removed when the test process exits.
    return casmap::test::MakeTempDir("bench_cmd_" + name);
}

/// bench.json without the fields that legitimately vary (elapsed time, thread count).
std::string RunsPart(const std::string& json) {
    return json.substr(0, json.rfind("], \"elapsed_s\""));
}

TEST(BenchCommand, WritesEveryOutputInTheIssueShapeAndIsThreadIndependent) {
    if (!HaveSimulator()) {
        GTEST_SKIP() << "built without the simulator";
    }
    const fs::path dir = FreshDir("outputs");
    Result r = Casmap("bench --courses 4 --tests T,TRP --seed 3 --threads 1 --out " +
                      (dir / "a").string() + " --json " + (dir / "a.json").string());
    ASSERT_EQ(r.code, 0) << r.output;
    EXPECT_NE(r.output.find("cas"), std::string::npos) << "PI table on the terminal";
    for (const char* f :
         {"bench.json", "pi_chart.png", "table2.md", "pi_table.txt", "sheets/course04_T.png",
          "sheets/course04_TRP.png", "runs/course04_T.yaml", "runs/course04_TRP.yaml"}) {
        EXPECT_TRUE(fs::exists(dir / "a" / f)) << f;
    }
    EXPECT_EQ(ReadText(dir / "a.json"), ReadText(dir / "a" / "bench.json"));
    EXPECT_NE(ReadText(dir / "a" / "runs" / "course04_T.yaml").find("seed: 3"), std::string::npos);

    // The issue's shape, checked by an independent JSON parser.
    const std::string script = dir.string() + "/check.py";
    std::ofstream(script) << R"PY(
import json, sys
d = json.load(open(sys.argv[1]))
assert set(d) >= {"runs", "elapsed_s", "threads"}, d.keys()
assert len(d["runs"]) == 2
for r in d["runs"]:
    assert r["course"] == 4 and r["test"] in ("T", "TRP") and r["seed"] == 3
    assert set(r["filters"]) == {"cas", "wiener", "average", "median", "cwm"}
    for f in r["filters"].values():
        assert set(f) >= {"pi", "rmse_m", "spikes", "fill_error_m"}
        assert 0 < f["pi"] < 5 and f["rmse_m"] > 0 and f["spikes"] >= 0
    c = r["cas_classes_pct"]
    assert set(c) == {"mixed", "missing", "untouched"}, c
    assert abs(c["mixed"] + c["missing"] + c["untouched"] - 100) < 1e-6, c
print("ok")
)PY";
    r = Shell("/usr/bin/python3 " + script + " " + (dir / "a.json").string());
    EXPECT_EQ(r.code, 0) << r.output;

    r = Casmap("bench --courses 4 --tests T,TRP --seed 3 --threads 2 --no-sheets --out " +
               (dir / "b").string());
    ASSERT_EQ(r.code, 0) << r.output;
    EXPECT_EQ(RunsPart(ReadText(dir / "a" / "bench.json")),
              RunsPart(ReadText(dir / "b" / "bench.json")))
        << "bench figures depend on the thread count";
}

TEST(BenchCommand, BadInputExitsTwoWithOneLineAndNoJson) {
    if (!HaveSimulator()) {
        GTEST_SKIP() << "built without the simulator";
    }
    const fs::path dir = FreshDir("bad");
    const std::string json = " --json " + (dir / "x.json").string();
    struct Case {
        std::string args;
        std::string needle;
    };
    const std::vector<Case> cases = {
        {"bench --courses 0" + json, "--courses"},
        {"bench --courses 17" + json, "--courses"},
        {"bench --courses 9-3" + json, "inverted"},
        {"bench --tests T,XY" + json, "XY"},
        {"bench --set nope=1" + json, "nope"},
        {"bench --courses 4 --json /nonexistent_dir/b.json", "/nonexistent_dir"},
        {"sweep --set A=10:5:1", "inverted"},
        {"sweep --set A=1:5:0", "STEP"},
        {"sweep --set Q=1:5:1", "Q"},
        {"sweep --set B=1:x:1", "B=1:x:1"},
        {"sweep --courses 4 --tests Z", "--tests"},
        {"sweep --courses 4 --filter bogus", "--filter = bogus"},
        {"sweep --courses 4 --train-seeds 1-2 --test-seeds 2", "--test-seeds = seed 2, course 4"},
        {"sweep --courses 4 --train-seeds x", "--train-seeds = x"},
        {"sweep --courses 4 --grow 99", "--grow = 99"},
        {"sweep --courses 4 --test-courses 17", "--test-courses"},
        {"bench --pipelines cas,bogus" + json, "--pipelines"},
        {"bench --set shadow.min_angle_deg=95" + json, "shadow.min_angle_deg = 95"},
        {"bench --set range_jump.jump_min_m=0.04" + json, "range_jump.margin_m"},
        {"bench --set sweep_jump.max_angle_deg=-1" + json, "sweep_jump.max_angle_deg = -1"},
        {"sweep --courses 4 --set sweep_jump.margin_m=0.01:0.03:0.01",
         "does not run the sweep_jump"},
        {"sweep --courses 4 --set shadow.min_angle_deg=5:25:10", "does not run the shadow"},
        {"sweep --courses 4 --filter kalman_median --set kalman.mahalanobis_gate=0:1:1",
         "kalman.mahalanobis_gate"},
        {"bench --preset no_such_preset" + json, "--preset"},
        {"bench --preset " + (dir / "bad_preset.yaml").string() + json, "set.A"},
        {"bench --scenes /nonexistent/s.yaml" + json, "--scenes"},
        {"bench --scenes " + std::string(CASMAP_SOURCE_DIR) + "/scenes/outdoor.yaml --motion fly" +
             json,
         "--motion"},

    };
    std::ofstream(dir / "bad_preset.yaml") << "set:\n  A: -3\n";
    for (const Case& c : cases) {
        const Result r = Casmap(c.args + " --out " + (dir / "out").string());
        EXPECT_EQ(r.code, 2) << c.args << "\n" << r.output;
        EXPECT_NE(r.output.find(c.needle), std::string::npos) << c.args << "\n" << r.output;
        EXPECT_EQ(std::count(r.output.begin(), r.output.end(), '\n'), 1) << r.output;
    }
    EXPECT_FALSE(fs::exists(dir / "x.json"));
    EXPECT_FALSE(fs::exists(dir / "out" / "bench.json"));
    // casmap filter takes the same presets.
    const Result f = Shell(std::string(CASMAP_EXE) +
                           " filter --method cas --preset no_such_preset --elevation x.tiff "
                           "--out " +
                           (dir / "y.tiff").string());
    EXPECT_EQ(f.code, 2) << f.output;
    EXPECT_NE(f.output.find("--preset"), std::string::npos) << f.output;
}

// Named pipelines and a preset from the command line: the summary table is printed and
// written, bench.json holds every pipeline asked for, --set overrides the preset.
TEST(BenchCommand, PipelinesAndPresetsFromTheCommandLine) {
    if (!HaveSimulator()) {
        GTEST_SKIP() << "built without the simulator";
    }
    const fs::path dir = FreshDir("pipelines");
    std::ofstream(dir / "trial.yaml") << "description: test\nset:\n  A: 45\n  h_sum_min: 10\n";
    Result r = Casmap(
        "bench --courses 4 --tests T --no-sheets --threads 2 --pipelines "
        "raw,kalman,cas,range_jump_cas --maps --preset " +
        (dir / "trial.yaml").string() + " --set h_sum_min=9 --out " + (dir / "a").string());
    ASSERT_EQ(r.code, 0) << r.output;
    EXPECT_NE(r.output.find("# Pipelines side by side"), std::string::npos) << r.output;
    EXPECT_NE(r.output.find("| kalman |"), std::string::npos) << r.output;
    EXPECT_TRUE(fs::exists(dir / "a" / "pipelines.md"));
    // --maps writes every pipeline's map for casmap view (raw once).
    for (const char* f : {"raw.tif", "kalman.tif", "cas.tif", "range_jump_cas.tif", "maps.json"}) {
        EXPECT_TRUE(fs::exists(dir / "a" / "runs" / "course04_T" / f)) << f;
    }
    EXPECT_FALSE(fs::exists(dir / "a" / "runs" / "course04_T" / "median.tif"));
    const std::string yaml = ReadText(dir / "a" / "runs" / "course04_T.yaml");
    EXPECT_NE(yaml.find("A: 45"), std::string::npos) << yaml;
    EXPECT_NE(yaml.find("h_sum_min: 9"), std::string::npos) << yaml;
    EXPECT_NE(yaml.find("preset: "), std::string::npos) << yaml;
    const std::string json = ReadText(dir / "a" / "bench.json");
    for (const char* name : {"\"raw\"", "\"kalman\"", "\"cas\"", "\"range_jump_cas\""}) {
        EXPECT_NE(json.find(std::string(name) + ":{\"pi\""), std::string::npos) << name;
    }
    EXPECT_EQ(json.find("\"median\":{\"pi\""), std::string::npos);
    // The paper preset changes nothing.
    r = Casmap("bench --courses 4 --tests T --no-sheets --threads 1 --out " + (dir / "b").string());
    ASSERT_EQ(r.code, 0) << r.output;
    r = Casmap("bench --courses 4 --tests T --no-sheets --threads 1 --preset paper --out " +
               (dir / "c").string());
    ASSERT_EQ(r.code, 0) << r.output;
    EXPECT_EQ(RunsPart(ReadText(dir / "b" / "bench.json")),
              RunsPart(ReadText(dir / "c" / "bench.json")));

    // The outdoor scene on the vehicle through --scenes: NaN unknown, RMSE on observed cells.
    r = Casmap("bench --scenes " + std::string(CASMAP_SOURCE_DIR) +
               "/scenes/outdoor.yaml --pipelines raw,cas_trail --threads 2 --out " +
               (dir / "d").string());
    ASSERT_EQ(r.code, 0) << r.output;
    EXPECT_NE(r.output.find("## Scene outdoor_vehicle"), std::string::npos) << r.output;
    EXPECT_TRUE(fs::exists(dir / "d" / "runs" / "outdoor_vehicle.yaml"));
    EXPECT_TRUE(fs::exists(dir / "d" / "sheets" / "outdoor_vehicle.png"));
    const std::string terrain = ReadText(dir / "d" / "bench.json");
    EXPECT_NE(terrain.find("\"course\":0,\"test\":\"vehicle\",\"scene\":"), std::string::npos)
        << terrain;
    EXPECT_NE(terrain.find("\"unknown\":\"nan\""), std::string::npos);
    EXPECT_EQ(terrain.find("course04"), std::string::npos);  // no courses without --courses
}

TEST(BenchCommand, KilledBenchLeavesNoHalfWrittenJson) {
    if (!HaveSimulator()) {
        GTEST_SKIP() << "built without the simulator";
    }
    const fs::path dir = FreshDir("killed");
    // Killed at some point of its work: no bench.json, or a complete one that parses.
    const Result r = Shell("timeout -s KILL 0.4 " + std::string(CASMAP_EXE) +
                           " bench --courses 1-4 --tests T --no-sheets --threads 1 --courses-dir " +
                           CASMAP_SOURCE_DIR + "/scenes/courses --out " + (dir / "o").string() +
                           " --json " + (dir / "b.json").string());
    for (const fs::path& json : {dir / "o" / "bench.json", dir / "b.json"}) {
        if (fs::exists(json)) {
            const Result parse =
                Shell("/usr/bin/python3 -c 'import json,sys; json.load(open(sys.argv[1]))' " +
                      json.string());
            EXPECT_EQ(parse.code, 0) << json << " is not complete JSON: " << parse.output;
        }
    }
    SUCCEED() << (fs::exists(dir / "b.json") ? "finished before the kill" : "killed: no JSON")
              << r.output;
}

TEST(SweepCommand, TwoParameterGridGivesStatsAndHeatMap) {
    if (!HaveSimulator()) {
        GTEST_SKIP() << "built without the simulator";
    }
    const fs::path dir = FreshDir("sweep");
    const Result r = Casmap("sweep --set A=6:12:6 --set a=2:3:1 --courses 4 --tests T --out " +
                            (dir / "s").string() + " --json " + (dir / "s.json").string());
    ASSERT_EQ(r.code, 0) << r.output;
    EXPECT_TRUE(fs::exists(dir / "s" / "heatmap.png"));
    EXPECT_TRUE(fs::exists(dir / "s" / "runs" / "course04_T.yaml"));
    const std::string script = dir.string() + "/check.py";
    std::ofstream(script) << R"PY(
import json, sys
d = json.load(open(sys.argv[1]))
assert d["parameters"] == ["A", "a"], d["parameters"]
pts = d["points"]
assert [(p["params"]["A"], p["params"]["a"]) for p in pts] == [(6, 2), (6, 3), (12, 2), (12, 3)]
for p in pts:
    assert p["runs"] == 1 and p["pi_std"] == 0 and p["pi_min"] == p["pi_max"] == p["pi_mean"]
    assert 0 < p["pi_mean"] < 5
# a changes the certainty map (re-mapped), so the points differ
assert len({p["pi_mean"] for p in pts}) == 4, pts
print("ok")
)PY";
    const Result check = Shell("/usr/bin/python3 " + script + " " + (dir / "s.json").string());
    EXPECT_EQ(check.code, 0) << check.output;
}

// Choosing on training seeds, scoring on a held-out seed, growing the grid: sweep.json says which
// point was chosen by which rule, the held-out figures beside the paper's, and the Pareto front.
TEST(SweepCommand, TrainsGrowsAndScoresHeldOut) {
    if (!HaveSimulator()) {
        GTEST_SKIP() << "built without the simulator";
    }
    const fs::path dir = FreshDir("sweep_held");
    const Result r = Casmap(
        "sweep --set A=12:24:12 --set h_sum_min=7:9:2 --courses 4 --tests T --train-seeds 1 "
        "--test-seeds 2 --grow 2 --out " +
        (dir / "s").string());
    ASSERT_EQ(r.code, 0) << r.output;
    EXPECT_NE(r.output.find("held-out runs (1)"), std::string::npos) << r.output;
    const std::string script = dir.string() + "/check.py";
    std::ofstream(script) << R"PY(
import json, sys
d = json.load(open(sys.argv[1]))
assert d["filter"] == "cas" and d["seeds"] == [1], d
pts = d["points"]
best = pts[d["best_point"]]
assert best["params"] == d["best_params"]
if any(p["keeps_every_pole"] for p in pts):
    assert best["keeps_every_pole"] and d["best_keeps_every_pole"]
    assert all(best["pi_mean"] <= p["pi_mean"] for p in pts if p["keeps_every_pole"])
for g in d["growth"]:
    assert g["axis"] in ("A", "h_sum_min") and g["round"] >= 1
assert len(d["pareto_front"]) >= 1
h = d["held_out"]
assert h["seeds"] == [2] and h["courses"] == [4] and h["chosen_params"] == d["best_params"]
assert [r["name"] for r in h["runs"]] == ["seed2_course04_T"]
t = h["by_test"]["T"]
assert t["chosen"]["runs"] == 1 and t["paper"]["runs"] == 1
assert t["chosen"]["pi_mean"] == h["runs"][0]["chosen"]["pi"]
print("ok")
)PY";
    const Result check =
        Shell("/usr/bin/python3 " + script + " " + (dir / "s" / "sweep.json").string());
    EXPECT_EQ(check.code, 0) << check.output;
}

}  // namespace
}  // namespace casmap
