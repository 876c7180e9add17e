// `casmap map`: runs the built binary on run files made here with exact geometry (a sensor
// moving along x over a floor at z = 0 with a raised block), then checks the maps it wrote.
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <yaml-cpp/yaml.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

#include "casmap/core/pose.hpp"
#include "casmap/io/image.hpp"
#include "casmap/io/run_file.hpp"
#include "tests/apps/cli_runner.hpp"
#include "tests/temp_dir.hpp"

namespace casmap {
namespace {
namespace fs = std::filesystem;

constexpr double kDeg = 3.14159265358979323846 / 180.0;
constexpr double kBlockTopM = 0.2;  // block over x in [1.0, 1.3], y in [-0.2, 0.2]

using test::Casmap;
using test::Result;

fs::path FreshDir(const std::string& name) { return casmap::test::MakeTempDir("map_cmd_" + name); }

/// Exact range along a ray to the floor (z = 0) or the block's top, whichever is hit first;
/// NaN if the ray goes up. Block sides are ignored (the test only checks floor and top cells).
double RangeTo(const Eigen::Vector3d& o, const Eigen::Vector3d& d) {
    if (d.z() >= -1e-9) {
        return std::nan("");
    }
    const double t_top = (kBlockTopM - o.z()) / d.z();
    const Eigen::Vector3d top = o + t_top * d;
    if (top.x() >= 1.0 && top.x() <= 1.3 && std::abs(top.y()) <= 0.2) {
        return t_top;
    }
    return -o.z() / d.z();
}

/// 1.5 s at 1 m/s, sensor 0.5 m high (beam spacing on the floor below the 25 mm cell) pitched 40
/// deg down, 75 scans/s, 181 beams.
io::RunData FlatFloorRun(bool with_truth) {
    io::RunData run;
    run.format = core::Lms200Format{};
    run.config_yaml = "test: flat floor with a block\n";
    std::vector<core::TimedPose> poses;
    for (int i = 0; i <= 1600; ++i) {  // 1 kHz physics-rate poses
        const double t = i * 0.001;
        poses.push_back({t, core::PoseFromXyzRpy({-0.5 + t, 0.0, 0.5}, {0.0, 40 * kDeg, 0.0})});
    }
    run.poses = core::Trajectory(poses);
    for (int k = 0; k < 112; ++k) {
        core::Scan s;
        s.stamp_s = 0.01 + k / 75.0;
        s.start_angle_rad = -90 * kDeg;
        s.angle_step_rad = 1 * kDeg;
        s.beam_period_s = core::Lms200Timing::kBeamPeriodS;
        core::ScanTruth truth;
        for (std::size_t i = 0; i < 181; ++i) {
            const core::Pose pose = *run.poses.PoseAt(s.BeamTime(i));
            const double a = s.BeamAngle(i);
            const Eigen::Vector3d d = pose.rotation * Eigen::Vector3d(std::cos(a), std::sin(a), 0);
            const double r = RangeTo(pose.translation, d);
            core::Beam b;
            if (std::isfinite(r) && r < 8.0) {
                b.status = core::BeamStatus::kOk;
                b.range_m = static_cast<float>(r);
                b.raw = run.format->EncodeRange(r);
            } else {
                b.status = core::BeamStatus::kNoReturn;
                b.raw = run.format->CodeFor(b.status);
            }
            s.beams.push_back(b);
            truth.labels.push_back(b.status == core::BeamStatus::kOk ? core::BeamLabel::kValid
                                                                     : core::BeamLabel::kNoTarget);
        }
        run.scans.push_back(s);
        if (with_truth) {
            run.truth.push_back(truth);
        }
    }
    return run;
}

TEST(MapCommand, FlatFloorAndBlockAppearInMapsAndRunFile) {
    const fs::path dir = FreshDir("flat");
    const io::RunData written = FlatFloorRun(true);
    io::RunData with_grid = written;
    with_grid.maps.grid = core::GridGeometry{0.0, -1.0, 0.025, 60, 80};  // x 0..1.5, y -1..1
    io::WriteRunFile(dir / "run.h5", with_grid);

    const Result r =
        Casmap("map " + (dir / "run.h5").string() + " --out " + (dir / "maps").string());
    ASSERT_EQ(r.code, 0) << r.output;
    for (const char* f : {"elevation.tiff", "elevation.png", "certainty.tiff", "certainty.png",
                          "map.yaml", "run_config.yaml"}) {
        EXPECT_TRUE(fs::exists(dir / "maps" / f)) << f;
    }
    const core::MapF h = io::ReadMapTiff(dir / "maps" / "elevation.tiff");
    const core::MapF c = io::ReadMapTiff(dir / "maps" / "certainty.tiff");
    ASSERT_EQ(h.rows, 60);
    ASSERT_EQ(h.cols, 80);
    // Floor cells (rows 6..30 = x 0.15..0.75, cols 24..56 = y -0.4..0.4) are seen and flat.
    for (int row = 6; row < 30; ++row) {
        for (int col = 24; col < 56; ++col) {
            EXPECT_GT(c.at(row, col), 0.0F) << row << "," << col;
            EXPECT_NEAR(h.at(row, col), 0.0F, 1e-3) << row << "," << col;
        }
    }
    // Block top: x in [1.0, 1.3] -> rows 40..51, y in [-0.2, 0.2] -> cols 32..47 (inner cells).
    int top_cells = 0;
    for (int row = 42; row < 50; ++row) {
        for (int col = 34; col < 46; ++col) {
            if (c.at(row, col) > 0.0F) {
                ++top_cells;
                EXPECT_NEAR(h.at(row, col), kBlockTopM, 1e-3) << row << "," << col;
            }
        }
    }
    EXPECT_GT(top_cells, 60);

    const io::RunData back = io::ReadRunFile(dir / "run.h5");
    ASSERT_TRUE(back.maps.elevation_m.has_value());
    ASSERT_TRUE(back.maps.certainty.has_value());
    EXPECT_EQ(back.maps.elevation_m->data, h.data);
    EXPECT_EQ(back.maps.certainty->data, c.data);
    EXPECT_EQ(back.scans.size(), written.scans.size());
    EXPECT_EQ(back.truth.size(), written.truth.size());
}

TEST(MapCommand, RecordedRunWithoutLabelsOrGridGetsTheBeamsExtent) {
    const fs::path dir = FreshDir("recorded");
    io::WriteRunFile(dir / "rec.h5", FlatFloorRun(false));
    const Result r = Casmap("map " + (dir / "rec.h5").string() + " --threads 1");
    ASSERT_EQ(r.code, 0) << r.output;
    EXPECT_TRUE(fs::exists(dir / "rec_maps" / "elevation.tiff"));
    const io::RunMaps maps = io::ReadRunMaps(dir / "rec.h5");
    ASSERT_TRUE(maps.grid.has_value());
    EXPECT_EQ(std::fmod(std::abs(maps.grid->x0_m) + 1e-9, 0.025) < 1e-6, true);
    EXPECT_GT(maps.grid->rows, 40);
    EXPECT_FALSE(maps.truth_m.has_value());
    // Every cell with certainty holds the floor or the block top.
    for (std::size_t i = 0; i < maps.elevation_m->data.size(); ++i) {
        if (maps.certainty->data[i] > 0.0F) {
            const float z = maps.elevation_m->data[i];
            EXPECT_TRUE(std::abs(z) < 2e-3 || std::abs(z - kBlockTopM) < 2e-3) << z;
        }
    }
}

TEST(MapCommand, BadInputExitsTwoNamingIt) {
    const fs::path dir = FreshDir("bad");
    Result r = Casmap("map " + (dir / "none.h5").string());
    EXPECT_EQ(r.code, 2) << r.output;
    EXPECT_NE(r.output.find("none.h5"), std::string::npos) << r.output;

    io::WriteRunFile(dir / "run.h5", FlatFloorRun(false));
    r = Casmap("map " + (dir / "run.h5").string() + " --grid 0,0,0,10,10");
    EXPECT_EQ(r.code, 2) << r.output;
    EXPECT_NE(r.output.find("--grid"), std::string::npos) << r.output;

    r = Casmap("map " + (dir / "run.h5").string() + " --out /proc/casmap_cannot");
    EXPECT_EQ(r.code, 2) << r.output;
    EXPECT_NE(r.output.find("/proc/casmap_cannot"), std::string::npos) << r.output;
}

TEST(MapCommand, UnknownNanKalmanAndPrefilterModes) {
    const fs::path dir = FreshDir("modes");
    io::RunData with_grid = FlatFloorRun(false);
    with_grid.maps.grid = core::GridGeometry{0.0, -1.0, 0.025, 60, 80};
    io::WriteRunFile(dir / "run.h5", with_grid);
    const std::string run = (dir / "run.h5").string();

    Result r = Casmap("map " + run + " --out " + (dir / "zero").string());
    ASSERT_EQ(r.code, 0) << r.output;
    const core::MapF h0 = io::ReadMapTiff(dir / "zero" / "elevation.tiff");
    const core::MapF c0 = io::ReadMapTiff(dir / "zero" / "certainty.tiff");

    // NaN: the same maps except never-observed cells, which hold NaN instead of 0.
    r = Casmap("map " + run + " --unknown nan --out " + (dir / "nan").string());
    ASSERT_EQ(r.code, 0) << r.output;
    const core::MapF hn = io::ReadMapTiff(dir / "nan" / "elevation.tiff");
    int unknown = 0;
    for (std::size_t i = 0; i < hn.data.size(); ++i) {
        if (c0.data[i] == 0.0F) {
            ++unknown;
            EXPECT_TRUE(std::isnan(hn.data[i])) << i;
        } else {
            EXPECT_EQ(hn.data[i], h0.data[i]) << i;
        }
    }
    EXPECT_GT(unknown, 0);
    EXPECT_NE(io::ReadRunMaps(run).elevation_m->data.size(), 0U);

    // Kalman: floor and block top at their heights where observed; map.yaml says which mapper.
    r = Casmap("map " + run + " --mapper kalman --out " + (dir / "kalman").string());
    ASSERT_EQ(r.code, 0) << r.output;
    const core::MapF hk = io::ReadMapTiff(dir / "kalman" / "elevation.tiff");
    const core::MapF ck = io::ReadMapTiff(dir / "kalman" / "certainty.tiff");
    int seen = 0;
    for (std::size_t i = 0; i < hk.data.size(); ++i) {
        if (ck.data[i] > 0.0F) {
            ++seen;
            const float z = hk.data[i];
            EXPECT_TRUE(std::abs(z) < 5e-3 || std::abs(z - kBlockTopM) < 5e-3) << i << ": " << z;
        }
    }
    EXPECT_GT(seen, 500);
    const std::string yaml = test::ReadText(dir / "kalman" / "map.yaml");
    EXPECT_NE(yaml.find("mode: kalman"), std::string::npos) << yaml;

    // Consensus: the paper's certainty, heights at least as close to the truth on the floor.
    r = Casmap("map " + run + " --mapper consensus --out " + (dir / "consensus").string());
    ASSERT_EQ(r.code, 0) << r.output;
    const core::MapF& hp = h0;
    const core::MapF& cp = c0;
    const core::MapF hc = io::ReadMapTiff(dir / "consensus" / "elevation.tiff");
    const core::MapF cc = io::ReadMapTiff(dir / "consensus" / "certainty.tiff");
    ASSERT_EQ(cc.data, cp.data);
    for (std::size_t i = 0; i < hc.data.size(); ++i) {
        // A mean never exceeds the largest |z|, Eq. 6's height.
        EXPECT_LE(std::abs(hc.data[i]), std::abs(hp.data[i])) << i;
    }
    EXPECT_NE(test::ReadText(dir / "consensus" / "map.yaml").find("mode: consensus"),
              std::string::npos);

    // A pre-filter rejects beams (recorded in map.yaml) and the block still maps.
    r = Casmap("map " + run + " --prefilter range_jump --out " + (dir / "jump").string());
    ASSERT_EQ(r.code, 0) << r.output;
    EXPECT_NE(test::ReadText(dir / "jump" / "map.yaml").find("prefilter: range_jump"),
              std::string::npos);
    r = Casmap("map " + run + " --prefilter shadow --out " + (dir / "shadow").string());
    ASSERT_EQ(r.code, 0) << r.output;
    r = Casmap("map " + run + " --prefilter sweep_jump --set sweep_jump.max_angle_deg=5 --out " +
               (dir / "sweep").string());
    ASSERT_EQ(r.code, 0) << r.output;
    const std::string sweep_yaml = test::ReadText(dir / "sweep" / "map.yaml");
    EXPECT_NE(sweep_yaml.find("prefilter: sweep_jump"), std::string::npos) << sweep_yaml;
    EXPECT_NE(sweep_yaml.find("max_angle_deg: 5"), std::string::npos) << sweep_yaml;
    EXPECT_NE(test::ReadText(dir / "shadow" / "map.yaml").find("prefilter: shadow"),
              std::string::npos);
}

TEST(MapCommand, BadModeFlagsExitTwoNamingTheFlag) {
    const fs::path dir = FreshDir("badmodes");
    io::WriteRunFile(dir / "run.h5", FlatFloorRun(false));
    const std::string run = (dir / "run.h5").string();
    for (const std::string flag : {"--mapper", "--unknown", "--prefilter"}) {
        const Result r = Casmap("map " + run + " " + flag + " bogus");
        EXPECT_EQ(r.code, 2) << flag << ": " << r.output;
        EXPECT_NE(r.output.find(flag), std::string::npos) << r.output;
        EXPECT_NE(r.output.find("bogus"), std::string::npos) << r.output;
    }
    EXPECT_FALSE(fs::exists(dir / "run_maps"));
    // --set takes the parameters of the stages run, by the names bench and presets use.
    struct Case {
        std::string args;
        std::string needle;
    };
    for (const Case& c : std::vector<Case>{
             {"--set A=30", "not a mapping-stage parameter"},
             {"--set shadow.min_angle_deg=5", "the pre-filter is none"},
             {"--prefilter shadow --set range_jump.jump_min_m=0.2", "the pre-filter is shadow"},
             {"--set kalman.mahalanobis_gate=2", "the mapper mode is paper"},
             {"--prefilter shadow --set shadow.min_angle_deg=95",
              "--set: shadow.min_angle_deg = 95"},
             {"--prefilter range_jump --set range_jump.jump_min_m=0.04", "range_jump.margin_m"},
             {"--prefilter sweep_jump --set sweep_jump.jump_min_m=0.06", "sweep_jump.margin_m"},
             {"--prefilter sweep_jump --set sweep_jump.max_angle_deg=90",
              "sweep_jump.max_angle_deg = 90"},
             {"--set sweep_jump.margin_m=0.01", "the pre-filter is none"},
             {"--mapper kalman --set kalman.min_variance_m2=0", "kalman.min_variance_m2"},
             {"--set consensus.spread_m=0.03", "the mapper mode is paper"},
             {"--mapper consensus --set consensus.min_hits=1", "consensus.min_hits = 1"},
             {"--mapper consensus --set consensus.spread_m=-0.01", "consensus.spread_m"},
             {"--mapper median", "consensus"},
             {"--prefilter shadow --set shadow.window", "NAME=VALUE"}}) {
        const Result r = Casmap("map " + run + " " + c.args);
        EXPECT_EQ(r.code, 2) << c.args << ": " << r.output;
        EXPECT_NE(r.output.find(c.needle), std::string::npos) << c.args << ": " << r.output;
    }
    EXPECT_FALSE(fs::exists(dir / "run_maps"));
}

// The stage parameters reach the mapper and map.yaml records them.
TEST(MapCommand, SetsThePreFilterAndKalmanParameters) {
    const fs::path dir = FreshDir("stageset");
    io::RunData with_grid = FlatFloorRun(false);
    with_grid.maps.grid = core::GridGeometry{0.0, -1.0, 0.025, 60, 80};
    io::WriteRunFile(dir / "run.h5", with_grid);
    const std::string run = (dir / "run.h5").string();
    Result r = Casmap("map " + run +
                      " --prefilter shadow --set shadow.min_angle_deg=30 --set "
                      "shadow.neighbors=2 --out " +
                      (dir / "shadow").string());
    ASSERT_EQ(r.code, 0) << r.output;
    const YAML::Node yaml = YAML::LoadFile((dir / "shadow" / "map.yaml").string());
    EXPECT_EQ(yaml["mapper"]["shadow"]["min_angle_deg"].as<double>(), 30.0);
    EXPECT_EQ(yaml["mapper"]["shadow"]["neighbors"].as<int>(), 2);
    r = Casmap("map " + run + " --mapper kalman --set kalman.range_sigma_m=0.02 --out " +
               (dir / "kalman").string());
    ASSERT_EQ(r.code, 0) << r.output;
    const YAML::Node k = YAML::LoadFile((dir / "kalman" / "map.yaml").string());
    EXPECT_EQ(k["mapper"]["kalman"]["range_sigma_m"].as<double>(), 0.02);
    EXPECT_FALSE(k["mapper"]["shadow"]);
    r = Casmap("map " + run + " --mapper consensus --set consensus.spread_m=0.03 --set " +
               "consensus.min_hits=4 --out " + (dir / "consensus").string());
    ASSERT_EQ(r.code, 0) << r.output;
    const YAML::Node c = YAML::LoadFile((dir / "consensus" / "map.yaml").string());
    EXPECT_EQ(c["mapper"]["consensus"]["spread_m"].as<double>(), 0.03);
    EXPECT_EQ(c["mapper"]["consensus"]["min_hits"].as<int>(), 4);
    EXPECT_FALSE(c["mapper"]["kalman"]);
}

}  // namespace
}  // namespace casmap
