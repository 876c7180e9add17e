#include "casmap/rig/pose_error.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "casmap/core/input_error.hpp"

namespace casmap::rig {
namespace {

constexpr double kDeg = std::numbers::pi / 180.0;

/// A straight 1 m/s run sampled at 1 kHz, pitched 30 deg down.
core::Trajectory Straight(int samples) {
    std::vector<core::TimedPose> poses;
    for (int i = 0; i < samples; ++i) {
        const double t = i * 1e-3;
        poses.push_back({t, core::PoseFromXyzRpy(Eigen::Vector3d(t, 0.0, 1.0),
                                                 Eigen::Vector3d(0.0, 30.0 * kDeg, 0.0))});
    }
    return core::Trajectory(std::move(poses));
}

/// Per-sample errors (position, attitude rpy in rad) of `estimate` against `truth`.
void Errors(const core::Trajectory& truth,
            const core::Trajectory& estimate,
            std::vector<Eigen::Vector3d>& pos,
            std::vector<Eigen::Vector3d>& att) {
    for (std::size_t i = 0; i < truth.size(); ++i) {
        const core::Pose& a = truth.samples()[i].world_T_sensor;
        const core::Pose& b = estimate.samples()[i].world_T_sensor;
        pos.push_back(b.translation - a.translation);
        att.push_back(core::RpyFromQuaternion(b.rotation) - core::RpyFromQuaternion(a.rotation));
    }
}

double StdDev(const std::vector<double>& v) {
    double s = 0.0, s2 = 0.0;
    for (const double x : v) {
        s += x;
        s2 += x * x;
    }
    const double n = static_cast<double>(v.size());
    return std::sqrt(s2 / n - (s / n) * (s / n));
}

TEST(PoseError, DefaultsAreValidAndDisabledIsIdentity) {
    EXPECT_NO_THROW(PoseErrorConfig{}.Validate());
    const core::Trajectory truth = Straight(100);
    const core::Trajectory same = ApplyPoseError(truth, PoseErrorConfig{});
    for (std::size_t i = 0; i < truth.size(); ++i) {
        EXPECT_EQ(same.samples()[i].world_T_sensor.translation,
                  truth.samples()[i].world_T_sensor.translation);
    }
}

TEST(PoseError, BiasShiftsEveryPoseExactly) {
    PoseErrorConfig config;
    config.enabled = true;
    config.position_bias_m = Eigen::Vector3d(0.01, -0.02, 0.03);
    config.attitude_bias_deg = Eigen::Vector3d(1.0, -2.0, 0.5);
    const core::Trajectory truth = Straight(50);
    std::vector<Eigen::Vector3d> pos, att;
    Errors(truth, ApplyPoseError(truth, config), pos, att);
    for (std::size_t i = 0; i < pos.size(); ++i) {
        EXPECT_TRUE(pos[i].isApprox(config.position_bias_m, 1e-9));
        EXPECT_TRUE(att[i].isApprox(config.attitude_bias_deg * kDeg, 1e-9));
    }
}

TEST(PoseError, JitterHasTheConfiguredSigma) {
    PoseErrorConfig config;
    config.enabled = true;
    config.seed = 7;
    config.position_jitter_m = 0.005;
    config.attitude_jitter_deg = 0.2;
    const core::Trajectory truth = Straight(20000);
    std::vector<Eigen::Vector3d> pos, att;
    Errors(truth, ApplyPoseError(truth, config), pos, att);
    std::vector<double> px, az;
    for (std::size_t i = 0; i < pos.size(); ++i) {
        px.push_back(pos[i].x());
        az.push_back(att[i].y());
    }
    EXPECT_NEAR(StdDev(px), 0.005, 0.005 * 0.05) << "seed 7";
    EXPECT_NEAR(StdDev(az), 0.2 * kDeg, 0.2 * kDeg * 0.05) << "seed 7";
}

TEST(PoseError, RandomWalkStepsScaleWithRootDt) {
    PoseErrorConfig config;
    config.enabled = true;
    config.seed = 11;
    config.position_random_walk_m_per_sqrt_s = 0.02;
    config.attitude_random_walk_deg_per_sqrt_s = 0.5;
    const core::Trajectory truth = Straight(20000);
    std::vector<Eigen::Vector3d> pos, att;
    Errors(truth, ApplyPoseError(truth, config), pos, att);
    std::vector<double> dz, droll;
    for (std::size_t i = 1; i < pos.size(); ++i) {
        dz.push_back(pos[i].z() - pos[i - 1].z());
        droll.push_back(att[i].x() - att[i - 1].x());
    }
    const double root_dt = std::sqrt(1e-3);
    EXPECT_NEAR(StdDev(dz), 0.02 * root_dt, 0.02 * root_dt * 0.05) << "seed 11";
    EXPECT_NEAR(StdDev(droll), 0.5 * kDeg * root_dt, 0.5 * kDeg * root_dt * 0.05) << "seed 11";
    EXPECT_EQ(pos[0], Eigen::Vector3d::Zero());  // the walk starts at zero
}

TEST(PoseError, SameSeedSameOutputOtherSeedDiffers) {
    PoseErrorConfig config;
    config.enabled = true;
    config.position_jitter_m = 0.01;
    const core::Trajectory truth = Straight(100);
    const core::Trajectory a = ApplyPoseError(truth, config);
    const core::Trajectory b = ApplyPoseError(truth, config);
    config.seed = 2;
    const core::Trajectory c = ApplyPoseError(truth, config);
    EXPECT_EQ(a.samples()[50].world_T_sensor.translation,
              b.samples()[50].world_T_sensor.translation);
    EXPECT_NE(a.samples()[50].world_T_sensor.translation,
              c.samples()[50].world_T_sensor.translation);
}

TEST(PoseError, RejectsNegativeSigmaNamingTheField) {
    PoseErrorConfig config;
    config.position_jitter_m = -1.0;
    EXPECT_THAT([&] { config.Validate("rig.yaml"); },
                testing::ThrowsMessage<InputError>(
                    testing::HasSubstr("rig.yaml: pose_error.position_jitter_m = -1")));
}

}  // namespace
}  // namespace casmap::rig
