#include "casmap/pipeline/sim_pipeline.hpp"

#include <gtest/gtest.h>
#include <yaml-cpp/yaml.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <string>
#include <vector>

#include "casmap/core/input_error.hpp"
#include "casmap/io/rig_config.hpp"
#include "casmap/io/scene_file.hpp"
#include "casmap/io/sensor_config.hpp"
#include "casmap/pipeline/bench.hpp"
#include "casmap/pipeline/bench_runner.hpp"
#include "casmap/pipeline/data_dir.hpp"
#include "casmap/pipeline/map_run.hpp"
#include "casmap/sim/simulator.hpp"
#include "tests/temp_dir.hpp"

namespace casmap::pipeline {
namespace {

SimFlags Course4(const std::string& motion) {
    SimFlags flags;
    flags.scene_path = CoursePath(CoursesDir().string(), 4);
    flags.motion = motion;
    flags.seed = 5;
    return flags;
}

TEST(ResolveSimSetup, NamesFieldsNotFlags) {
    SimFlags bad = Course4("XY");
    try {
        (void)ResolveSimSetup(bad);
        FAIL();
    } catch (const InputError& e) {
        EXPECT_EQ(e.field(), "motion");
    }
    SimFlags fast = Course4("T");
    fast.speed_m_s = 2.0;
    try {
        (void)ResolveSimSetup(fast);
        FAIL();
    } catch (const InputError& e) {
        EXPECT_EQ(e.field(), "speed_m_s");
        EXPECT_EQ(std::string(e.what()).find("--"), std::string::npos) << e.what();
    }
}

// SimulateRun is sim::Simulate plus the run's bookkeeping: the same scans, progress up to the
// scan count, identical results at any thread count.
TEST(SimulateRun, IsSimSimulateWithProgress) {
    SimFlags flags = Course4("T");
    flags.speed_m_s = 1.0;
    const SimSetup setup = ResolveSimSetup(flags);
    const core::Scene scene = io::LoadScene(setup.scene_path);
    const sim::World world(scene);
    const core::Trajectory poses = RigTrajectory(setup, scene);
    std::size_t last = 0;
    std::size_t total_seen = 0;
    SimulateRunOptions options;
    options.threads = 2;
    options.truth = false;
    options.progress = [&](std::size_t done, std::size_t total) {
        EXPECT_EQ(done, last + 1);
        last = done;
        total_seen = total;
    };
    const SimulatedRun run = SimulateRun(setup, scene, world, poses, options);
    EXPECT_EQ(run.run.scans.size(), ScanCount(setup, poses));
    EXPECT_EQ(last, run.run.scans.size());
    EXPECT_EQ(total_seen, run.run.scans.size());
    EXPECT_FALSE(run.run.maps.truth_m.has_value());

    const sensor_models::Lms200Model model(setup.lms, setup.seed);
    sim::SimulateOptions direct;
    direct.start_s = poses.StartTime();
    direct.scan_count = 3;
    direct.threads = 1;
    const std::vector<sim::ScanResult> first = sim::Simulate(world, model, poses, direct);
    for (std::size_t k = 0; k < first.size(); ++k) {
        ASSERT_EQ(first[k].scan.beams.size(), run.run.scans[k].beams.size());
        for (std::size_t i = 0; i < first[k].scan.beams.size(); ++i) {
            EXPECT_EQ(first[k].scan.beams[i].range_m, run.run.scans[k].beams[i].range_m);
        }
    }
    options.threads = 1;
    options.progress = {};
    const SimulatedRun again = SimulateRun(setup, scene, world, poses, options);
    EXPECT_EQ(again.run.config_yaml, run.run.config_yaml);
    ASSERT_EQ(again.run.scans.size(), run.run.scans.size());
    EXPECT_EQ(again.run.scans.back().beams[90].range_m, run.run.scans.back().beams[90].range_m);
}

double Up(double v) { return std::nextafter(v, std::numeric_limits<double>::infinity()); }

std::string WriteTemp(const std::string& name, const YAML::Node& node) {
    const std::filesystem::path path =
        casmap::test::MakeTempDir("effective") / ("casmap_effective_" + name + ".yaml");
    YAML::Emitter out;
    out << node;
    std::ofstream(path) << out.c_str() << "\n";
    return path.string();
}

// The effective configuration is written with yaml-cpp's emitter and core::FormatNumber: it
// loads back (sensor and rig sections through the io loaders) to the very same values, even
// values with 17 significant digits, and a path that needs quoting stays one value.
TEST(EffectiveConfigYaml, LoadsBackToTheSameConfiguration) {
    SimFlags flags = Course4("TRP");
    SimSetup setup = ResolveSimSetup(flags);
    setup.scene_path = "/tmp/a dir/scene: #4.yaml";
    setup.seed = 18446744073709551615ULL;
    setup.table.speed_m_s = 0.1 + 0.2;  // 0.30000000000000004
    setup.table.mount_pitch_deg = std::nextafter(setup.table.mount_pitch_deg, 0.0);
    setup.table.roll_profile.period_s = 10.0 / 3.0;
    setup.vehicle_config.wheelbase_m = Up(setup.vehicle_config.wheelbase_m);
    setup.pose_error.position_jitter_m = 1e-5;
    setup.lms.divergence_rad = Up(setup.lms.divergence_rad);
    setup.grid.x0_m = Up(setup.grid.x0_m);

    const std::string text = EffectiveConfigYaml(setup);
    EXPECT_EQ(text, EffectiveConfigYaml(setup)) << "deterministic";
    const YAML::Node root = YAML::Load(text);
    EXPECT_EQ(root["scene"].as<std::string>(), setup.scene_path);
    EXPECT_EQ(root["motion"].as<std::string>(), "TRP");
    EXPECT_EQ(root["seed"].as<std::uint64_t>(), setup.seed);
    EXPECT_TRUE(root["rig_file"].IsNull());
    EXPECT_TRUE(root["sensor_file"].IsNull());
    const YAML::Node grid = root["grid"];
    EXPECT_EQ(grid["origin_x_m"].as<double>(), setup.grid.x0_m);
    EXPECT_EQ(grid["origin_y_m"].as<double>(), setup.grid.y0_m);
    EXPECT_EQ(grid["cell_m"].as<double>(), setup.grid.cell_m);
    EXPECT_EQ(grid["rows"].as<int>(), setup.grid.rows);
    EXPECT_EQ(grid["cols"].as<int>(), setup.grid.cols);

    const sensor_models::Lms200Config lms =
        io::LoadLms200Config(WriteTemp("sensor", root["sensor"]));
    EXPECT_EQ(lms.divergence_rad, setup.lms.divergence_rad);
    EXPECT_EQ(io::Lms200ConfigToYaml(lms), io::Lms200ConfigToYaml(setup.lms));

    YAML::Node rig;
    for (const char* key : {"table", "vehicle", "pose_error"}) {
        rig[key] = root[key];
    }
    const io::RigConfig back = io::LoadRigConfig(WriteTemp("rig", rig));
    EXPECT_EQ(back.table.speed_m_s, setup.table.speed_m_s);
    EXPECT_EQ(back.table.mount_pitch_deg, setup.table.mount_pitch_deg);
    EXPECT_EQ(back.table.roll_profile.period_s, setup.table.roll_profile.period_s);
    EXPECT_EQ(back.vehicle.wheelbase_m, setup.vehicle_config.wheelbase_m);
    EXPECT_EQ(back.pose_error.position_jitter_m, setup.pose_error.position_jitter_m);
    EXPECT_EQ(io::RigConfigToYaml(back), io::RigConfigToYaml(io::RigConfig{
                                             setup.table, setup.vehicle_config, setup.pose_error}));
}

TEST(FilterParamsYaml, ListsTheParametersWithExactNumbers) {
    mapper::FilterParams params;
    params.cas.speed_m_s = 0.1 + 0.2;
    params.cas.scan_period_s = 1.0 / 75.0;
    params.baseline.noise = 1e-7;
    const YAML::Node root = YAML::Load(FilterParamsYaml(params));
    const YAML::Node cas = root["filters"]["cas"];
    EXPECT_EQ(cas["k"].as<int>(), params.cas.k);
    EXPECT_EQ(cas["speed_m_s"].as<double>(), params.cas.speed_m_s);
    EXPECT_EQ(cas["scan_period_s"].as<double>(), params.cas.scan_period_s);
    EXPECT_EQ(cas["A"].as<double>(), params.cas.EffectiveA());
    EXPECT_EQ(cas["G"].as<double>(), params.cas.EffectiveG());
    EXPECT_EQ(root["filters"]["baseline"]["noise"].as<double>(), 1e-7);
    params.baseline.noise.reset();
    EXPECT_EQ(
        YAML::Load(FilterParamsYaml(params))["filters"]["baseline"]["noise"].as<std::string>(),
        "mean_local_variance");
}

TEST(MapConfigYaml, NullSeedAndExactNumbers) {
    MappedRun mapped;
    mapped.config.grid = core::GridGeometry{Up(1.0), -1.0, 0.025, 200, 80};
    mapped.config.scan_period_s = 1.0 / 75.0;
    mapped.stats.beams_seen = 12345678901ULL;
    YAML::Node root = YAML::Load(MapConfigYaml("/runs/a b.h5", std::nullopt, mapped));
    EXPECT_EQ(root["run"].as<std::string>(), "/runs/a b.h5");
    EXPECT_TRUE(root["seed"].IsNull());
    EXPECT_EQ(root["grid"]["origin_x_m"].as<double>(), Up(1.0));
    EXPECT_EQ(root["mapper"]["scan_period_s"].as<double>(), 1.0 / 75.0);
    EXPECT_EQ(root["stats"]["beams_seen"].as<std::uint64_t>(), 12345678901ULL);
    root = YAML::Load(MapConfigYaml("r.h5", 7, mapped));
    EXPECT_EQ(root["seed"].as<std::uint64_t>(), 7U);
    EXPECT_EQ(GridYaml(mapped.config.grid),
              "{origin_x_m: 1.0000000000000002, origin_y_m: -1, cell_m: 0.025, rows: 200, cols: "
              "80}");
}

}  // namespace
}  // namespace casmap::pipeline
