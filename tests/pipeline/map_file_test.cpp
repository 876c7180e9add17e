// pipeline::MapRunFile (what `casmap map` runs): the maps of a run file written beside it and
// stored back into it, equal to MapScans on the same scans; errors name fields, not flags.
#include "casmap/pipeline/map_file.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <numbers>
#include <string>
#include <vector>

#include "casmap/core/input_error.hpp"
#include "casmap/core/lms200.hpp"
#include "casmap/io/image.hpp"
#include "casmap/io/run_file.hpp"
#include "tests/temp_dir.hpp"

namespace casmap::pipeline {
namespace {
namespace fs = std::filesystem;
constexpr double kDeg = std::numbers::pi / 180.0;

/// A scanner 0.5 m over a flat floor, 40 deg nose down, driving 1 m/s along x.
io::RunData FloorRun() {
    io::RunData run;
    run.format = core::Lms200Format{};
    run.config_yaml = "test: flat floor\n";
    std::vector<core::TimedPose> poses;
    for (int i = 0; i <= 1600; ++i) {
        const double t = i * 0.001;
        poses.push_back({t, core::PoseFromXyzRpy({-0.5 + t, 0.0, 0.5}, {0.0, 40 * kDeg, 0.0})});
    }
    run.poses = core::Trajectory(poses);
    for (int k = 0; k < 100; ++k) {
        core::Scan s;
        s.stamp_s = 0.01 + k / 75.0;
        s.start_angle_rad = -90 * kDeg;
        s.angle_step_rad = 1 * kDeg;
        s.beam_period_s = core::Lms200Timing::kBeamPeriodS;
        for (std::size_t i = 0; i < 181; ++i) {
            const core::Pose pose = *run.poses.PoseAt(s.BeamTime(i));
            const double a = s.BeamAngle(i);
            const Eigen::Vector3d d = pose.rotation * Eigen::Vector3d(std::cos(a), std::sin(a), 0);
            const double r = d.z() < -1e-6 ? -pose.translation.z() / d.z() : 1e9;
            core::Beam b;
            b.status = r < 8.0 ? core::BeamStatus::kOk : core::BeamStatus::kNoReturn;
            b.range_m = r < 8.0 ? static_cast<float>(r) : 0.0F;
            b.raw = r < 8.0 ? run.format->EncodeRange(r) : run.format->CodeFor(b.status);
            s.beams.push_back(b);
        }
        run.scans.push_back(s);
    }
    return run;
}

fs::path FreshDir(const std::string& name) { return casmap::test::MakeTempDir("map_file_" + name); }

TEST(MapRunFile, WritesTheMapsAndStoresThemInTheRun) {
    const fs::path dir = FreshDir("ok");
    const io::RunData run = FloorRun();
    io::WriteRunFile(dir / "run.h5", run);
    MapRunFileOptions o;
    o.run = (dir / "run.h5").string();
    o.grid = core::GridGeometry{0.0, -1.0, 0.025, 60, 80};
    const MapRunFileResult r = MapRunFile(o);
    EXPECT_EQ(r.out_dir, dir / "run_maps");  // the default: beside the run
    for (const char* f : {"elevation.tiff", "elevation.png", "certainty.tiff", "certainty.png",
                          "map.yaml", "run_config.yaml"}) {
        EXPECT_TRUE(fs::exists(r.out_dir / f)) << f;
    }
    EXPECT_FALSE(fs::exists(r.out_dir / "truth.tiff"));  // the run holds no truth
    const MappedRun direct = MapScans(run.scans, run.poses, *o.grid, MapSettings{});
    EXPECT_GT(direct.stats.beams_mapped, 1000U);
    EXPECT_EQ(r.mapped.stats.beams_mapped, direct.stats.beams_mapped);
    const core::MapF tiff = io::ReadMapTiff(r.out_dir / "elevation.tiff");
    const io::RunData stored = io::ReadRunFile(o.run);
    ASSERT_TRUE(stored.maps.elevation_m.has_value());
    ASSERT_TRUE(stored.maps.grid.has_value());
    EXPECT_EQ(*stored.maps.grid, *o.grid);
    EXPECT_EQ(tiff.data, direct.elevation.data);  // NaN-free: unknown cells are 0
    EXPECT_EQ(stored.maps.elevation_m->data, direct.elevation.data);
    EXPECT_EQ(stored.maps.certainty->data, direct.certainty.data);
}

TEST(MapRunFile, ErrorsNameFieldsNotFlags) {
    const fs::path dir = FreshDir("bad");
    io::RunData run = FloorRun();
    run.maps.grid = core::GridGeometry{0.0, -1.0, 0.025, 60, 80};
    io::WriteRunFile(dir / "run.h5", run);
    MapRunFileOptions o;
    o.run = (dir / "run.h5").string();
    o.grid = core::GridGeometry{0.0, -1.0, 0.05, 30, 40};
    try {
        (void)MapRunFile(o);
        FAIL() << "a second grid was accepted";
    } catch (const InputError& e) {
        EXPECT_EQ(e.where(), o.run);
        EXPECT_EQ(e.field(), "grid");
        EXPECT_EQ(std::string(e.what()).find("--"), std::string::npos) << e.what();
    }
    run.poses = core::Trajectory();
    io::WriteRunFile(dir / "no_poses.h5", run);
    o.run = (dir / "no_poses.h5").string();
    o.grid.reset();
    try {
        (void)MapRunFile(o);
        FAIL() << "a run without poses was mapped";
    } catch (const InputError& e) {
        EXPECT_EQ(e.field(), "/poses");
    }
    EXPECT_FALSE(fs::exists(dir / "no_poses_maps"));
}

}  // namespace
}  // namespace casmap::pipeline
