#include "casmap/mapper/terrain_mapper.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <random>

#include "casmap/core/input_error.hpp"

namespace casmap::mapper {
namespace {

constexpr double kDeg = std::numbers::pi / 180.0;

TerrainMapperConfig SmallGrid() {
    TerrainMapperConfig cfg;
    cfg.grid = core::GridGeometry{0.0, -1.0, 0.025, 160, 80};  // x in [0, 4), y in [-1, 1)
    return cfg;
}

TEST(TerrainMapperConfig, DefaultsAreValidWithAGrid) {
    EXPECT_NO_THROW(SmallGrid().Validate());
    TerrainMapperConfig bad = SmallGrid();
    bad.a = 0;
    EXPECT_THROW(bad.Validate(), InputError);
    bad = SmallGrid();
    bad.delta_l_m = -1.0;
    EXPECT_THROW(bad.Validate(), InputError);
    bad = SmallGrid();
    bad.scan_period_s = 0.0;
    EXPECT_THROW(bad.Validate(), InputError);
}

TEST(TerrainMapper, Eq5AndEq6HandComputed) {
    TerrainMapper m(SmallGrid());  // a = 3
    const Eigen::Vector3d cell(1.01, 0.01, 0.0);
    const auto at = [&](double z, double dz) {
        ASSERT_TRUE(m.AddPoint(Eigen::Vector3d(cell.x(), cell.y(), z), dz));
    };
    const core::Cell idx = *m.config().grid.CellOf(cell.x(), cell.y());
    const auto h = [&] { return m.elevation().at(idx.row, idx.col); };
    const auto c = [&] { return m.certainty().at(idx.row, idx.col); };
    EXPECT_EQ(h(), 0.0F);  // unknown: 0 and 0
    EXPECT_EQ(c(), 0.0F);
    at(0.10, 0.02);  // first hit: c = 0 -> c = a; |0.10| > 0 -> h = 0.10
    EXPECT_EQ(c(), 3.0F);
    EXPECT_FLOAT_EQ(h(), 0.10F);
    at(0.11, 0.02);  // |0.11 - 0.10| = 0.01 <= 0.02 -> c = 6; h = 0.11
    EXPECT_EQ(c(), 6.0F);
    EXPECT_FLOAT_EQ(h(), 0.11F);
    at(0.50, 0.02);  // |0.50 - 0.11| > 0.02 -> c stays 6; |0.50| > |0.11| -> h = 0.50
    EXPECT_EQ(c(), 6.0F);
    EXPECT_FLOAT_EQ(h(), 0.50F);
    at(0.45, -0.06);  // |0.45 - 0.50| = 0.05 <= |-0.06| -> c = 9; h stays 0.50
    EXPECT_EQ(c(), 9.0F);
    EXPECT_FLOAT_EQ(h(), 0.50F);
    at(-0.60, 0.02);  // Eq. 6 compares magnitudes: |-0.60| > |0.50| -> h = -0.60
    EXPECT_EQ(c(), 9.0F);
    EXPECT_FLOAT_EQ(h(), -0.60F);
    EXPECT_FALSE(m.AddPoint(Eigen::Vector3d(-0.5, 0.0, 1.0), 0.1));  // off the grid
}

TEST(TerrainMapper, FirstHitAtZeroHeightCountsButKeepsZero) {
    TerrainMapper m(SmallGrid());
    ASSERT_TRUE(m.AddPoint(Eigen::Vector3d(2.0, 0.0, 0.0), 0.0));
    const core::Cell idx = *m.config().grid.CellOf(2.0, 0.0);
    EXPECT_EQ(m.certainty().at(idx.row, idx.col), 3.0F);
    EXPECT_EQ(m.elevation().at(idx.row, idx.col), 0.0F);
}

double Z(double range, double roll, double pitch, double yaw, double angle) {
    const core::Pose pose =
        core::PoseFromXyzRpy(Eigen::Vector3d(0.3, -0.2, 0.9), Eigen::Vector3d(roll, pitch, yaw));
    return BeamToWorld(pose, angle, range).z();
}

TEST(Eq4, PartialsMatchFiniteDifferences) {
    const unsigned seed = 12345;
    std::mt19937 rng(seed);
    std::uniform_real_distribution<double> u(-1.0, 1.0);
    for (int n = 0; n < 200; ++n) {
        const double roll = 15 * kDeg * u(rng);
        const double pitch = 40 * kDeg * u(rng);
        const double yaw = 180 * kDeg * u(rng);
        const double angle = 90 * kDeg * u(rng);
        const double range = 2.0 + 1.5 * u(rng);
        const core::Pose pose = core::PoseFromXyzRpy(Eigen::Vector3d(0.3, -0.2, 0.9),
                                                     Eigen::Vector3d(roll, pitch, yaw));
        const ZPartials d = BeamZPartials(pose.rotation.toRotationMatrix(), angle, range);
        const double e = 1e-6;
        const double fd_l =
            (Z(range + e, roll, pitch, yaw, angle) - Z(range - e, roll, pitch, yaw, angle)) /
            (2 * e);
        const double fd_r =
            (Z(range, roll + e, pitch, yaw, angle) - Z(range, roll - e, pitch, yaw, angle)) /
            (2 * e);
        const double fd_p =
            (Z(range, roll, pitch + e, yaw, angle) - Z(range, roll, pitch - e, yaw, angle)) /
            (2 * e);
        ASSERT_NEAR(d.d_range, fd_l, 1e-7) << "seed " << seed << " sample " << n;
        ASSERT_NEAR(d.d_roll, fd_r, 1e-7) << "seed " << seed << " sample " << n;
        ASSERT_NEAR(d.d_pitch, fd_p, 1e-7) << "seed " << seed << " sample " << n;
    }
}

TEST(Eq4, ReducesToThePapersFormOnTheTable) {
    // Paper Eq. 2 with zero lever arms: theta = -pitch (about the across-track axis),
    // phi = roll, beta = angle + 90 deg; Eq. 4 with magnitudes.
    const double l = 2.1;
    const double angle = 20 * kDeg;
    const double roll = 8 * kDeg;
    const double pitch = 32 * kDeg;
    const double d_roll = 0.5 * kDeg;
    const double d_pitch = -0.4 * kDeg;
    const double dy = 1.0 / 75.0;  // 1 m/s for one scan period, along world x
    const double th = -pitch;
    const double ph = roll;
    const double b = angle + 90 * kDeg;
    const double dz_dl = std::sin(th) * std::sin(b) - std::cos(th) * std::sin(ph) * std::cos(b);
    const double dz_dth =
        l * std::cos(th) * std::sin(b) + l * std::sin(th) * std::sin(ph) * std::cos(b);
    const double dz_dph = -l * std::cos(th) * std::cos(ph) * std::cos(b);
    const double paper = std::abs(-dy * std::tan(th)) + std::abs(dz_dl) * 0.032 +
                         std::abs(dz_dth * -d_pitch) + std::abs(dz_dph * d_roll);
    SensorState s;
    s.world_R_sensor = core::QuaternionFromRpy(roll, pitch, 0.0).toRotationMatrix();
    s.motion.displacement_m = Eigen::Vector3d(dy, 0.0, 0.0);
    s.motion.d_roll_rad = d_roll;
    s.motion.d_pitch_rad = d_pitch;
    EXPECT_NEAR(DeltaZMax(s, angle, l, 0.032), paper, 1e-12);
}

TEST(Eq4, MotionBetweenGivesRollAndPitchChange) {
    const core::Pose a = core::PoseFromXyzRpy(Eigen::Vector3d(1, 2, 3),
                                              Eigen::Vector3d(10 * kDeg, 30 * kDeg, 50 * kDeg));
    const core::Pose b = core::PoseFromXyzRpy(Eigen::Vector3d(1.5, 2, 2.9),
                                              Eigen::Vector3d(12 * kDeg, 27 * kDeg, 55 * kDeg));
    const BeamMotion m = MotionBetween(a, b);
    EXPECT_NEAR(m.d_roll_rad, 2 * kDeg, 1e-12);
    EXPECT_NEAR(m.d_pitch_rad, -3 * kDeg, 1e-12);
    EXPECT_NEAR((m.displacement_m - Eigen::Vector3d(0.5, 0, -0.1)).norm(), 0.0, 1e-12);
    const core::Pose c =
        core::PoseFromXyzRpy(Eigen::Vector3d::Zero(), Eigen::Vector3d(179 * kDeg, 0, 0));
    const core::Pose d =
        core::PoseFromXyzRpy(Eigen::Vector3d::Zero(), Eigen::Vector3d(-179 * kDeg, 0, 0));
    EXPECT_NEAR(MotionBetween(c, d).d_roll_rad, 2 * kDeg, 1e-12);  // wraps
}

core::Scan ThreeBeamScan(double stamp_s) {
    core::Scan scan;
    scan.stamp_s = stamp_s;
    scan.start_angle_rad = -10 * kDeg;
    scan.angle_step_rad = 10 * kDeg;
    scan.beam_period_s = (1.0 / 75.0) / 360.0;
    scan.beams.resize(3);
    for (auto& b : scan.beams) {
        b.range_m = 2.0F;
        b.status = core::BeamStatus::kOk;
    }
    return scan;
}

core::Trajectory MovingTable(double pitch_rad) {
    // 1 m/s along x, sensor 1 m high, pitched down; samples every 1 ms for 1 s.
    std::vector<core::TimedPose> samples;
    for (int n = 0; n <= 1000; ++n) {
        const double t = n * 1e-3;
        samples.push_back({t, core::PoseFromXyzRpy(Eigen::Vector3d(t, 0.0, 1.0),
                                                   Eigen::Vector3d(0.0, pitch_rad, 0.0))});
    }
    return core::Trajectory(samples);
}

TEST(TerrainMapper, PlacesEachBeamWithThePoseAtItsOwnTime) {
    TerrainMapper m(SmallGrid());
    const core::Trajectory traj = MovingTable(30 * kDeg);
    core::Scan scan = ThreeBeamScan(0.5);
    scan.beam_period_s = 0.02;  // exaggerated so the beams' poses differ by 2 cells
    m.AddScan(scan, traj);
    EXPECT_EQ(m.stats().beams_mapped, 3U);
    for (std::size_t i = 0; i < 3; ++i) {
        const core::Pose pose = *traj.PoseAt(scan.BeamTime(i));
        const Eigen::Vector3d p = BeamToWorld(pose, scan.BeamAngle(i), 2.0);
        const core::Cell cell = *m.config().grid.CellOf(p.x(), p.y());
        EXPECT_FLOAT_EQ(m.elevation().at(cell.row, cell.col), static_cast<float>(p.z())) << i;
        EXPECT_EQ(m.certainty().at(cell.row, cell.col), 3.0F) << i;
    }
}

TEST(TerrainMapper, AddBeamIsEq1PlusEq4) {
    TerrainMapper m(SmallGrid());
    const core::Pose pose =
        core::PoseFromXyzRpy(Eigen::Vector3d(0.5, 0.1, 1.0), Eigen::Vector3d(0.05, 0.5, 0.2));
    SensorState s;
    s.world_R_sensor = pose.rotation.toRotationMatrix();
    s.origin_m = pose.translation;
    s.motion.displacement_m = Eigen::Vector3d(0.013, 0.0, 0.0);
    m.AddBeam(s, 0.3, 1.7);
    const Eigen::Vector3d p = BeamToWorld(pose, 0.3, 1.7);
    const core::Cell cell = *m.config().grid.CellOf(p.x(), p.y());
    EXPECT_FLOAT_EQ(m.elevation().at(cell.row, cell.col), static_cast<float>(p.z()));
    // A second hit within Delta z_max of the first adds a; one just beyond does not.
    const double dz = DeltaZMax(s, 0.3, 1.7, 0.032);
    ASSERT_TRUE(m.AddPoint(Eigen::Vector3d(p.x(), p.y(), p.z() - 0.99 * dz), dz));
    EXPECT_EQ(m.certainty().at(cell.row, cell.col), 6.0F);
    ASSERT_TRUE(m.AddPoint(Eigen::Vector3d(p.x(), p.y(), p.z() - 1.01 * dz), dz));
    EXPECT_EQ(m.certainty().at(cell.row, cell.col), 6.0F);
}

TEST(TerrainMapper, BeamsWithoutReturnOrPoseUpdateNothing) {
    TerrainMapper m(SmallGrid());
    const core::Trajectory traj = MovingTable(30 * kDeg);
    core::Scan scan = ThreeBeamScan(0.5);
    scan.beams[0].status = core::BeamStatus::kNoReturn;
    scan.beams[1].status = core::BeamStatus::kDazzle;
    scan.beams[2].status = core::BeamStatus::kOutOfRange;
    m.AddScan(scan, traj);
    core::Scan late = ThreeBeamScan(5.0);  // after the trajectory ends
    m.AddScan(late, traj);
    EXPECT_EQ(m.stats().beams_seen, 6U);
    EXPECT_EQ(m.stats().beams_not_ok, 3U);
    EXPECT_EQ(m.stats().beams_no_pose, 3U);
    EXPECT_EQ(m.stats().beams_mapped, 0U);
    for (std::size_t i = 0; i < m.certainty().data.size(); ++i) {
        ASSERT_EQ(m.certainty().data[i], 0.0F);
        ASSERT_EQ(m.elevation().data[i], 0.0F);
    }
}

TEST(TerrainMapper, FlatFloorScansAccumulateCertainty) {
    // The table moving at 1 m/s over a flat floor at z = 0: consecutive hits in a cell differ
    // by at most the noise-free 0, so every hit after the first adds a as well (Eq. 5).
    TerrainMapper m(SmallGrid());
    const core::Trajectory traj = MovingTable(30 * kDeg);
    const double range = 1.0 / std::sin(30 * kDeg);  // straight ahead hits z = 0
    for (int n = 0; n < 30; ++n) {
        core::Scan scan;
        scan.stamp_s = 0.1 + n / 75.0;
        scan.angle_step_rad = kDeg;
        scan.beam_period_s = 0.0;
        scan.beams.assign(1, core::Beam{static_cast<float>(range), core::BeamStatus::kOk, 0});
        m.AddScan(scan, traj);
    }
    float total = 0.0F;
    float max_h = 0.0F;
    for (std::size_t i = 0; i < m.certainty().data.size(); ++i) {
        total += m.certainty().data[i];
        max_h = std::max(max_h, std::abs(m.elevation().data[i]));
    }
    EXPECT_EQ(total, 90.0F);  // 30 beams x a
    EXPECT_LT(max_h, 1e-9F);
}

}  // namespace
}  // namespace casmap::mapper
