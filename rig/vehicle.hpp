#pragma once

// rig::Vehicle: a four-wheeled vehicle with suspension (Bullet's raycast vehicle) driving
// straight along world +x over a scene's terrain at a set speed, the LMS 200 mounted nose down
// (the paper's Gorilla vehicle: -11 deg in the paper's sign, +11 deg here). docs/rigs.md.

#include <Eigen/Core>
#include <optional>
#include <string>
#include <vector>

#include "casmap/core/scene.hpp"
#include "casmap/core/trajectory.hpp"

namespace casmap::rig {

struct VehicleLimits {
    static constexpr double kMaxSpeedMS = 3.0;
    static constexpr double kMinMountPitchDeg = 0.0;
    static constexpr double kMaxMountPitchDeg = 45.0;
};

struct VehicleConfig {
    double physics_rate_hz = 1000.0;
    int output_decimation = 1;  // keep every n-th physics step in the trajectory
    double speed_m_s = 1.0;     // set speed of the speed controller
    double speed_ramp_s = 1.0;  // the set speed rises linearly from 0 over this time
    // Chassis centre at the start, and the scanner x that ends the run. The scan line lies
    // about h / tan(11 deg) = 3.1 m ahead of the scanner (h = 0.6 m): these defaults sweep
    // x in about [2.5, 6.1] on scenes/outdoor.yaml (its vehicle lane is y = -1).
    Eigen::Vector2d start_xy_m = Eigen::Vector2d(-1.0, -1.0);
    double end_x_m = 3.0;
    double settle_s = 0.5;  // braked settling on the suspension before t = 0
    // Chassis and running gear (chassis frame: x forward, y left, z up, origin = centre of mass).
    double chassis_mass_kg = 80.0;
    Eigen::Vector3d chassis_size_m = Eigen::Vector3d(0.9, 0.6, 0.25);
    double wheelbase_m = 0.7;
    double track_m = 0.6;
    double wheel_radius_m = 0.15;
    double suspension_rest_m = 0.12;
    double suspension_travel_m = 0.10;
    double suspension_stiffness = 50.0;   // Bullet's, per unit chassis mass (1/s^2)
    double suspension_compression = 4.4;  // Bullet's damping while compressing
    double suspension_relaxation = 2.3;   // Bullet's damping while extending
    double wheel_friction = 1.5;          // Bullet's friction slip
    // Speed controller: drive force = m a_set + kp (v_set - v) + ki * integral, clamped.
    // Defaults put both closed-loop poles at -5 1/s for the default mass (80 (s + 5)^2).
    double speed_kp_n_per_m_s = 800.0;
    double speed_ki_n_per_m = 2000.0;
    double max_drive_force_n = 800.0;
    // Scanner mount on the chassis (chassis frame) and its nose-down pitch.
    Eigen::Vector3d mount_xyz_m = Eigen::Vector3d(0.4, 0.0, 0.35);
    double mount_pitch_deg = 11.0;

    /// The one validation of a rig config (as Lms200Config::Validate): throws InputError
    /// "[<where>: ]vehicle.<key> = <value> (<rule>)" for the first broken rule; io's rig loader
    /// puts the key's file:line:col in front instead.
    void Validate(const std::string& where = "") const;
};

/// One simulated drive: timed scanner poses and how many wheels touched ground at each sample.
struct VehicleRun {
    core::Trajectory trajectory;         // world_T_sensor, stamps from 0 (end of settling)
    std::vector<int> wheels_in_contact;  // 0..4, per sample
    std::vector<double> speed_m_s;       // forward chassis speed, per sample
};

/// Drives over the scene's objects marked `terrain: true` (meshes as BVH triangle meshes,
/// boxes and cylinders as primitives). Throws InputError if the scene has no terrain, the
/// config breaks a rule, or the vehicle cannot reach end_x_m (stuck or fallen off).
[[nodiscard]] VehicleRun RunVehicle(const core::Scene& scene, const VehicleConfig& config);

/// RunVehicle(...).trajectory.
[[nodiscard]] core::Trajectory SimulateVehicle(const core::Scene& scene,
                                               const VehicleConfig& config);

}  // namespace casmap::rig
