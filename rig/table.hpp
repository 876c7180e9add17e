#pragma once

// rig::Table: the paper's linear/rotary table simulated in Bullet (Fig. 2). A carriage on a
// prismatic joint along world +x carries a pitch joint (about world y) carrying a roll joint
// (about the pitched x axis) carrying the LMS 200. Joint motors track commanded profiles at a
// fixed physics rate. Frames, Eq. 2 and the defaults: docs/rigs.md.

#include <optional>
#include <string>
#include <vector>

#include "casmap/core/trajectory.hpp"
#include "casmap/rig/profile.hpp"
#include "casmap/rig/table_kinematics.hpp"

namespace casmap::rig {

/// The paper's benchmark motions: translation only, plus roll, plus pitch, plus both.
enum class Motion { kT, kTR, kTP, kTRP };

/// "T" | "TR" | "TP" | "TRP"; throws InputError naming `field` otherwise.
[[nodiscard]] Motion ParseMotion(const std::string& text, const std::string& field = "motion");
[[nodiscard]] const char* MotionName(Motion motion);

/// The paper's limits for the table (Fig. 2 caption), pitch in casmap's nose-down sign.
struct TableLimits {
    static constexpr double kMaxSpeedMS = 1.0;
    static constexpr double kMaxAbsRollDeg = 15.0;
    static constexpr double kMinPitchDeg = 25.0;
    static constexpr double kMaxPitchDeg = 40.0;
    static constexpr double kMaxRateDegS = 37.5;
};

/// The map region the scan must sweep at cruise speed (world frame). The run starts early
/// enough that the whole scan footprint over the course is seen after the speed ramp and lasts
/// until the footprint has passed end_x_m.
struct CourseConfig {
    double start_x_m = 1.0;         // scenes/courses: map region x in [1, 6) m
    double end_x_m = 6.0;           // 200 rows of 25 mm
    double lateral_offset_m = 0.0;  // course centre line y relative to the linear axis (y = 0)
    double width_m = 2.0;           // 80 columns of 25 mm
};

/// Optional spring-damper drive of the rotary table (the paper saw it vibrate): each rotary
/// joint is pulled to its command by a torque I (wn^2 e + 2 zeta wn e_dot) instead of a rigid
/// motor, so the table lags, sags under gravity and rings at natural_frequency_hz.
struct ComplianceConfig {
    bool enabled = false;
    double natural_frequency_hz = 6.0;
    double damping_ratio = 0.05;
};

struct TableConfig {
    double physics_rate_hz = 1000.0;
    int output_decimation = 1;      // keep every n-th physics step in the trajectory
    double speed_m_s = 1.0;         // cruise speed of the carriage
    double speed_ramp_s = 0.5;      // time to reach (and leave) the cruise speed
    double sensor_height_m = 1.0;   // scanner origin above the floor at roll 0, mount pitch
    double mount_pitch_deg = 40.0;  // fixed pitch for T and TR (nose down, 25..40)
    Eigen::Vector3d pitch_to_roll_m = Eigen::Vector3d(0.0, 0.0, 0.05);
    double roll_to_sensor_m = 0.10;
    double max_range_m = 8.0;  // only floor hits within this range count for the course
    CourseConfig course;
    AngleProfile roll_profile{ProfileShape::kSinusoid, 0.0, 14.0, 3.0, 0.0};
    AngleProfile pitch_profile{ProfileShape::kSinusoid, 32.5, 7.0, 2.0, 0.0};
    ComplianceConfig compliance;

    /// The one validation of a rig config (as Lms200Config::Validate): throws InputError
    /// "[<where>: ]table.<key> = <value> (<rule>)" for the first broken rule; io's rig loader puts
    /// the key's file:line:col in front instead.
    void Validate(const std::string& where = "") const;
};

/// The joint commands of a motion (centre, amplitude, ...): T and TR hold mount_pitch_deg,
/// T and TP hold roll 0.
[[nodiscard]] AngleProfile RollCommand(const TableConfig& config, Motion motion);
[[nodiscard]] AngleProfile PitchCommand(const TableConfig& config, Motion motion);

/// Geometry of the table implied by the config (pitch-axis height solved from sensor_height_m).
[[nodiscard]] TableGeometry GeometryOf(const TableConfig& config);

/// The carriage schedule that makes the scan sweep the course at cruise speed. Throws
/// InputError if no beam within max_range_m reaches the course's floor strip.
[[nodiscard]] SpeedSchedule PlanCarriage(const TableConfig& config, Motion motion);

/// One simulated run: timed sensor poses and the joint values Bullet reached at each sample.
struct TableRun {
    core::Trajectory trajectory;      // world_T_sensor, stamps k * decimation / rate from 0
    std::vector<TableJoints> joints;  // measured from the Bullet bodies, per sample
    std::vector<TableJoints> rates;   // joint rates (m/s, rad/s), per sample
    SpeedSchedule schedule;
};

/// Simulates the table in Bullet. Validates the config first (InputError naming the field).
[[nodiscard]] TableRun RunTable(const TableConfig& config, Motion motion);

/// RunTable(...).trajectory.
[[nodiscard]] core::Trajectory SimulateTable(const TableConfig& config, Motion motion);

}  // namespace casmap::rig
