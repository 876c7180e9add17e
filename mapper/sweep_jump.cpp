// The sweep-jump pre-filter (sweep_jump.hpp): each scan's beams as world rays and points, three
// scans at a time, then the depth, margin and line-of-sight tests beam by beam.
#include "casmap/mapper/sweep_jump.hpp"

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <deque>
#include <numbers>
#include <optional>

#include "casmap/core/check.hpp"

namespace casmap::mapper {
namespace {

SweepJumpBeams ToWorld(const core::Scan& scan, const core::Trajectory& world_T_sensor) {
    const std::size_t n = scan.beams.size();
    SweepJumpBeams w;
    w.origin.resize(n);
    w.direction.resize(n);
    w.range.assign(n, 0.0);
    w.valid.assign(n, 0);
    core::Trajectory::Cursor cursor;
    for (std::size_t i = 0; i < n; ++i) {
        const core::Beam& beam = scan.beams[i];
        if (beam.status != core::BeamStatus::kOk || !std::isfinite(beam.range_m) ||
            beam.range_m <= 0.0F) {
            continue;
        }
        const std::optional<core::Pose> pose = world_T_sensor.PoseAt(scan.BeamTime(i), cursor);
        if (!pose) {
            continue;
        }
        const double angle = scan.BeamAngle(i);
        w.origin[i] = pose->translation;
        w.direction[i] = pose->rotation * Eigen::Vector3d(std::cos(angle), std::sin(angle), 0.0);
        w.range[i] = beam.range_m;
        w.valid[i] = 1;
    }
    return w;
}

bool SameGeometry(const core::Scan& a, const core::Scan& b) {
    return a.beams.size() == b.beams.size() && a.start_angle_rad == b.start_angle_rad &&
           a.angle_step_rad == b.angle_step_rad;
}

// The median time between consecutive scans (0 with fewer than two scans).
double MedianGap(std::span<const core::Scan> scans) {
    std::vector<double> gaps;
    for (std::size_t k = 1; k < scans.size(); ++k) {
        gaps.push_back(std::abs(scans[k].stamp_s - scans[k - 1].stamp_s));
    }
    if (gaps.empty()) {
        return 0.0;
    }
    auto mid = gaps.begin() + static_cast<std::ptrdiff_t>(gaps.size() / 2);
    std::nth_element(gaps.begin(), mid, gaps.end());
    return *mid;
}

// A neighbour scan `step` scans away counts only with the same beam grid and no dropped scan in
// between: at most step + 0.5 median gaps away (a recorded run may lose telegrams; one scan
// further, the sensor has moved further and a surface's own depth change can look like a jump).
bool UsableNeighbour(const core::Scan& scan,
                     const core::Scan& neighbour,
                     std::size_t step,
                     double median_gap_s) {
    return SameGeometry(scan, neighbour) && std::abs(neighbour.stamp_s - scan.stamp_s) <=
                                                (static_cast<double>(step) + 0.5) * median_gap_s;
}

// Labels of the middle scan `cur` from two neighbour scans, one before and one after it.
std::vector<std::uint8_t> Labels(const SweepJumpBeams& before,
                                 const SweepJumpBeams& cur,
                                 const SweepJumpBeams& after,
                                 const SweepJumpConfig& config) {
    std::vector<std::uint8_t> keep(cur.valid.size(), 1);
    const double cos_max = std::cos(config.max_angle_deg * std::numbers::pi / 180.0);
    for (std::size_t i = 0; i < keep.size(); ++i) {
        if (!cur.valid[i] || !before.valid[i] || !after.valid[i]) {
            continue;
        }
        const Eigen::Vector3d& o = cur.origin[i];
        const Eigen::Vector3d& d = cur.direction[i];
        const Eigen::Vector3d p0 = before.origin[i] + before.range[i] * before.direction[i];
        const Eigen::Vector3d p1 = after.origin[i] + after.range[i] * after.direction[i];
        const double depth0 = (p0 - o).dot(d);
        const double depth1 = (p1 - o).dot(d);
        const double near = std::min(depth0, depth1);
        const double far = std::max(depth0, depth1);
        const double r = cur.range[i];
        if (!(far - near > config.jump_min_m && r > near + config.margin_m &&
              r < far - config.margin_m)) {
            continue;
        }
        const Eigen::Vector3d chord = p1 - p0;
        const double length = chord.norm();
        double cos_limit = cos_max;
        if (config.depression_share > 0.0) {
            // Depression of the line of sight below the horizon (world z up); a beam at or
            // above the horizon gets a zero limit: nothing rejected.
            const double depression = std::asin(std::clamp(-d.z(), -1.0, 1.0));
            cos_limit =
                std::max(cos_limit, std::cos(config.depression_share * std::max(depression, 0.0)));
        }
        if (length > 0.0 && std::abs(chord.dot(d)) >= cos_limit * length) {
            keep[i] = 0;
        }
    }
    return keep;
}

}  // namespace

void SweepJumpConfig::Validate() const {
    const core::Check check("scan filter");
    check.That(std::isfinite(jump_min_m) && jump_min_m > 0.0, "sweep_jump.jump_min_m", jump_min_m,
               "allowed: > 0");
    check.That(std::isfinite(margin_m) && margin_m >= 0.0 && 2.0 * margin_m <= jump_min_m,
               "sweep_jump.margin_m", margin_m, "allowed: >= 0 and <= jump_min_m / 2");
    check.That(std::isfinite(max_angle_deg) && max_angle_deg > 0.0 && max_angle_deg < 90.0,
               "sweep_jump.max_angle_deg", max_angle_deg, "allowed: > 0 and < 90");
    check.That(
        std::isfinite(depression_share) && depression_share >= 0.0 && depression_share <= 1.0,
        "sweep_jump.depression_share", depression_share, "allowed: 0..1 (0: off)");
    check.That(reach >= 1 && reach <= 3, "sweep_jump.reach", reach, "allowed: 1, 2 or 3");
}

SweepJumpBeams SweepJumpWorldBeams(const core::Scan& scan, const core::Trajectory& world_T_sensor) {
    return ToWorld(scan, world_T_sensor);
}

std::vector<std::uint8_t> SweepJumpScanLabels(const core::Scan& scan,
                                              const SweepJumpBeams& beams,
                                              std::span<const SweepJumpNeighbour> before,
                                              std::span<const SweepJumpNeighbour> after,
                                              double median_gap_s,
                                              const SweepJumpConfig& config) {
    std::vector<std::uint8_t> labels(beams.valid.size(), 1);
    const std::size_t reach = std::min(before.size(), after.size());
    for (std::size_t step = 1; step <= reach; ++step) {
        const SweepJumpNeighbour& b = before[step - 1];
        const SweepJumpNeighbour& a = after[step - 1];
        if (b.scan == nullptr || a.scan == nullptr ||
            !UsableNeighbour(scan, *b.scan, step, median_gap_s) ||
            !UsableNeighbour(scan, *a.scan, step, median_gap_s)) {
            continue;
        }
        const std::vector<std::uint8_t> keep = Labels(*b.beams, beams, *a.beams, config);
        for (std::size_t i = 0; i < keep.size(); ++i) {
            labels[i] &= keep[i];
        }
    }
    return labels;
}

std::vector<std::vector<std::uint8_t>> SweepJumpLabels(std::span<const core::Scan> scans,
                                                       const core::Trajectory& world_T_sensor,
                                                       const SweepJumpConfig& config) {
    config.Validate();
    std::vector<std::vector<std::uint8_t>> labels(scans.size());
    if (scans.empty()) {
        return labels;
    }
    const double median_gap_s = MedianGap(scans);
    const auto reach = static_cast<std::size_t>(config.reach);
    // A sliding window of world beams, scans [first, first + window.size()), each computed once.
    std::deque<SweepJumpBeams> window;
    std::size_t first = 0;
    const auto world = [&](std::size_t j) -> const SweepJumpBeams& {
        while (first + window.size() <= j) {
            window.push_back(ToWorld(scans[first + window.size()], world_T_sensor));
        }
        return window[j - first];
    };
    std::vector<SweepJumpNeighbour> before(reach);
    std::vector<SweepJumpNeighbour> after(reach);
    for (std::size_t k = 0; k < scans.size(); ++k) {
        while (first + reach < k) {
            window.pop_front();
            ++first;
        }
        for (std::size_t step = 1; step <= reach; ++step) {
            before[step - 1] = k < step ? SweepJumpNeighbour{}
                                        : SweepJumpNeighbour{&scans[k - step], &world(k - step)};
            after[step - 1] = k + step >= scans.size()
                                  ? SweepJumpNeighbour{}
                                  : SweepJumpNeighbour{&scans[k + step], &world(k + step)};
        }
        labels[k] = SweepJumpScanLabels(scans[k], world(k), before, after, median_gap_s, config);
    }
    return labels;
}

}  // namespace casmap::mapper
