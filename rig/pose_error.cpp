#include "casmap/rig/pose_error.hpp"

#include <cmath>
#include <numbers>
#include <random>

#include "casmap/core/check.hpp"

namespace casmap::rig {

namespace {

constexpr double kDegToRad = std::numbers::pi / 180.0;

/// Standard normal samples from mt19937_64 by Box-Muller: unlike std::normal_distribution,
/// the sequence is the same with every standard library.
class Gaussian {
public:
    explicit Gaussian(std::uint64_t seed) : engine_(seed) {}
    double operator()() {
        if (has_spare_) {
            has_spare_ = false;
            return spare_;
        }
        const double u1 = 1.0 - Uniform();  // (0, 1]
        const double u2 = Uniform();
        const double r = std::sqrt(-2.0 * std::log(u1));
        spare_ = r * std::sin(2.0 * std::numbers::pi * u2);
        has_spare_ = true;
        return r * std::cos(2.0 * std::numbers::pi * u2);
    }
    Eigen::Vector3d Vector() {
        const double x = (*this)();
        const double y = (*this)();
        const double z = (*this)();
        return {x, y, z};
    }

private:
    double Uniform() { return static_cast<double>(engine_() >> 11U) * 0x1.0p-53; }

    std::mt19937_64 engine_;
    double spare_ = 0.0;
    bool has_spare_ = false;
};

}  // namespace

void PoseErrorConfig::Validate(const std::string& where) const {
    const core::Check check(where, "pose_error.");
    const char* const rule = "must be finite and >= 0";
    check.NonNegative("position_random_walk_m_per_sqrt_s", position_random_walk_m_per_sqrt_s, rule);
    check.NonNegative("attitude_random_walk_deg_per_sqrt_s", attitude_random_walk_deg_per_sqrt_s,
                      rule);
    check.NonNegative("position_jitter_m", position_jitter_m, rule);
    check.NonNegative("attitude_jitter_deg", attitude_jitter_deg, rule);
    for (int i = 0; i < 3; ++i) {
        check.Finite("position_bias_m", position_bias_m[i]);
        check.That(std::abs(attitude_bias_deg[i]) <= 90.0, "attitude_bias_deg",
                   attitude_bias_deg[i], "allowed: -90..90 deg");
    }
}

core::Trajectory ApplyPoseError(const core::Trajectory& truth, const PoseErrorConfig& config) {
    config.Validate();
    if (!config.enabled || truth.empty()) {
        return truth;
    }
    Gaussian gauss(config.seed);
    std::vector<core::TimedPose> out = truth.samples();
    Eigen::Vector3d walk_pos = Eigen::Vector3d::Zero();
    Eigen::Vector3d walk_att = Eigen::Vector3d::Zero();  // rad
    for (std::size_t i = 0; i < out.size(); ++i) {
        if (i > 0) {
            const double root_dt = std::sqrt(out[i].stamp_s - out[i - 1].stamp_s);
            walk_pos += config.position_random_walk_m_per_sqrt_s * root_dt * gauss.Vector();
            walk_att +=
                config.attitude_random_walk_deg_per_sqrt_s * kDegToRad * root_dt * gauss.Vector();
        }
        const Eigen::Vector3d jitter_pos = config.position_jitter_m * gauss.Vector();
        const Eigen::Vector3d jitter_att = config.attitude_jitter_deg * kDegToRad * gauss.Vector();
        core::Pose& pose = out[i].world_T_sensor;
        pose.translation += config.position_bias_m + walk_pos + jitter_pos;
        const Eigen::Vector3d rpy = core::RpyFromQuaternion(pose.rotation) +
                                    config.attitude_bias_deg * kDegToRad + walk_att + jitter_att;
        pose.rotation = core::QuaternionFromRpy(rpy.x(), rpy.y(), rpy.z());
    }
    return core::Trajectory(std::move(out));
}

}  // namespace casmap::rig
