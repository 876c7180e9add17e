#include "casmap/rig/table_kinematics.hpp"

#include <Eigen/Geometry>

namespace casmap::rig {

core::Pose TableForwardKinematics(const TableGeometry& geometry, const TableJoints& joints) {
    // Outer joint: pitch about the across-track axis (the paper's theta, about x_n, whose
    // negative is our pitch); inner joint: roll about the pitched forward axis (the paper's phi,
    // about its y_b). Eq. 2 = Rx(theta) (Ry(phi) (p_s + (0, 0, p)) + (t, m, q)) + (u, v, w).
    const Eigen::Matrix3d pitch =
        Eigen::AngleAxisd(joints.pitch_rad, Eigen::Vector3d::UnitY()).toRotationMatrix();
    const Eigen::Matrix3d roll =
        Eigen::AngleAxisd(joints.roll_rad, Eigen::Vector3d::UnitX()).toRotationMatrix();
    const Eigen::Matrix3d rotation = pitch * roll;
    const Eigen::Vector3d origin =
        geometry.pitch_axis_origin_m + Eigen::Vector3d(joints.linear_m, 0.0, 0.0);
    const Eigen::Vector3d sensor_above_roll(0.0, 0.0, geometry.roll_to_sensor_m);
    const Eigen::Vector3d translation =
        origin + pitch * (geometry.pitch_to_roll_m + roll * sensor_above_roll);
    return core::Pose{translation, Eigen::Quaterniond(rotation).normalized()};
}

}  // namespace casmap::rig
