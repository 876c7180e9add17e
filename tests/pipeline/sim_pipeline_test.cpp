#include "casmap/pipeline/sim_pipeline.hpp"

#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "casmap/core/input_error.hpp"
#include "casmap/io/scene_file.hpp"
#include "casmap/pipeline/bench_runner.hpp"
#include "casmap/pipeline/data_dir.hpp"
#include "casmap/sim/simulator.hpp"

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

}  // namespace
}  // namespace casmap::pipeline
