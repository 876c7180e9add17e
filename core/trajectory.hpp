#pragma once

#include <cstddef>
#include <optional>
#include <vector>

#include "casmap/core/pose.hpp"

namespace casmap::core {

struct TimedPose {
    double stamp_s = 0.0;
    Pose world_T_sensor;
};

/// Timed sensor poses, strictly increasing in time. Poses between samples are interpolated
/// (linear in position, slerp in orientation); outside [StartTime, EndTime] there is none.
class Trajectory {
public:
    Trajectory() = default;
    /// Throws InputError if the stamps are not strictly increasing or not finite.
    explicit Trajectory(std::vector<TimedPose> samples);

    [[nodiscard]] std::optional<Pose> PoseAt(double stamp_s) const;
    /// The same pose, found from `hint` (the sample index a previous call left there; start
    /// with 0): nearby stamps in a row (a scan's beams) skip the binary search. Same result.
    [[nodiscard]] std::optional<Pose> PoseAt(double stamp_s, std::size_t& hint) const;
    /// State of a run of look-ups at nearby stamps: the search hint and the slerp angle of the
    /// sample pair last interpolated (acos and sin depend on the pair only, not on the stamp).
    struct Cursor {
        std::size_t hint = 0;
        std::size_t pair = static_cast<std::size_t>(-1);  // index of the pair's later sample
        bool linear = false;                              // Eigen's nearly-equal branch
        double theta = 0.0;
        double sin_theta = 0.0;
    };
    /// The same pose from `cursor` (start with Cursor{}): look-ups between the same two
    /// samples, e.g. a scan's beams, take the slerp's acos and sin once. The translation is
    /// bit-identical to PoseAt(stamp_s); the rotation within a few ulp (small-angle sines by
    /// polynomial), the same for any sequence of look-ups.
    [[nodiscard]] std::optional<Pose> PoseAt(double stamp_s, Cursor& cursor) const;
    [[nodiscard]] bool empty() const { return samples_.empty(); }
    [[nodiscard]] std::size_t size() const { return samples_.size(); }
    [[nodiscard]] double StartTime() const { return samples_.front().stamp_s; }
    [[nodiscard]] double EndTime() const { return samples_.back().stamp_s; }
    [[nodiscard]] const std::vector<TimedPose>& samples() const { return samples_; }

private:
    // Index of the first sample after stamp_s (size() if none), from `hint`; updates `hint`.
    [[nodiscard]] std::size_t After(double stamp_s, std::size_t& hint) const;

    std::vector<TimedPose> samples_;
};

/// Interpolates between two poses, t in [0, 1].
[[nodiscard]] Pose Interpolate(const Pose& a, const Pose& b, double t);

}  // namespace casmap::core
