#include "casmap/core/trajectory.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "casmap/core/input_error.hpp"

namespace casmap::core {
namespace {

constexpr double kDeg = std::numbers::pi / 180.0;

TEST(Pose, RpyRoundTrip) {
    const Eigen::Vector3d rpy(10 * kDeg, 25 * kDeg, -40 * kDeg);
    const Eigen::Vector3d back = RpyFromQuaternion(QuaternionFromRpy(rpy.x(), rpy.y(), rpy.z()));
    EXPECT_NEAR(back.x(), rpy.x(), 1e-12);
    EXPECT_NEAR(back.y(), rpy.y(), 1e-12);
    EXPECT_NEAR(back.z(), rpy.z(), 1e-12);
}

TEST(Pose, PositivePitchIsNoseDown) {
    const Pose pose = PoseFromXyzRpy(Eigen::Vector3d::Zero(), Eigen::Vector3d(0, 30 * kDeg, 0));
    const Eigen::Vector3d forward = pose * Eigen::Vector3d::UnitX();
    EXPECT_NEAR(forward.z(), -std::sin(30 * kDeg), 1e-12);
    EXPECT_NEAR(forward.x(), std::cos(30 * kDeg), 1e-12);
}

TEST(Pose, InverseComposesToIdentity) {
    const Pose pose = PoseFromXyzRpy({1, 2, 3}, {0.1, 0.2, 0.3});
    const Pose id = pose * pose.Inverse();
    EXPECT_NEAR(id.translation.norm(), 0.0, 1e-12);
    EXPECT_NEAR(id.rotation.angularDistance(Eigen::Quaterniond::Identity()), 0.0, 1e-12);
}

TEST(Trajectory, InterpolatesLinearlyAndSlerps) {
    const Trajectory traj({{0.0, PoseFromXyzRpy({0, 0, 0}, {0, 0, 0})},
                           {1.0, PoseFromXyzRpy({2, 0, 1}, {0, 0, 90 * kDeg})}});
    const std::optional<Pose> mid = traj.PoseAt(0.25);
    ASSERT_TRUE(mid.has_value());
    EXPECT_NEAR(mid->translation.x(), 0.5, 1e-12);
    EXPECT_NEAR(mid->translation.z(), 0.25, 1e-12);
    EXPECT_NEAR(RpyFromQuaternion(mid->rotation).z(), 22.5 * kDeg, 1e-9);
}

TEST(Trajectory, NoPoseOutsideItsSpan) {
    const Trajectory traj({{0.0, Pose{}}, {1.0, Pose{}}});
    EXPECT_FALSE(traj.PoseAt(-0.001).has_value());
    EXPECT_FALSE(traj.PoseAt(1.001).has_value());
    EXPECT_TRUE(traj.PoseAt(1.0).has_value());
}

TEST(Trajectory, RejectsNonIncreasingStamps) {
    EXPECT_THROW(Trajectory({{1.0, Pose{}}, {1.0, Pose{}}}), InputError);
}

}  // namespace
}  // namespace casmap::core
