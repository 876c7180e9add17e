// The Kalman elevation mapper (Fankhauser et al.): per-scan lowest point, 1-D fusion, gate.
#include "casmap/mapper/kalman_mapper.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "casmap/core/input_error.hpp"

namespace casmap::mapper {
namespace {

constexpr double kDeg = std::numbers::pi / 180.0;

KalmanMapperConfig Config() {
    KalmanMapperConfig c;
    c.grid = core::GridGeometry{0.0, -2.0, 0.025, 160, 160};
    return c;
}

TEST(KalmanMapper, FusesTwoMeasurementsByTheirVariances) {
    KalmanMapper m(Config());
    m.Fuse(5, 0.10, 4e-4);
    m.Fuse(5, 0.13, 2e-4);  // inside the gate: 0.03 < 2.5 * 0.02
    EXPECT_NEAR(m.elevation().data[5], (4e-4 * 0.13 + 2e-4 * 0.10) / 6e-4, 1e-6);
    EXPECT_NEAR(m.variance().data[5], 4e-4 * 2e-4 / 6e-4, 1e-9);
    EXPECT_EQ(m.certainty().data[5], 6.0F);
}

TEST(KalmanMapper, OutlierInflatesVarianceInsteadOfFusing) {
    KalmanMapper m(Config());
    m.Fuse(7, 0.0, 1e-4);
    m.Fuse(7, 0.5, 1e-4);  // 50 sigma away
    EXPECT_FLOAT_EQ(m.elevation().data[7], 0.0F);
    EXPECT_NEAR(m.variance().data[7], 1e-4 + 1e-4, 1e-9);
    EXPECT_TRUE(std::isnan(m.variance().data[8]));  // unknown
}

TEST(KalmanMapper, VarianceGrowsWithRange) {
    const KalmanMapper m(Config());
    EXPECT_LT(m.PointVariance(1.0, -0.5), m.PointVariance(4.0, -0.5));
    EXPECT_NEAR(m.PointVariance(2.0, -1.0), 0.005 * 0.005, 1e-12);  // straight down: range only
}

TEST(KalmanMapper, MapsAFlatFloorFromAScanWithTheLowestPointPerCell) {
    // Sensor 1 m above the floor pitched 30 deg down; every beam hits z = 0.
    const core::Pose pose =
        core::PoseFromXyzRpy(Eigen::Vector3d(0, 0, 1.0), Eigen::Vector3d(0, 30 * kDeg, 0));
    const core::Trajectory traj({{0.0, pose}, {1.0, pose}});
    core::Scan s;
    s.stamp_s = 0.5;
    s.start_angle_rad = -30 * kDeg;
    s.angle_step_rad = kDeg;
    s.beam_period_s = (1.0 / 75.0) / 360.0;
    for (int i = 0; i <= 60; ++i) {
        const double a = s.start_angle_rad + i * s.angle_step_rad;
        // Range to z = 0 along (cos a, sin a, 0) rotated by the pitch: z drops l cos a sin 30.
        s.beams.push_back(
            core::Beam{static_cast<float>(1.0 / (std::cos(a) * 0.5)), core::BeamStatus::kOk, 0});
    }
    KalmanMapper m(Config());
    m.AddScan(s, traj);
    EXPECT_EQ(m.stats().beams_mapped, 61U);
    int known = 0;
    for (std::size_t n = 0; n < m.elevation().data.size(); ++n) {
        if (m.certainty().data[n] > 0.0F) {
            EXPECT_NEAR(m.elevation().data[n], 0.0, 1e-4);
            ++known;
        }
    }
    EXPECT_GT(known, 20);
}

TEST(KalmanMapper, RejectsBadSettingsNamingTheField) {
    KalmanMapperConfig c = Config();
    c.mahalanobis_gate = 0.0;
    try {
        KalmanMapper m(c);
        FAIL();
    } catch (const InputError& e) {
        EXPECT_NE(std::string(e.what()).find("kalman.mahalanobis_gate"), std::string::npos);
    }
}

}  // namespace
}  // namespace casmap::mapper
