#include "casmap/core/pose.hpp"

#include <algorithm>
#include <cmath>

namespace casmap::core {

Eigen::Quaterniond QuaternionFromRpy(double roll_rad, double pitch_rad, double yaw_rad) {
    const Eigen::Quaterniond q = Eigen::AngleAxisd(yaw_rad, Eigen::Vector3d::UnitZ()) *
                                 Eigen::AngleAxisd(pitch_rad, Eigen::Vector3d::UnitY()) *
                                 Eigen::AngleAxisd(roll_rad, Eigen::Vector3d::UnitX());
    return q.normalized();
}

Eigen::Vector3d RpyFromQuaternion(const Eigen::Quaterniond& q) {
    const Eigen::Matrix3d r = q.normalized().toRotationMatrix();
    // R = Rz(y) Ry(p) Rx(r): r20 = -sin(p), r21 = cos(p) sin(r), r22 = cos(p) cos(r),
    // r10 = sin(y) cos(p), r00 = cos(y) cos(p).
    const double pitch = std::asin(std::clamp(-r(2, 0), -1.0, 1.0));
    const double roll = std::atan2(r(2, 1), r(2, 2));
    const double yaw = std::atan2(r(1, 0), r(0, 0));
    return {roll, pitch, yaw};
}

Pose PoseFromXyzRpy(const Eigen::Vector3d& xyz_m, const Eigen::Vector3d& rpy_rad) {
    return Pose{xyz_m, QuaternionFromRpy(rpy_rad.x(), rpy_rad.y(), rpy_rad.z())};
}

}  // namespace casmap::core
