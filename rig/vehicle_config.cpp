// VehicleConfig validation (no Bullet here).
#include <cmath>

#include "casmap/core/check.hpp"
#include "casmap/core/limits.hpp"
#include "casmap/core/text.hpp"
#include "casmap/rig/vehicle.hpp"

namespace casmap::rig {

namespace {

struct Rule {
    bool ok;
    const char* field;
    double value;
    const char* rule;
};

}  // namespace

void VehicleConfig::Validate(const std::string& where) const {
    const core::Check check(where);
    const double max_hz = 100000.0;
    const Rule rules[] = {
        {physics_rate_hz >= 100.0 && physics_rate_hz <= max_hz, "vehicle.physics_rate_hz",
         physics_rate_hz, "allowed: 100..100000 Hz"},
        {output_decimation >= 1, "vehicle.output_decimation",
         static_cast<double>(output_decimation), "must be >= 1"},
        {speed_m_s > 0.0 && speed_m_s <= VehicleLimits::kMaxSpeedMS, "vehicle.speed_m_s", speed_m_s,
         "allowed: 0 < v <= 3 m/s"},
        {speed_ramp_s > 0.0 && speed_ramp_s <= 60.0, "vehicle.speed_ramp_s", speed_ramp_s,
         "allowed: 0 < ramp <= 60 s"},
        {std::isfinite(start_xy_m.x()), "vehicle.start_xy_m", start_xy_m.x(), "must be finite"},
        {std::isfinite(start_xy_m.y()), "vehicle.start_xy_m", start_xy_m.y(), "must be finite"},
        {end_x_m > start_xy_m.x() + mount_xyz_m.x(), "vehicle.end_x_m", end_x_m,
         "must lie ahead of the scanner's start x"},
        {settle_s >= 0.0 && settle_s <= 60.0, "vehicle.settle_s", settle_s, "allowed: 0..60 s"},
        {chassis_mass_kg > 0.0, "vehicle.chassis_mass_kg", chassis_mass_kg, "must be > 0"},
        {chassis_size_m.minCoeff() > 0.0, "vehicle.chassis_size_m", chassis_size_m.minCoeff(),
         "every size must be > 0"},
        {wheelbase_m > 0.0, "vehicle.wheelbase_m", wheelbase_m, "must be > 0"},
        {track_m > 0.0, "vehicle.track_m", track_m, "must be > 0"},
        {wheel_radius_m > 0.0, "vehicle.wheel_radius_m", wheel_radius_m, "must be > 0"},
        {suspension_rest_m > 0.0, "vehicle.suspension_rest_m", suspension_rest_m, "must be > 0"},
        {suspension_travel_m > 0.0 && suspension_travel_m <= suspension_rest_m,
         "vehicle.suspension_travel_m", suspension_travel_m,
         "allowed: 0 < travel <= suspension_rest_m"},
        {suspension_stiffness > 0.0, "vehicle.suspension_stiffness", suspension_stiffness,
         "must be > 0"},
        {suspension_compression >= 0.0, "vehicle.suspension_compression", suspension_compression,
         "must be >= 0"},
        {suspension_relaxation >= 0.0, "vehicle.suspension_relaxation", suspension_relaxation,
         "must be >= 0"},
        {wheel_friction > 0.0, "vehicle.wheel_friction", wheel_friction, "must be > 0"},
        {speed_kp_n_per_m_s >= 0.0, "vehicle.speed_kp_n_per_m_s", speed_kp_n_per_m_s,
         "must be >= 0"},
        {speed_ki_n_per_m >= 0.0, "vehicle.speed_ki_n_per_m", speed_ki_n_per_m, "must be >= 0"},
        {max_drive_force_n > 0.0, "vehicle.max_drive_force_n", max_drive_force_n, "must be > 0"},
        {mount_xyz_m.allFinite() && mount_xyz_m.cwiseAbs().maxCoeff() <= 5.0, "vehicle.mount_xyz_m",
         mount_xyz_m.cwiseAbs().maxCoeff(), "each component within +-5 m"},
        {mount_pitch_deg >= VehicleLimits::kMinMountPitchDeg &&
             mount_pitch_deg <= VehicleLimits::kMaxMountPitchDeg,
         "vehicle.mount_pitch_deg", mount_pitch_deg, "allowed: 0..45 deg (nose down)"},
    };
    for (const Rule& r : rules) {
        check.That(r.ok && std::isfinite(r.value), r.field, r.value, r.rule);
    }
    // The run's length in space, time and poses bounds what the rig allocates
    // (docs/limits.md).
    namespace limits = core::limits;
    const double length_m = end_x_m - start_xy_m.x();
    check.That(length_m <= limits::kMaxCourseLengthM, "vehicle.end_x_m", end_x_m,
               "course length end_x_m - start_xy_m[0] limit " +
                   core::FormatNumber(limits::kMaxCourseLengthM) + " m, see docs/limits.md");
    const double duration_s = length_m / speed_m_s + speed_ramp_s + settle_s;
    check.That(duration_s <= limits::kMaxRunDurationS, "vehicle.speed_m_s", speed_m_s,
               "the course takes " + core::FormatNumber(duration_s) + " s, limit " +
                   core::FormatNumber(limits::kMaxRunDurationS) + " s, see docs/limits.md");
    const double poses = duration_s * physics_rate_hz / output_decimation;
    check.That(poses <= static_cast<double>(limits::kMaxPoses), "vehicle.output_decimation",
               output_decimation,
               core::FormatNumber(poses) + " poses, limit " + std::to_string(limits::kMaxPoses) +
                   ", see docs/limits.md");
}

}  // namespace casmap::rig
