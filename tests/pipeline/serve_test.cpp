// pipeline::Serve (what `casmap serve` runs): the checks name the options' fields (never a
// flag), and a run file served on a pseudo-terminal is recorded back scan for scan by
// pipeline::Record, with the run's poses written in the served sweeps' clock.
#include "casmap/pipeline/serve.hpp"

#include <gtest/gtest.h>
#include <unistd.h>

#include <atomic>
#include <filesystem>
#include <numbers>
#include <string>
#include <thread>
#include <vector>

#include "../drivers/test_source.hpp"
#include "casmap/core/input_error.hpp"
#include "casmap/drivers/pose_file.hpp"
#include "casmap/io/run_file.hpp"
#include "casmap/pipeline/record.hpp"
#include "tests/temp_dir.hpp"

namespace casmap::pipeline {
namespace {
namespace fs = std::filesystem;

/// The error ServeOptions::Validate throws for `o`, checking that no flag is named.
InputError ErrorOf(const ServeOptions& o) {
    try {
        o.Validate();
    } catch (const InputError& e) {
        EXPECT_EQ(std::string(e.what()).find("--"), std::string::npos) << e.what();
        return e;
    }
    ADD_FAILURE() << "no error";
    return InputError("none");
}

TEST(Serve, ChecksNameTheOptionsFields) {
    ServeOptions o;
    EXPECT_EQ(ErrorOf(o).field(), "run / scene");  // neither
    o.run = "run.h5";
    o.scene = "course.yaml";
    EXPECT_EQ(ErrorOf(o).field(), "run / scene");  // both
    o = ServeOptions{};
    o.scene = "course.yaml";
    EXPECT_EQ(ErrorOf(o).field(), "scene / motion");
    o = ServeOptions{};
    o.run = "run.h5";
    o.baud = 57600;
    EXPECT_EQ(ErrorOf(o).field(), "baud");
    o.baud = 9600;
    o.faults = "crc=2";
    EXPECT_EQ(ErrorOf(o).where(), "faults");
    EXPECT_EQ(ErrorOf(o).field(), "crc");
    o.faults.clear();
    o.poses_out = "/nonexistent/poses.txt";
    EXPECT_EQ(ErrorOf(o).field(), "poses_out");
    EXPECT_EQ(ErrorOf(o).where(), o.poses_out);  // the path, so a CLI can name its flag
    o.poses_out.clear();
    o.eeprom = testing::TempDir();  // a folder
    EXPECT_EQ(ErrorOf(o).field(), "eeprom");
}

TEST(Serve, AServedRunIsRecordedBackWithItsPoses) {
    const casmap::test::TempDir tmp("pipeline_serve");
    const fs::path& dir = tmp.Path();
    io::RunData run;
    std::vector<core::TimedPose> poses;
    for (int i = 0; i < 40; ++i) {
        core::Scan s =
            drivers::testing::NumberedSource::Make(static_cast<std::uint64_t>(i), {180, 100});
        s.angle_step_rad = std::numbers::pi / 180.0;
        s.stamp_s = 100.0 + i / 75.0;
        run.scans.push_back(s);
        core::TimedPose p;
        p.stamp_s = s.stamp_s;
        p.world_T_sensor.translation.x() = 0.01 * i;
        poses.push_back(p);
    }
    run.poses = core::Trajectory(poses);
    io::WriteRunFile(dir / "served.h5", run);

    ServeOptions o;
    o.run = (dir / "served.h5").string();
    o.link = "/tmp/casmap_pipeline_serve_" + std::to_string(getpid());
    o.poses_out = (dir / "poses.txt").string();
    std::atomic<bool> stop{false};
    std::atomic<bool> started{false};
    ServeStarted info;
    ServeResult result;
    std::thread server([&] {
        result = Serve(o, 1, stop, [&](const ServeStarted& s) {
            info = s;
            started = true;
        });
    });
    RecordOptions r;
    r.device = o.link;
    r.out = (dir / "recorded.h5").string();
    r.scans = 5;
    r.timeout_s = 20.0;
    std::string record_error;
    try {
        Record(r, {}, {});
    } catch (const std::exception& e) {  // stop the server first: a joinable thread aborts
        record_error = e.what();
    }
    stop = true;
    server.join();
    ASSERT_TRUE(record_error.empty()) << record_error;
    ASSERT_TRUE(started);
    EXPECT_EQ(info.scans, 40U);
    EXPECT_EQ(info.variant, (drivers::Variant{180, 100}));
    EXPECT_NE(info.device.find("/dev/pts/"), std::string::npos) << info.device;
    EXPECT_GE(result.stats.scans_sent, 5U);
    EXPECT_TRUE(result.poses_out_error.empty()) << result.poses_out_error;
    const io::RunData recorded = io::ReadRunFile(r.out);
    ASSERT_EQ(recorded.scans.size(), 5U);
    for (const core::Scan& s : recorded.scans) {  // beam 0 names the served sweep
        const std::size_t i = s.beams[0].raw;
        ASSERT_LT(i, run.scans.size());
        EXPECT_EQ(s.beams.size(), run.scans[i].beams.size());
        EXPECT_EQ(s.beams[5].raw, run.scans[i].beams[5].raw);
    }
    // The pose file holds the run's poses, shifted by one offset into the system clock.
    const core::Trajectory written = drivers::ReadPoseFile(o.poses_out);
    ASSERT_EQ(written.size(), run.poses.size());
    const double offset = written.StartTime() - run.poses.StartTime();
    EXPECT_GT(offset, 1e9);  // seconds since the epoch
    EXPECT_NEAR(written.EndTime() - run.poses.EndTime(), offset, 1e-6);
    const std::string json = ServeStatsJson(result.stats);
    EXPECT_NE(json.find("\"scans_sent\": " + std::to_string(result.stats.scans_sent)),
              std::string::npos)
        << json;
}

}  // namespace
}  // namespace casmap::pipeline
