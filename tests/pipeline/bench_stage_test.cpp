// Per-pipeline stage parameters of the sweep_jump pre-filter in `casmap bench`: a map re-made
// for a pipeline is shared only by pipelines with the same stage settings (StageKey), and the
// settings reach the run's config.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "casmap/pipeline/bench.hpp"
#include "tests/temp_dir.hpp"

namespace casmap::pipeline {
namespace {

// A preset section giving sweep_jump_median its own angle: sweep_jump keeps the shared value,
// sweep_jump_median equals a bench where the whole run had the section's value. If the stage
// key left sweep_jump's parameters out, both pipelines would share the first map made.
TEST(BenchStage, SweepJumpSectionMapsItsPipelineAgain) {
    const casmap::test::TempDir tmp("bench_sweep_jump_preset");
    const std::filesystem::path file = tmp / "casmap_bench_sweep_jump_preset.yaml";
    std::ofstream(file) << "set: {}\npipelines:\n"
                           "  sweep_jump_median: {sweep_jump.max_angle_deg: 2.5}\n";
    BenchOptions options;
    options.courses = {4};
    options.tests = {"TRP"};
    options.sheets = false;
    options.threads = 2;
    options.pipelines = {"sweep_jump", "sweep_jump_median"};
    const BenchResult plain = RunBench(options);
    BenchOptions global = options;
    global.filter_settings = {"sweep_jump.max_angle_deg=2.5"};
    const BenchResult narrow = RunBench(global);
    options.preset = file.string();
    const BenchResult own = RunBench(options);
    const auto rmse = [](const BenchResult& r, const std::string& name) {
        return r.runs[0].filters.at(name).rmse_m;
    };
    ASSERT_NE(rmse(narrow, "sweep_jump_median"), rmse(plain, "sweep_jump_median"));
    EXPECT_EQ(rmse(own, "sweep_jump"), rmse(plain, "sweep_jump"));
    EXPECT_EQ(rmse(own, "sweep_jump_median"), rmse(narrow, "sweep_jump_median"));
    // The run's config lists the shared values, and the section's under its pipeline.
    const std::string& config = own.run_configs[0];
    EXPECT_NE(config.find("sweep_jump: {jump_min_m: 0.1, margin_m: 0.05, max_angle_deg: 10, "
                          "depression_share: 0.35, reach: 1}"),
              std::string::npos)
        << config;
    EXPECT_NE(config.find("sweep_jump_median: [sweep_jump.max_angle_deg=2.5]"), std::string::npos)
        << config;
}

}  // namespace
}  // namespace casmap::pipeline
