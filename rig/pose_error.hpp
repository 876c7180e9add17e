#pragma once

// Pose-estimate error model for stress tests: the mapper sees poses with bias, random walk and
// jitter on position and attitude, while the simulator casts rays from the true poses.

#include <Eigen/Core>
#include <cstdint>
#include <optional>
#include <string>

#include "casmap/core/trajectory.hpp"

namespace casmap::rig {

/// Errors per axis: position in world x, y, z (m); attitude on roll, pitch, yaw (deg), i.e.
/// on the angles an attitude sensor reports. Error(t) = bias + random walk(t) + jitter(t);
/// the walk starts at 0 at the first sample and grows by sigma * sqrt(dt) N(0, 1) per sample;
/// the jitter is white, drawn once per trajectory sample.
struct PoseErrorConfig {
    bool enabled = false;
    std::uint64_t seed = 1;
    Eigen::Vector3d position_bias_m = Eigen::Vector3d::Zero();
    Eigen::Vector3d attitude_bias_deg = Eigen::Vector3d::Zero();
    double position_random_walk_m_per_sqrt_s = 0.0;
    double attitude_random_walk_deg_per_sqrt_s = 0.0;
    double position_jitter_m = 0.0;
    double attitude_jitter_deg = 0.0;

    /// The one validation of a rig config (as Lms200Config::Validate): throws InputError
    /// "[<where>: ]pose_error.<key> = <value> (<rule>)" for the first broken rule; io's rig loader
    /// puts the key's file:line:col in front instead.
    void Validate(const std::string& where = "") const;
};

/// The poses the mapper sees: `truth` with the seeded error added (a copy if disabled).
/// Same config and trajectory => identical output.
[[nodiscard]] core::Trajectory ApplyPoseError(const core::Trajectory& truth,
                                              const PoseErrorConfig& config);

}  // namespace casmap::rig
