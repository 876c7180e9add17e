#include "casmap/core/trajectory.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "casmap/core/input_error.hpp"

namespace casmap::core {
namespace {

// sin(x): for |x| < 1/8 (the rotation between two samples of a 1 kHz trajectory) its Taylor
// polynomial to x^11 (truncation < 3e-21 relative) within ~1 ulp of std::sin, inline; else
// std::sin.
double SinOfSmall(double x) {
    if (!(std::abs(x) < 0.125)) {
        return std::sin(x);
    }
    const double x2 = x * x;
    const double p =
        -1.0 / 6.0 + x2 * (1.0 / 120.0 +
                           x2 * (-1.0 / 5040.0 + x2 * (1.0 / 362880.0 + x2 * (-1.0 / 39916800.0))));
    return x + x * x2 * p;
}

}  // namespace

Trajectory::Trajectory(std::vector<TimedPose> samples) : samples_(std::move(samples)) {
    for (std::size_t i = 0; i < samples_.size(); ++i) {
        if (!std::isfinite(samples_[i].stamp_s)) {
            throw MakeInputError("trajectory", "poses[" + std::to_string(i) + "].stamp_s",
                                 std::to_string(samples_[i].stamp_s), "must be finite");
        }
        if (i > 0 && samples_[i].stamp_s <= samples_[i - 1].stamp_s) {
            throw MakeInputError("trajectory", "poses[" + std::to_string(i) + "].stamp_s",
                                 std::to_string(samples_[i].stamp_s),
                                 "stamps must increase strictly");
        }
    }
}

Pose Interpolate(const Pose& a, const Pose& b, double t) {
    return Pose{a.translation + t * (b.translation - a.translation),
                a.rotation.slerp(t, b.rotation)};
}

std::optional<Pose> Trajectory::PoseAt(double stamp_s) const {
    std::size_t hint = 0;
    return PoseAt(stamp_s, hint);
}

std::size_t Trajectory::After(double stamp_s, std::size_t& hint) const {
    // The first sample after stamp_s lies in [lo, hi], found by upper_bound over [lo, hi):
    // every sample before lo is at or before stamp_s, and hi is the end or after stamp_s.
    // From a valid hint, gallop forward (1, 2, 4, ... samples).
    const std::size_t n = samples_.size();
    std::size_t lo = 0;
    std::size_t hi = n;
    if (hint > 0 && hint <= n && samples_[hint - 1].stamp_s <= stamp_s) {
        lo = hint;
        hi = lo;
        for (std::size_t step = 1; lo < n && samples_[lo].stamp_s <= stamp_s; step *= 2) {
            const std::size_t next = lo + step;
            if (next >= n || stamp_s < samples_[next].stamp_s) {
                lo = lo + 1;
                hi = std::min(next, n);
                break;
            }
            lo = next + 1;
            hi = lo;
        }
    }
    const auto after =
        std::upper_bound(samples_.begin() + static_cast<std::ptrdiff_t>(lo),
                         samples_.begin() + static_cast<std::ptrdiff_t>(hi), stamp_s,
                         [](double t, const TimedPose& sample) { return t < sample.stamp_s; });
    hint = static_cast<std::size_t>(after - samples_.begin());
    return hint;
}

std::optional<Pose> Trajectory::PoseAt(double stamp_s, std::size_t& hint) const {
    if (samples_.empty() || stamp_s < samples_.front().stamp_s ||
        stamp_s > samples_.back().stamp_s) {
        return std::nullopt;
    }
    const std::size_t after = After(stamp_s, hint);
    if (after == samples_.size()) {
        return samples_.back().world_T_sensor;
    }
    const TimedPose& b = samples_[after];
    const TimedPose& a = samples_[after - 1];
    const double t = (stamp_s - a.stamp_s) / (b.stamp_s - a.stamp_s);
    return Interpolate(a.world_T_sensor, b.world_T_sensor, t);
}

std::optional<Pose> Trajectory::PoseAt(double stamp_s, Cursor& cursor) const {
    if (samples_.empty() || stamp_s < samples_.front().stamp_s ||
        stamp_s > samples_.back().stamp_s) {
        return std::nullopt;
    }
    const std::size_t after = After(stamp_s, cursor.hint);
    if (after == samples_.size()) {
        return samples_.back().world_T_sensor;
    }
    const Pose& a = samples_[after - 1].world_T_sensor;
    const Pose& b = samples_[after].world_T_sensor;
    const double t = (stamp_s - samples_[after - 1].stamp_s) /
                     (samples_[after].stamp_s - samples_[after - 1].stamp_s);
    // Eigen 3.4's QuaternionBase::slerp step by step, its pair-only part cached.
    const double d = a.rotation.dot(b.rotation);
    if (cursor.pair != after) {
        cursor.pair = after;
        const double abs_d = std::abs(d);
        cursor.linear = abs_d >= 1.0 - std::numeric_limits<double>::epsilon();
        if (!cursor.linear) {
            cursor.theta = std::acos(abs_d);
            cursor.sin_theta = std::sin(cursor.theta);
        }
    }
    double scale0 = 1.0 - t;
    double scale1 = t;
    if (!cursor.linear) {
        scale0 = SinOfSmall((1.0 - t) * cursor.theta) / cursor.sin_theta;
        scale1 = SinOfSmall(t * cursor.theta) / cursor.sin_theta;
    }
    if (d < 0.0) {
        scale1 = -scale1;
    }
    return Pose{a.translation + t * (b.translation - a.translation),
                Eigen::Quaterniond(scale0 * a.rotation.coeffs() + scale1 * b.rotation.coeffs())};
}

}  // namespace casmap::core
