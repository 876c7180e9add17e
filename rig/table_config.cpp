// TableConfig validation, motion names, commands, geometry and run planning (no Bullet here).
#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

#include "casmap/core/check.hpp"
#include "casmap/core/input_error.hpp"
#include "casmap/core/limits.hpp"
#include "casmap/core/text.hpp"
#include "casmap/rig/table.hpp"

namespace casmap::rig {

namespace {

constexpr double kDegToRad = std::numbers::pi / 180.0;

/// Rules shared by both rotary profiles: period, amplitude, rate limit, range.
void CheckProfile(const core::Check& check,
                  const AngleProfile& p,
                  const std::string& field,
                  double min_deg,
                  double max_deg) {
    check.Positive(field + ".period_s", p.period_s);
    check.NonNegative(field + ".amplitude_deg", p.amplitude_deg);
    check.Finite(field + ".phase_deg", p.phase_deg);
    const std::string range =
        "allowed: " + core::FormatNumber(min_deg) + ".." + core::FormatNumber(max_deg) + " deg";
    check.That(p.center_deg >= min_deg && p.center_deg <= max_deg, field + ".center_deg",
               p.center_deg, range);
    check.That(
        p.center_deg - p.amplitude_deg >= min_deg && p.center_deg + p.amplitude_deg <= max_deg,
        field + ".amplitude_deg", p.amplitude_deg,
        range + " (centre " + core::FormatNumber(p.center_deg) + ")");
    const double rate = PeakRateDegS(p);
    check.That(rate <= TableLimits::kMaxRateDegS, field + ".period_s", p.period_s,
               "peak rate " + core::FormatNumber(rate) + " deg/s exceeds the " +
                   core::FormatNumber(TableLimits::kMaxRateDegS) + " deg/s limit");
}

void CheckCourse(const core::Check& check, const CourseConfig& c) {
    const double max_length_m = core::limits::kMaxCourseLengthM;
    check.Finite("table.course.start_x_m", c.start_x_m);
    check.That(c.end_x_m > c.start_x_m && std::isfinite(c.end_x_m), "table.course.end_x_m",
               c.end_x_m, "must be > course.start_x_m");
    check.That(std::abs(c.lateral_offset_m) < 100.0, "table.course.lateral_offset_m",
               c.lateral_offset_m, "must be finite, |y| < 100 m");
    check.That(c.end_x_m - c.start_x_m <= max_length_m, "table.course.end_x_m", c.end_x_m,
               "course length end_x_m - start_x_m limit " + core::FormatNumber(max_length_m) +
                   " m, see docs/limits.md");
    check.That(c.width_m > 0.0 && c.width_m <= max_length_m, "table.course.width_m", c.width_m,
               "allowed: 0 < w <= " + core::FormatNumber(max_length_m) + " m");
}

// The run's length in time and in poses bounds what the rig allocates (docs/limits.md).
void CheckRunSize(const core::Check& check, const TableConfig& c) {
    const double duration_s =
        (c.course.end_x_m - c.course.start_x_m) / c.speed_m_s + c.speed_ramp_s;
    check.That(duration_s <= core::limits::kMaxRunDurationS, "table.speed_m_s", c.speed_m_s,
               "the course takes " + core::FormatNumber(duration_s) + " s, limit " +
                   core::FormatNumber(core::limits::kMaxRunDurationS) + " s, see docs/limits.md");
    const double poses = duration_s * c.physics_rate_hz / c.output_decimation;
    check.That(poses <= static_cast<double>(core::limits::kMaxPoses), "table.output_decimation",
               c.output_decimation,
               core::FormatNumber(poses) + " poses, limit " +
                   std::to_string(core::limits::kMaxPoses) + ", see docs/limits.md");
}

void CheckMechanism(const core::Check& check, const TableConfig& c) {
    check.That(c.physics_rate_hz >= 100.0 && c.physics_rate_hz <= 100000.0, "table.physics_rate_hz",
               c.physics_rate_hz, "allowed: 100..100000 Hz");
    check.That(c.output_decimation >= 1, "table.output_decimation", c.output_decimation,
               "must be >= 1");
    check.That(c.speed_m_s > 0.0 && c.speed_m_s <= TableLimits::kMaxSpeedMS, "table.speed_m_s",
               c.speed_m_s, "allowed: 0 < v <= 1 m/s");
    check.That(c.speed_ramp_s > 0.0 && c.speed_ramp_s <= 60.0, "table.speed_ramp_s", c.speed_ramp_s,
               "allowed: 0 < ramp <= 60 s");
    check.That(c.sensor_height_m > 0.0 && c.sensor_height_m <= 10.0, "table.sensor_height_m",
               c.sensor_height_m, "allowed: 0 < h <= 10 m");
    check.That(c.mount_pitch_deg >= TableLimits::kMinPitchDeg &&
                   c.mount_pitch_deg <= TableLimits::kMaxPitchDeg,
               "table.mount_pitch_deg", c.mount_pitch_deg, "allowed: 25..40 deg");
    for (int i = 0; i < 3; ++i) {
        check.That(std::abs(c.pitch_to_roll_m[i]) <= 1.0, "table.pitch_to_roll_m",
                   c.pitch_to_roll_m[i], "each component within +-1 m");
    }
    check.That(c.roll_to_sensor_m >= 0.0 && c.roll_to_sensor_m <= 1.0, "table.roll_to_sensor_m",
               c.roll_to_sensor_m, "allowed: 0..1 m");
    check.That(c.max_range_m > 0.0 && c.max_range_m <= 80.0, "table.max_range_m", c.max_range_m,
               "allowed: 0 < r <= 80 m");
}

void CheckCompliance(const core::Check& check, const TableConfig& c) {
    if (!c.compliance.enabled) {
        return;
    }
    // Explicit spring-damper: keep wn dt small so the integration stays stable.
    const double max_hz = 0.05 * c.physics_rate_hz;
    check.That(
        c.compliance.natural_frequency_hz > 0.0 && c.compliance.natural_frequency_hz <= max_hz,
        "table.compliance.natural_frequency_hz", c.compliance.natural_frequency_hz,
        "allowed: 0 < f <= physics_rate_hz / 20 = " + core::FormatNumber(max_hz));
    check.That(c.compliance.damping_ratio >= 0.0 && c.compliance.damping_ratio <= 2.0,
               "table.compliance.damping_ratio", c.compliance.damping_ratio, "allowed: 0..2");
}

}  // namespace

Motion ParseMotion(const std::string& text, const std::string& field) {
    if (text == "T") {
        return Motion::kT;
    }
    if (text == "TR") {
        return Motion::kTR;
    }
    if (text == "TP") {
        return Motion::kTP;
    }
    if (text == "TRP") {
        return Motion::kTRP;
    }
    throw MakeInputError("", field, text, "allowed: T, TR, TP, TRP");
}

const char* MotionName(Motion motion) {
    switch (motion) {
        case Motion::kT:
            return "T";
        case Motion::kTR:
            return "TR";
        case Motion::kTP:
            return "TP";
        case Motion::kTRP:
            return "TRP";
    }
    return "?";
}

void TableConfig::Validate(const std::string& where) const {
    const core::Check check(where);
    CheckMechanism(check, *this);
    CheckCourse(check, course);
    CheckRunSize(check, *this);
    CheckProfile(check, roll_profile, "table.roll_profile", -TableLimits::kMaxAbsRollDeg,
                 TableLimits::kMaxAbsRollDeg);
    CheckProfile(check, pitch_profile, "table.pitch_profile", TableLimits::kMinPitchDeg,
                 TableLimits::kMaxPitchDeg);
    CheckCompliance(check, *this);
}

AngleProfile RollCommand(const TableConfig& config, Motion motion) {
    if (motion == Motion::kTR || motion == Motion::kTRP) {
        return config.roll_profile;
    }
    return AngleProfile{ProfileShape::kSinusoid, 0.0, 0.0, 1.0, 0.0};
}

AngleProfile PitchCommand(const TableConfig& config, Motion motion) {
    if (motion == Motion::kTP || motion == Motion::kTRP) {
        return config.pitch_profile;
    }
    return AngleProfile{ProfileShape::kSinusoid, config.mount_pitch_deg, 0.0, 1.0, 0.0};
}

TableGeometry GeometryOf(const TableConfig& config) {
    TableGeometry geometry;
    geometry.pitch_to_roll_m = config.pitch_to_roll_m;
    geometry.roll_to_sensor_m = config.roll_to_sensor_m;
    geometry.pitch_axis_origin_m = Eigen::Vector3d::Zero();
    const core::Pose nominal =
        TableForwardKinematics(geometry, TableJoints{0.0, 0.0, config.mount_pitch_deg * kDegToRad});
    geometry.pitch_axis_origin_m.z() = config.sensor_height_m - nominal.translation.z();
    return geometry;
}

SpeedSchedule PlanCarriage(const TableConfig& config, Motion motion) {
    config.Validate();
    const TableGeometry geometry = GeometryOf(config);
    const AngleProfile roll = RollCommand(config, motion);
    const AngleProfile pitch = PitchCommand(config, motion);
    const CourseConfig& course = config.course;
    // Floor hits (z = 0) of every beam over the attitude envelope, relative to the carriage.
    double min_ahead = std::numeric_limits<double>::infinity();
    double max_ahead = -min_ahead;
    constexpr int kSteps = 8;
    for (int i = 0; i <= kSteps; ++i) {
        for (int j = 0; j <= kSteps; ++j) {
            const double r = roll.center_deg + roll.amplitude_deg * (2.0 * i / kSteps - 1.0);
            const double p = pitch.center_deg + pitch.amplitude_deg * (2.0 * j / kSteps - 1.0);
            const core::Pose pose =
                TableForwardKinematics(geometry, TableJoints{0.0, r * kDegToRad, p * kDegToRad});
            for (int b = 0; b <= 360; ++b) {
                const double a = (-90.0 + 0.5 * b) * kDegToRad;
                const Eigen::Vector3d dir =
                    pose.rotation * Eigen::Vector3d(std::cos(a), std::sin(a), 0.0);
                if (dir.z() > -1e-9) {
                    continue;
                }
                const double range = -pose.translation.z() / dir.z();
                const Eigen::Vector3d hit = pose.translation + range * dir;
                if (range <= config.max_range_m &&
                    std::abs(hit.y() - course.lateral_offset_m) <= 0.5 * course.width_m) {
                    min_ahead = std::min(min_ahead, hit.x());
                    max_ahead = std::max(max_ahead, hit.x());
                }
            }
        }
    }
    if (!std::isfinite(min_ahead)) {
        throw MakeInputError("table config", "table.course.lateral_offset_m",
                             core::FormatNumber(course.lateral_offset_m),
                             "no beam within max_range_m reaches the course's floor strip");
    }
    SpeedSchedule schedule;
    schedule.speed_m_s = config.speed_m_s;
    schedule.ramp_s = config.speed_ramp_s;
    const double ramp_distance = 0.5 * config.speed_m_s * config.speed_ramp_s;
    schedule.start_m = course.start_x_m - max_ahead - ramp_distance;
    const double cruise_m = (course.end_x_m - min_ahead) - (course.start_x_m - max_ahead);
    schedule.cruise_s = cruise_m / config.speed_m_s;
    return schedule;
}

}  // namespace casmap::rig
