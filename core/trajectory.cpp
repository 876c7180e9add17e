#include "casmap/core/trajectory.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "casmap/core/input_error.hpp"

namespace casmap::core {

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

std::optional<Pose> Trajectory::PoseAt(double stamp_s, std::size_t& hint) const {
    if (samples_.empty() || stamp_s < samples_.front().stamp_s ||
        stamp_s > samples_.back().stamp_s) {
        return std::nullopt;
    }
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
    if (after == samples_.end()) {
        return samples_.back().world_T_sensor;
    }
    const TimedPose& b = *after;
    const TimedPose& a = *(after - 1);
    const double t = (stamp_s - a.stamp_s) / (b.stamp_s - a.stamp_s);
    return Interpolate(a.world_T_sensor, b.world_T_sensor, t);
}

}  // namespace casmap::core
