// The simulator halves of pipeline::MakeLiveSetup and pipeline::Serve: a live setup from a
// scene is anchored at the simulated map's grid, its m and Eq. 8's v follow the rig, and its
// source hands out the run `casmap simulate` makes; serve simulates the same run.
#include "casmap/pipeline/live_sim.hpp"

#include <gtest/gtest.h>

#include <atomic>
#include <string>
#include <vector>

#include "casmap/core/input_error.hpp"
#include "casmap/pipeline/live_setup.hpp"
#include "casmap/pipeline/sim_pipeline.hpp"

namespace casmap::pipeline {
namespace {

const std::string kCourse = std::string(CASMAP_SOURCE_DIR) + "/scenes/courses/course04.yaml";

TEST(LiveSim, SceneSetupFollowsTheSimulatedRig) {
    LiveOptions o;
    o.scene = kCourse;
    o.motion = "T";
    o.seed = 3;
    o.out = "unused";
    LiveSetup s = MakeLiveSetup(o, 2);
    SimFlags flags;
    flags.scene_path = kCourse;
    flags.motion = "T";
    flags.seed = 3;
    const SimSetup sim = ResolveSimSetup(flags);
    EXPECT_EQ(s.config.window.origin_x_m, sim.grid.x0_m);
    EXPECT_EQ(s.config.window.origin_y_m, sim.grid.y0_m);
    EXPECT_EQ(s.config.window.cas.speed_m_s, sim.table.speed_m_s);
    // The table's scanner looks further ahead than the paper's vehicle: m differs from 142
    // and leaves the filtered row's neighbourhood inside the window.
    EXPECT_NE(s.config.window.m, mapper::ActiveWindowConfig{}.m);
    EXPECT_GE(s.config.window.m, s.config.window.cas.k + 1);
    EXPECT_LE(s.config.window.m, s.config.window.rows - s.config.window.cas.k);
    o.m = 60;  // a given m wins
    EXPECT_EQ(MakeLiveSetup(o, 1).config.window.m, 60);

    // The source hands out the simulated run as fast as asked (not real time), all of it.
    const io::RunData run = SimulateServedRun(ServeOptions{"", kCourse, "T", {}, 3}, 1);
    ASSERT_FALSE(run.scans.empty());
    s.scans->Start();
    std::size_t n = 0;
    while (const auto scan = s.scans->Next(0.1)) {
        ASSERT_LT(n, run.scans.size());
        EXPECT_EQ(scan->stamp_s, run.scans[n].stamp_s);
        EXPECT_EQ(scan->beams.size(), run.scans[n].beams.size());
        ++n;
    }
    EXPECT_EQ(n, run.scans.size());
    EXPECT_TRUE(s.scans->finished());
    std::vector<core::TimedPose> poses;
    s.poses->Poll(poses);
    EXPECT_EQ(poses.size(), run.poses.size());
}

TEST(LiveSim, SimulatorErrorsNameTheOptionsFields) {
    LiveOptions o;
    o.scene = kCourse;
    o.motion = "Q";
    try {
        (void)MakeLiveSetup(o, 1);
        FAIL() << "no error";
    } catch (const InputError& e) {
        EXPECT_EQ(e.field(), "motion");
        EXPECT_EQ(std::string(e.what()).find("--"), std::string::npos) << e.what();
    }
}

}  // namespace
}  // namespace casmap::pipeline
