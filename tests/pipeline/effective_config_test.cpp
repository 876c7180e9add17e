// The sweep_jump parameters in the effective configurations `casmap bench` (runs/<run>.yaml)
// and `casmap map` (map.yaml) write: both list the values the run used, and both read back
// through the project's preset reader (LoadPreset, FilterParams::Set) to those values.
#include <gtest/gtest.h>
#include <yaml-cpp/yaml.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "casmap/io/run_file.hpp"
#include "casmap/io/scene_file.hpp"
#include "casmap/mapper/filter_params.hpp"
#include "casmap/pipeline/bench.hpp"
#include "casmap/pipeline/data_dir.hpp"
#include "casmap/pipeline/map_file.hpp"
#include "casmap/pipeline/preset.hpp"
#include "casmap/pipeline/sim_pipeline.hpp"
#include "casmap/sim/world.hpp"
#include "tests/temp_dir.hpp"

namespace casmap::pipeline {
namespace {
namespace fs = std::filesystem;

// Every field away from its default (reach = 2 also tests an integer field).
const std::vector<std::string> kSweepJump = {
    "sweep_jump.jump_min_m=0.2", "sweep_jump.margin_m=0.075", "sweep_jump.max_angle_deg=7.25",
    "sweep_jump.depression_share=0.5", "sweep_jump.reach=2"};

/// The `sweep_jump` section of a written configuration as a preset file (`set:` with each key
/// under its --set name), loaded with LoadPreset and applied to default parameters.
mapper::SweepJumpConfig ReadBack(const YAML::Node& section, const fs::path& preset_path) {
    std::ostringstream text;
    text << "set:\n";
    for (const auto& entry : section) {
        text << "  sweep_jump." << entry.first.as<std::string>() << ": "
             << entry.second.as<std::string>() << "\n";
    }
    std::ofstream(preset_path) << text.str();
    mapper::FilterParams params;
    for (const std::string& s : LoadPreset(preset_path.string()).settings) {
        params.SetAssignment(s);
    }
    return params.sweep_jump;
}

/// The configuration `casmap map --prefilter sweep_jump --set ...` writes for a simulated run
/// of course 4, test T.
std::string MapYaml(const fs::path& dir) {
    SimFlags flags;
    flags.scene_path = (DataDir() / "scenes" / "courses" / "course04.yaml").string();
    const SimSetup setup = ResolveSimSetup(flags);
    const core::Scene scene = io::LoadScene(setup.scene_path);
    const sim::World world(scene);
    SimulateRunOptions sim_options;
    sim_options.threads = 2;
    sim_options.truth = false;
    const SimulatedRun sim =
        SimulateRun(setup, scene, world, RigTrajectory(setup, scene), sim_options);
    io::WriteRunFile(dir / "run.h5", sim.run);
    MapRunFileOptions options;
    options.run = (dir / "run.h5").string();
    options.settings.prefilter = Prefilter::kSweepJump;
    ApplyStageSettings(options.settings, kSweepJump, "--set");
    const MapRunFileResult result = MapRunFile(options);
    std::ifstream in(result.out_dir / "map.yaml");
    return std::string(std::istreambuf_iterator<char>(in), {});
}

TEST(EffectiveConfig, BenchAndMapSweepJumpReadBackToTheValuesRun) {
    const casmap::test::TempDir tmp("effective_config_sweep_jump");
    mapper::FilterParams expected;
    for (const std::string& s : kSweepJump) {
        expected.SetAssignment(s);
    }
    BenchOptions bench;
    bench.courses = {4};
    bench.tests = {"T"};
    bench.sheets = false;
    bench.threads = 2;
    bench.pipelines = {"sweep_jump"};
    bench.filter_settings = kSweepJump;
    const BenchResult result = RunBench(bench);
    ASSERT_EQ(result.run_configs.size(), 1U);
    const YAML::Node bench_section = YAML::Load(result.run_configs[0])["filters"]["sweep_jump"];
    const YAML::Node map_section = YAML::Load(MapYaml(tmp.Path()))["mapper"]["sweep_jump"];
    ASSERT_TRUE(bench_section.IsMap()) << result.run_configs[0];
    ASSERT_TRUE(map_section.IsMap());

    const std::vector<std::pair<YAML::Node, std::string>> written = {{bench_section, "bench"},
                                                                     {map_section, "map"}};
    for (const auto& [section, name] : written) {
        const mapper::SweepJumpConfig back = ReadBack(section, tmp / (name + ".yaml"));
        EXPECT_EQ(back.jump_min_m, expected.sweep_jump.jump_min_m) << name;
        EXPECT_EQ(back.margin_m, expected.sweep_jump.margin_m) << name;
        EXPECT_EQ(back.max_angle_deg, expected.sweep_jump.max_angle_deg) << name;
        EXPECT_EQ(back.depression_share, expected.sweep_jump.depression_share) << name;
        EXPECT_EQ(back.reach, expected.sweep_jump.reach) << name;
    }
    EXPECT_EQ(YAML::Dump(bench_section), YAML::Dump(map_section));  // one table, one text
}

}  // namespace
}  // namespace casmap::pipeline
