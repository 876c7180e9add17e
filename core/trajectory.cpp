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
    if (samples_.empty() || stamp_s < samples_.front().stamp_s ||
        stamp_s > samples_.back().stamp_s) {
        return std::nullopt;
    }
    const auto after =
        std::upper_bound(samples_.begin(), samples_.end(), stamp_s,
                         [](double t, const TimedPose& sample) { return t < sample.stamp_s; });
    if (after == samples_.end()) {
        return samples_.back().world_T_sensor;
    }
    const TimedPose& b = *after;
    const TimedPose& a = *(after - 1);
    const double t = (stamp_s - a.stamp_s) / (b.stamp_s - a.stamp_s);
    return Interpolate(a.world_T_sensor, b.world_T_sensor, t);
}

}  // namespace casmap::core
