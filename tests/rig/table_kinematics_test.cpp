#include "casmap/rig/table_kinematics.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <random>

namespace casmap::rig {
namespace {

constexpr double kDeg = std::numbers::pi / 180.0;

/// The paper's Eq. 2, typed as printed (with r read as t, see docs/rigs.md), in the paper's
/// frames: x_n to the right, y_n along the motion, z_n up; beta from the scanner's right.
Eigen::Vector3d PaperEq2(double l,
                         double beta,
                         double theta,
                         double phi,
                         double t,
                         double m,
                         double q,
                         double p,
                         double u,
                         double v,
                         double w) {
    const double cf = std::cos(phi), sf = std::sin(phi);
    const double ct = std::cos(theta), st = std::sin(theta);
    const double cb = std::cos(beta), sb = std::sin(beta);
    return {l * cf * cb + p * sf + t + u,
            l * ct * sb + l * st * sf * cb - q * st + m * ct - p * st * cf + v,
            l * st * sb - l * ct * sf * cb + q * ct + m * st + p * ct * cf + w};
}

TEST(TableKinematics, ZeroJointsStackTheOffsets) {
    TableGeometry g;
    g.pitch_axis_origin_m = {1.0, 2.0, 0.9};
    g.pitch_to_roll_m = {0.01, 0.02, 0.05};
    g.roll_to_sensor_m = 0.1;
    const core::Pose pose = TableForwardKinematics(g, TableJoints{0.5, 0.0, 0.0});
    EXPECT_TRUE(pose.translation.isApprox(Eigen::Vector3d(1.51, 2.02, 1.05), 1e-12));
    EXPECT_TRUE(pose.rotation.isApprox(Eigen::Quaterniond::Identity()));
}

TEST(TableKinematics, PositivePitchLooksDown) {
    const core::Pose pose = TableForwardKinematics(TableGeometry{}, {0.0, 0.0, 30.0 * kDeg});
    const Eigen::Vector3d forward = pose.rotation * Eigen::Vector3d::UnitX();
    EXPECT_NEAR(forward.z(), -0.5, 1e-12);
    const Eigen::Vector3d rpy = core::RpyFromQuaternion(pose.rotation);
    EXPECT_NEAR(rpy.y(), 30.0 * kDeg, 1e-12);
}

TEST(TableKinematics, BeamPointsMatchThePapersEq2) {
    // Our frames from the paper's: x = y_n, y = -x_n, z = z_n; pitch = -theta, roll = phi;
    // beam angle alpha = beta - 90 deg; (u, v, w) = (-y0, linear, z0); (t, m, q) = (-b, a, c)
    // for pitch_to_roll (a, b, c).
    std::mt19937_64 rng(20240601);
    std::printf("seed 20240601\n");
    std::uniform_real_distribution<double> uni(-1.0, 1.0);
    for (int trial = 0; trial < 200; ++trial) {
        TableGeometry g;
        g.pitch_axis_origin_m = {0.0, 0.5 * uni(rng), 1.0 + 0.2 * uni(rng)};
        g.pitch_to_roll_m = {0.1 * uni(rng), 0.1 * uni(rng), 0.1 * uni(rng)};
        g.roll_to_sensor_m = 0.1 + 0.05 * uni(rng);
        const TableJoints j{2.0 * uni(rng), 15.0 * kDeg * uni(rng), (32.5 + 7.5 * uni(rng)) * kDeg};
        const double l = 3.0 + 2.0 * uni(rng);
        const int k = static_cast<int>(1 + std::lround(90.0 * (1.0 + uni(rng))));  // 1..181
        const double beta = (k - 1) * kDeg;                                        // Eq. 3
        const double alpha = beta - 90.0 * kDeg;
        const core::Pose pose = TableForwardKinematics(g, j);
        const Eigen::Vector3d ours =
            pose * Eigen::Vector3d(l * std::cos(alpha), l * std::sin(alpha), 0.0);
        const Eigen::Vector3d paper =
            PaperEq2(l, beta, -j.pitch_rad, j.roll_rad, -g.pitch_to_roll_m.y(),
                     g.pitch_to_roll_m.x(), g.pitch_to_roll_m.z(), g.roll_to_sensor_m,
                     -g.pitch_axis_origin_m.y(), j.linear_m, g.pitch_axis_origin_m.z());
        ASSERT_NEAR(ours.x(), paper.y(), 1e-12) << "trial " << trial;
        ASSERT_NEAR(ours.y(), -paper.x(), 1e-12) << "trial " << trial;
        ASSERT_NEAR(ours.z(), paper.z(), 1e-12) << "trial " << trial;
    }
}

}  // namespace
}  // namespace casmap::rig
