#include "casmap/pipeline/dataset.hpp"

#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <vector>

#include "casmap/core/input_error.hpp"
#include "casmap/io/dataset_spec_file.hpp"
#include "casmap/io/run_file.hpp"
#include "casmap/io/scene_file.hpp"
#include "casmap/pipeline/sim_pipeline.hpp"
#include "casmap/sim/world.hpp"
#include "tests/temp_dir.hpp"

namespace casmap::pipeline {
namespace {
namespace fs = std::filesystem;

// Unique per call (several worktrees' test runs share /tmp on one machine), removed at exit.
fs::path TempDir(const std::string& name) {
    return casmap::test::MakeTempDir("dataset_test_" + name);
}

std::string Slurp(const fs::path& path) {
    std::ifstream in(path, std::ios::binary);
    std::stringstream s;
    s << in.rdbuf();
    return s.str();
}

// A small, quick spec: a 1 m course, fast table runs at 1 deg, both scene types.
scenegen::DatasetSpec SmallSpec(int count) {
    scenegen::DatasetSpec spec;
    spec.count = count;
    spec.seed = 5;
    spec.region_length_m = 1.0;
    spec.scene.terrain_probability = 0.5;
    spec.scene.ground_cell_m = 0.1;
    spec.domain.motion_weights = {1, 1, 1, 1, 0};
    spec.domain.table_speed_m_s = {1.0, 1.0};
    spec.domain.angular_resolutions_deg = {1.0};
    spec.outputs.pose_decimation = 10;
    spec.Validate("test");
    return spec;
}

DatasetContext Context(const fs::path& dir) {
    DatasetContext c;
    c.out_dir = dir;
    c.rock_meshes = FindRockMeshes(std::string(CASMAP_SOURCE_DIR) + "/scenes/meshes");
    return c;
}

// Every file under `dir`, relative path -> bytes.
std::map<std::string, std::string> Tree(const fs::path& dir) {
    std::map<std::string, std::string> files;
    for (const fs::directory_entry& e : fs::recursive_directory_iterator(dir)) {
        if (e.is_regular_file()) {
            files[fs::relative(e.path(), dir).string()] = Slurp(e.path());
        }
    }
    return files;
}

TEST(Dataset, SamplesAndManifestAreTheSameAtAnyThreadCountAndShard) {
    const scenegen::DatasetSpec spec = SmallSpec(4);
    const fs::path a = TempDir("threads1");
    const fs::path b = TempDir("threads2");
    const fs::path c = TempDir("shards");
    const DatasetSummary sa = RunDataset(spec, Context(a), DatasetOptions{1, 0, 1, {}});
    EXPECT_EQ(sa.generated + sa.failed, 4U);
    EXPECT_EQ(sa.failed, 0U);
    (void)RunDataset(spec, Context(b), DatasetOptions{2, 0, 1, {}});
    const DatasetSummary half = RunDataset(spec, Context(c), DatasetOptions{1, 1, 2, {}});
    EXPECT_EQ(half.pending, 2U) << "shard 1/2 leaves the even indices pending";
    (void)RunDataset(spec, Context(c), DatasetOptions{1, 0, 2, {}});
    const auto ta = Tree(a);
    EXPECT_EQ(ta, Tree(b));
    EXPECT_EQ(ta, Tree(c));
    EXPECT_TRUE(ta.count("manifest.jsonl"));
    EXPECT_TRUE(ta.count("samples/000003/run.h5"));
    EXPECT_TRUE(ta.count("card/contact_sheet.png"));
}

TEST(Dataset, ResumeSkipsVerifiedSamplesAndRegeneratesDamagedOnes) {
    const scenegen::DatasetSpec spec = SmallSpec(2);
    const fs::path dir = TempDir("resume");
    (void)RunDataset(spec, Context(dir), DatasetOptions{});
    const auto before = Tree(dir);
    const DatasetSummary again = RunDataset(spec, Context(dir), DatasetOptions{});
    EXPECT_EQ(again.reused, 2U);
    EXPECT_EQ(again.generated, 0U);
    {
        std::ofstream damage(dir / "samples/000001/run.h5", std::ios::binary | std::ios::trunc);
        damage << "truncated";
    }
    const DatasetSummary repaired = RunDataset(spec, Context(dir), DatasetOptions{});
    EXPECT_EQ(repaired.reused, 1U);
    EXPECT_EQ(repaired.generated, 1U);
    EXPECT_EQ(Tree(dir), before);
}

TEST(Dataset, SampleCarriesLabelsMapsAndNegativeTruthAndReSimulatesAlone) {
    scenegen::DatasetSpec spec = SmallSpec(1);
    spec.scene.terrain_probability = 0.0;
    spec.scene.holes = {2.0, 2.0};
    spec.scene.hole_depth_m = {0.2, 0.2};
    const fs::path dir = TempDir("sample");
    const SampleRecord r = GenerateSample(spec, Context(dir), 0);
    ASSERT_TRUE(r.ok) << r.line;
    const fs::path sample = SampleDir(dir, 0);
    const io::RunData run = io::ReadRunFile(sample / "run.h5");
    ASSERT_FALSE(run.scans.empty());
    ASSERT_EQ(run.truth.size(), run.scans.size());
    ASSERT_TRUE(run.maps.truth_m && run.maps.elevation_m && run.maps.certainty);
    ASSERT_TRUE(run.maps.cas_classes);
    EXPECT_EQ(run.maps.filtered.size(), 5U);
    float lowest = 0.0F;
    for (const float z : run.maps.truth_m->data) {
        lowest = std::min(lowest, z);
    }
    EXPECT_LT(lowest, -0.15F) << "the holes' negative heights are kept in the truth";
    // `casmap simulate --scene scene.yaml --rig rig.yaml --sensor sensor.yaml --seed S`.
    const std::string line = r.line;
    const std::size_t at = line.find("--seed ");
    ASSERT_NE(at, std::string::npos);
    const std::string motion_key = "--motion ";
    const std::size_t m = line.find(motion_key);
    SimFlags flags;
    flags.scene_path = (sample / "scene.yaml").string();
    flags.motion = line.substr(m + motion_key.size(),
                               line.find(' ', m + motion_key.size()) - m - motion_key.size());
    flags.rig_path = (sample / "rig.yaml").string();
    flags.sensor_path = (sample / "sensor.yaml").string();
    flags.seed = std::stoull(line.substr(at + 7));
    const SimSetup setup = ResolveSimSetup(flags);
    const core::Scene scene = io::LoadScene(setup.scene_path);
    const sim::World world(scene);
    const SimulatedRun again =
        SimulateRun(setup, scene, world, RigTrajectory(setup, scene), {1, {}, false});
    ASSERT_EQ(again.run.scans.size(), run.scans.size());
    for (std::size_t k = 0; k < run.scans.size(); ++k) {
        for (std::size_t i = 0; i < run.scans[k].beams.size(); ++i) {
            ASSERT_EQ(again.run.scans[k].beams[i].status, run.scans[k].beams[i].status);
        }
    }
}

TEST(Dataset, AFailingSampleIsRecordedAndTheRunGoesOn) {
    scenegen::DatasetSpec spec = SmallSpec(3);
    spec.scene.kind_weights = {0, 0, 0, 0, 0, 0, 1};  // rocks only
    spec.scene.clutter_per_m2 = {2.0, 2.0};
    const fs::path dir = TempDir("failing");
    DatasetContext context = Context(dir);
    const fs::path broken = dir / "rock_01.ply";
    std::ofstream(broken) << "not a mesh\n";
    context.rock_meshes = {broken};
    const DatasetSummary s = RunDataset(spec, context, DatasetOptions{2, 0, 1, {}});
    EXPECT_EQ(s.failed, 3U);
    const std::string manifest = Slurp(dir / "manifest.jsonl");
    EXPECT_EQ(std::count(manifest.begin(), manifest.end(), '\n'), 3);
    EXPECT_NE(manifest.find("\"status\":\"failed\""), std::string::npos) << manifest;
    EXPECT_NE(manifest.find("rock_01.ply"), std::string::npos) << "the error names the mesh";
    EXPECT_FALSE(fs::exists(SampleDir(dir, 0) / "sample.json"));
    EXPECT_TRUE(fs::exists(dir / "card.md"));
}

// Sample 106 of the default spec: 556 scans of 1/75 s end exactly at its 7.42 s trajectory, and
// the scan count's quotient rounded up to one scan too many.
TEST(Dataset, TheLastScanEndingOnTheTrajectoryEndIsKeptOrDropped) {
    const scenegen::DatasetSpec spec =
        io::LoadDatasetSpec(std::string(CASMAP_SOURCE_DIR) + "/config/datasets/default.yaml");
    const SampleRecord r = GenerateSample(spec, Context(TempDir("rounding")), 106);
    EXPECT_TRUE(r.ok) << r.line;
}

TEST(DatasetSpecFile, UnknownKeyAndBadRangeNameFileAndField) {
    const fs::path dir = TempDir("spec");
    const fs::path path = dir / "spec.yaml";
    std::ofstream(path) << "count: 3\nscene:\n  pole_diameter: [0.01, 0.02]\n";
    try {
        (void)io::LoadDatasetSpec(path.string());
        FAIL() << "accepted an unknown key";
    } catch (const InputError& e) {
        const std::string what = e.what();
        EXPECT_NE(what.find("spec.yaml:3:3"), std::string::npos) << what;
        EXPECT_NE(what.find("scene.pole_diameter"), std::string::npos) << what;
    }
    std::ofstream(path) << "domain:\n  table_speed_m_s: [0.5, 2.0]\n";
    try {
        (void)io::LoadDatasetSpec(path.string());
        FAIL() << "accepted a table speed above 1 m/s";
    } catch (const InputError& e) {
        EXPECT_NE(std::string(e.what()).find("domain.table_speed_m_s"), std::string::npos)
            << e.what();
    }
}

TEST(DatasetSpecFile, EffectiveYamlReadsBackToTheSameSpec) {
    const scenegen::DatasetSpec spec =
        io::LoadDatasetSpec(std::string(CASMAP_SOURCE_DIR) + "/config/datasets/default.yaml");
    const fs::path path = TempDir("roundtrip") / "effective.yaml";
    std::ofstream(path) << io::DatasetSpecToYaml(spec);
    EXPECT_EQ(io::DatasetSpecToYaml(io::LoadDatasetSpec(path.string())),
              io::DatasetSpecToYaml(spec));
}

}  // namespace
}  // namespace casmap::pipeline

namespace casmap::pipeline {
namespace {

TEST(DatasetShard, ParsesIOverKAndNamesTheFieldOtherwise) {
    DatasetOptions o;
    ParseShard("2/5", o);
    EXPECT_EQ(o.shard, 2U);
    EXPECT_EQ(o.shards, 5U);
    EXPECT_NO_THROW(o.Validate());
    for (const char* bad : {"5/5", "1/0", "1", "a/2", "1/2/3", "-1/2", " 1/2"}) {
        try {
            ParseShard(bad, o, "--shard");
            ADD_FAILURE() << bad;
        } catch (const InputError& e) {
            EXPECT_EQ(std::string(e.what()),
                      "--shard = " + std::string(bad) + " (expected I/K with 0 <= I < K)");
        }
    }
    o.shard = 3;
    o.shards = 3;
    EXPECT_THROW(o.Validate(), InputError);
    o.shard = 0;
    o.threads = 0;
    EXPECT_THROW(o.Validate(), InputError);
}

}  // namespace
}  // namespace casmap::pipeline
