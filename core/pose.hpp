#pragma once

#include <Eigen/Geometry>

namespace casmap::core {

/// A rigid transform world_T_sensor: p_world = rotation * p_sensor + translation.
/// Orientation convention (DESIGN.md): R = Rz(yaw) * Ry(pitch) * Rx(roll), REP-103 frames,
/// so positive pitch tilts sensor +x below the horizon (nose down).
struct Pose {
    Eigen::Vector3d translation = Eigen::Vector3d::Zero();
    Eigen::Quaterniond rotation = Eigen::Quaterniond::Identity();

    [[nodiscard]] Eigen::Vector3d operator*(const Eigen::Vector3d& p) const {
        return rotation * p + translation;
    }
    [[nodiscard]] Pose operator*(const Pose& other) const {
        return Pose{rotation * other.translation + translation, rotation * other.rotation};
    }
    [[nodiscard]] Pose Inverse() const {
        const Eigen::Quaterniond inv = rotation.conjugate();
        return Pose{-(inv * translation), inv};
    }
    [[nodiscard]] Eigen::Isometry3d ToIsometry() const {
        Eigen::Isometry3d t = Eigen::Isometry3d::Identity();
        t.linear() = rotation.toRotationMatrix();
        t.translation() = translation;
        return t;
    }
};

/// Rotation R = Rz(yaw) Ry(pitch) Rx(roll), angles in radians.
[[nodiscard]] Eigen::Quaterniond QuaternionFromRpy(double roll_rad,
                                                   double pitch_rad,
                                                   double yaw_rad);

/// Inverse of QuaternionFromRpy: (roll, pitch, yaw) in radians, pitch in [-pi/2, pi/2].
[[nodiscard]] Eigen::Vector3d RpyFromQuaternion(const Eigen::Quaterniond& q);

/// Pose from position (m) and roll, pitch, yaw (rad).
[[nodiscard]] Pose PoseFromXyzRpy(const Eigen::Vector3d& xyz_m, const Eigen::Vector3d& rpy_rad);

}  // namespace casmap::core
