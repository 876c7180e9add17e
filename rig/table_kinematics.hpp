#pragma once

// Closed-form forward kinematics of the linear/rotary table: the paper's Eq. 2 rewritten in
// casmap frames (DESIGN.md). Derivation and the mapping of the paper's symbols: docs/rigs.md.

#include <Eigen/Core>

#include "casmap/core/pose.hpp"

namespace casmap::rig {

/// Fixed geometry of the table (metres, world frame REP-103, x along the linear axis).
struct TableGeometry {
    /// Pitch-axis origin when the linear joint is 0: the paper's o_1 = (u, v, w).
    Eigen::Vector3d pitch_axis_origin_m = Eigen::Vector3d(0.0, 0.0, 0.9);
    /// Roll-axis origin in the pitch-rotated frame: the paper's (t, m, q) of o_2.
    Eigen::Vector3d pitch_to_roll_m = Eigen::Vector3d(0.0, 0.0, 0.05);
    /// Scanner origin above the roll axis along the rolled z axis: the paper's p.
    double roll_to_sensor_m = 0.10;
};

/// Joint values: carriage travel along world +x (m), roll about the rolled-frame x axis (rad,
/// positive tilts the top to the right, i.e. towards -y), pitch about the world y axis (rad,
/// positive = nose down).
struct TableJoints {
    double linear_m = 0.0;
    double roll_rad = 0.0;
    double pitch_rad = 0.0;
};

/// world_T_sensor = T(o_1 + linear x) Ry(pitch) T(pitch_to_roll) Rx(roll) T(0, 0, p): Eq. 2.
[[nodiscard]] core::Pose TableForwardKinematics(const TableGeometry& geometry,
                                                const TableJoints& joints);

}  // namespace casmap::rig
