#include "casmap/rig/table.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "casmap/core/input_error.hpp"

namespace casmap::rig {
namespace {

constexpr double kDeg = std::numbers::pi / 180.0;

/// A short course keeps the runs (and the tests) short: 0.5 m of course.
TableConfig ShortCourse() {
    TableConfig config;
    config.course.start_x_m = 0.0;
    config.course.end_x_m = 0.5;
    return config;
}

double AngleBetween(const Eigen::Quaterniond& a, const Eigen::Quaterniond& b) {
    return a.angularDistance(b);
}

TEST(Table, DefaultsAreValid) { EXPECT_NO_THROW(TableConfig{}.Validate()); }

TEST(Table, ParsesMotionNames) {
    for (const Motion m : {Motion::kT, Motion::kTR, Motion::kTP, Motion::kTRP}) {
        EXPECT_EQ(ParseMotion(MotionName(m)), m);
    }
    EXPECT_THAT([] { (void)ParseMotion("TX"); },
                testing::ThrowsMessage<InputError>(testing::HasSubstr("motion = TX")));
}

TEST(Table, TranslationHoldsAttitudeAndSpeedAfterRamp) {
    const TableConfig config = ShortCourse();
    const TableRun run = RunTable(config, Motion::kT);
    const auto& samples = run.trajectory.samples();
    ASSERT_GT(samples.size(), 100U);
    double max_speed_err = 0.0;
    double max_att_err = 0.0;
    int cruise_samples = 0;
    for (std::size_t i = 1; i < samples.size(); ++i) {
        const double t = samples[i].stamp_s;
        const Eigen::Vector3d rpy = core::RpyFromQuaternion(samples[i].world_T_sensor.rotation);
        max_att_err = std::max({max_att_err, std::abs(rpy.x()), std::abs(rpy.z()),
                                std::abs(rpy.y() - config.mount_pitch_deg * kDeg)});
        if (t > config.speed_ramp_s && t < run.schedule.Duration() - config.speed_ramp_s) {
            const double v = (samples[i].world_T_sensor.translation.x() -
                              samples[i - 1].world_T_sensor.translation.x()) /
                             (t - samples[i - 1].stamp_s);
            max_speed_err = std::max(max_speed_err, std::abs(v - config.speed_m_s));
            ++cruise_samples;
        }
    }
    EXPECT_GT(cruise_samples, 450);
    EXPECT_LT(max_att_err, 0.01 * kDeg);
    EXPECT_LT(max_speed_err, 1e-3);
    // The height stays at the configured mount height.
    EXPECT_NEAR(samples.back().world_T_sensor.translation.z(), config.sensor_height_m, 1e-3);
}

TEST(Table, RunLastsAsLongAsTheCourseNeeds) {
    // T at pitch p and height h with roll 0: every beam meets the floor on the line
    // x = x_sensor + h / tan(p). The line must reach start_x when the ramp ends and end_x
    // when the deceleration begins; the run is 2 ramps + course length / speed.
    TableConfig config = ShortCourse();
    config.course.start_x_m = 1.0;
    config.course.end_x_m = 2.2;
    config.speed_m_s = 0.8;
    config.speed_ramp_s = 0.3;
    const TableRun run = RunTable(config, Motion::kT);
    const double length_s = 2 * 0.3 + 1.2 / 0.8;
    EXPECT_NEAR(run.trajectory.EndTime() - run.trajectory.StartTime(), length_s, 1.5e-3);
    const double ahead_m = config.sensor_height_m / std::tan(config.mount_pitch_deg * kDeg);
    const core::Pose at_cruise = *run.trajectory.PoseAt(0.3);
    const core::Pose at_brake = *run.trajectory.PoseAt(length_s - 0.3);
    EXPECT_NEAR(at_cruise.translation.x() + ahead_m, 1.0, 1e-3);
    EXPECT_NEAR(at_brake.translation.x() + ahead_m, 2.2, 1e-3);
}

TEST(Table, RollPitchAndRatesStayInsideLimitsForTrp) {
    TableConfig config = ShortCourse();
    config.roll_profile = {ProfileShape::kTriangle, 0.0, 14.5, 2.0, 0.0};    // 29 deg/s
    config.pitch_profile = {ProfileShape::kSinusoid, 32.5, 7.4, 1.3, 30.0};  // 35.8 deg/s
    const TableRun run = RunTable(config, Motion::kTRP);
    const auto& samples = run.trajectory.samples();
    double roll_lo = 1e9, roll_hi = -1e9, pitch_lo = 1e9, pitch_hi = -1e9, rate_hi = 0.0;
    for (std::size_t i = 0; i < samples.size(); ++i) {
        const Eigen::Vector3d rpy = core::RpyFromQuaternion(samples[i].world_T_sensor.rotation);
        roll_lo = std::min(roll_lo, rpy.x());
        roll_hi = std::max(roll_hi, rpy.x());
        pitch_lo = std::min(pitch_lo, rpy.y());
        pitch_hi = std::max(pitch_hi, rpy.y());
        if (i > 0) {  // rates from the poses themselves, by finite differences
            const Eigen::Vector3d prev =
                core::RpyFromQuaternion(samples[i - 1].world_T_sensor.rotation);
            const double dt = samples[i].stamp_s - samples[i - 1].stamp_s;
            rate_hi = std::max(
                {rate_hi, std::abs(rpy.x() - prev.x()) / dt, std::abs(rpy.y() - prev.y()) / dt});
        }
    }
    EXPECT_GE(roll_lo, -15.0 * kDeg);
    EXPECT_LE(roll_hi, 15.0 * kDeg);
    EXPECT_GE(pitch_lo, 25.0 * kDeg);
    EXPECT_LE(pitch_hi, 40.0 * kDeg);
    EXPECT_LE(rate_hi, 37.5 * kDeg);
    // ... and the motion really used the range (roll and pitch both oscillated).
    EXPECT_LT(roll_lo, -14.0 * kDeg);
    EXPECT_GT(roll_hi, 14.0 * kDeg);
    EXPECT_GT(pitch_hi - pitch_lo, 14.0 * kDeg);
    EXPECT_GT(rate_hi, 35.0 * kDeg);
}

TEST(Table, BulletPoseEqualsEq2ForTheSameJointValues) {
    TableConfig config = ShortCourse();
    config.pitch_to_roll_m = Eigen::Vector3d(0.03, -0.02, 0.06);  // exercise every term
    for (const bool compliant : {false, true}) {  // springs let the joints move freely too
        config.compliance.enabled = compliant;
        const TableRun run = RunTable(config, Motion::kTRP);
        const TableGeometry geometry = GeometryOf(config);
        double max_pos = 0.0;
        double max_ang = 0.0;
        const auto& samples = run.trajectory.samples();
        for (std::size_t i = 0; i < samples.size(); ++i) {
            const core::Pose eq2 = TableForwardKinematics(geometry, run.joints[i]);
            max_pos =
                std::max(max_pos, (eq2.translation - samples[i].world_T_sensor.translation).norm());
            max_ang =
                std::max(max_ang, AngleBetween(eq2.rotation, samples[i].world_T_sensor.rotation));
        }
        std::printf("TRP, compliance %d: Bullet vs Eq. 2 max %.2e m, %.2e deg\n", compliant,
                    max_pos, max_ang / kDeg);
        EXPECT_LT(max_pos, 1e-3);
        EXPECT_LT(max_ang, 0.05 * kDeg);
    }
}

TEST(Table, RigidMotorsTrackTheCommand) {
    const TableConfig config = ShortCourse();
    const TableRun run = RunTable(config, Motion::kTRP);
    double max_err = 0.0;
    for (std::size_t i = 0; i < run.joints.size(); ++i) {
        const double t = run.trajectory.samples()[i].stamp_s;
        max_err = std::max(
            {max_err,
             std::abs(run.joints[i].roll_rad - EvaluateProfile(config.roll_profile, t).value_rad),
             std::abs(run.joints[i].pitch_rad -
                      EvaluateProfile(config.pitch_profile, t).value_rad)});
    }
    EXPECT_LT(max_err, 0.01 * kDeg);
}

TEST(Table, ComplianceMakesTheRotaryTableVibrate) {
    TableConfig config = ShortCourse();
    config.pitch_profile = {ProfileShape::kTriangle, 32.5, 5.0, 2.0, 0.0};
    config.compliance.enabled = true;
    const TableRun run = RunTable(config, Motion::kTP);
    // Oscillation about the command after each triangle reversal: the pitch error changes
    // sign many times and reaches a visible amplitude.
    std::vector<double> err(run.joints.size());
    double mean = 0.0;
    for (std::size_t i = 0; i < run.joints.size(); ++i) {
        const double t = run.trajectory.samples()[i].stamp_s;
        err[i] = run.joints[i].pitch_rad - EvaluateProfile(config.pitch_profile, t).value_rad;
        mean += err[i] / static_cast<double>(err.size());
    }
    int sign_changes = 0;
    double max_err = 0.0;
    for (std::size_t i = 1; i < err.size(); ++i) {
        max_err = std::max(max_err, std::abs(err[i] - mean));
        sign_changes += (err[i] - mean) * (err[i - 1] - mean) < 0.0 ? 1 : 0;
    }
    EXPECT_GT(max_err, 0.05 * kDeg);
    EXPECT_GT(sign_changes, 10);
}

TEST(Table, SameConfigGivesIdenticalTrajectory) {
    const TableConfig config = ShortCourse();
    const core::Trajectory a = SimulateTable(config, Motion::kTRP);
    const core::Trajectory b = SimulateTable(config, Motion::kTRP);
    ASSERT_EQ(a.size(), b.size());
    for (std::size_t i = 0; i < a.size(); ++i) {
        ASSERT_EQ(a.samples()[i].stamp_s, b.samples()[i].stamp_s);
        ASSERT_EQ(a.samples()[i].world_T_sensor.translation,
                  b.samples()[i].world_T_sensor.translation);
        ASSERT_EQ(a.samples()[i].world_T_sensor.rotation.coeffs(),
                  b.samples()[i].world_T_sensor.rotation.coeffs());
    }
}

TEST(Table, DecimationKeepsEveryNthStep) {
    TableConfig config = ShortCourse();
    const core::Trajectory full = SimulateTable(config, Motion::kT);
    EXPECT_NEAR(full.samples()[1].stamp_s - full.samples()[0].stamp_s, 1e-3, 1e-12);
    config.output_decimation = 10;
    const core::Trajectory t = SimulateTable(config, Motion::kT);
    EXPECT_NEAR(t.samples()[1].stamp_s - t.samples()[0].stamp_s, 0.01, 1e-12);
}

void ExpectRejected(const TableConfig& config, const std::string& field) {
    EXPECT_THAT([&] { config.Validate("rig.yaml"); },
                testing::ThrowsMessage<InputError>(testing::HasSubstr("rig.yaml: " + field)));
    EXPECT_THROW((void)SimulateTable(config, Motion::kT), InputError);
}

TEST(Table, RejectsValuesBeyondTheLimitsNamingTheField) {
    TableConfig c;
    c.speed_m_s = 1.5;
    ExpectRejected(c, "table.speed_m_s = 1.5");
    c = TableConfig{};
    c.mount_pitch_deg = 45.0;
    ExpectRejected(c, "table.mount_pitch_deg = 45");
    c = TableConfig{};
    c.roll_profile.amplitude_deg = 20.0;
    ExpectRejected(c, "table.roll_profile.amplitude_deg = 20");
    c = TableConfig{};
    c.pitch_profile.center_deg = -30.0;  // the paper's sign, not ours
    ExpectRejected(c, "table.pitch_profile.center_deg = -30");
    c = TableConfig{};
    c.pitch_profile.period_s = 1.0;  // 2 pi 7 / 1 = 44 deg/s
    ExpectRejected(c, "table.pitch_profile.period_s = 1");
    c = TableConfig{};
    c.course.end_x_m = -1.0;
    ExpectRejected(c, "table.course.end_x_m");
    c = TableConfig{};
    c.speed_ramp_s = 0.0;
    ExpectRejected(c, "table.speed_ramp_s");
}

TEST(Table, RejectsACourseNoBeamReaches) {
    TableConfig c = ShortCourse();
    c.course.lateral_offset_m = 50.0;
    EXPECT_THAT(
        [&] { (void)PlanCarriage(c, Motion::kT); },
        testing::ThrowsMessage<InputError>(testing::HasSubstr("table.course.lateral_offset_m")));
}

}  // namespace
}  // namespace casmap::rig
