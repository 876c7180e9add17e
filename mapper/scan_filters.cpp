// Scan-domain pre-filters (scan_filters.hpp). The shadow test follows the geometry of ROS
// laser_filters' ScanShadowsFilter (Atsushi Watanabe's ScanShadowDetector): in the frame of
// beam i, p_i = (r_i, 0) and p_j = (r_j cos t, r_j sin t) with t the angle between the beams;
// the angle at p_i between the way back to the scanner (-1, 0) and p_j - p_i is
// atan2(|r_j sin t|, r_i - r_j cos t).
#include "casmap/mapper/scan_filters.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

#include "casmap/core/check.hpp"
#include "casmap/core/input_error.hpp"
#include "casmap/core/text.hpp"

namespace casmap::mapper {
namespace {

constexpr double kDeg = std::numbers::pi / 180.0;

bool Valid(const core::Scan& scan, std::size_t i) {
    return scan.beams[i].status == core::BeamStatus::kOk && std::isfinite(scan.beams[i].range_m) &&
           scan.beams[i].range_m > 0.0F;
}

}  // namespace

void ShadowFilterConfig::Validate() const {
    const core::Check check("scan filter");
    check.That(std::isfinite(min_angle_deg) && min_angle_deg > 0.0 && min_angle_deg < 90.0,
               "shadow.min_angle_deg", min_angle_deg, "allowed: > 0 and < 90");
    check.That(std::isfinite(max_angle_deg) && max_angle_deg > 90.0 && max_angle_deg < 180.0,
               "shadow.max_angle_deg", max_angle_deg, "allowed: > 90 and < 180");
    check.That(window >= 1 && window <= 10, "shadow.window", window, "allowed: integer 1..10");
    check.That(neighbors >= 0 && neighbors <= 20, "shadow.neighbors", neighbors,
               "allowed: integer 0..20");
}

void RangeJumpConfig::Validate() const {
    const core::Check check("scan filter");
    check.That(std::isfinite(jump_min_m) && jump_min_m > 0.0, "range_jump.jump_min_m", jump_min_m,
               "allowed: > 0");
    check.That(std::isfinite(margin_m) && margin_m >= 0.0 && 2.0 * margin_m < jump_min_m,
               "range_jump.margin_m", margin_m, "allowed: >= 0 and < jump_min_m / 2");
    check.That(std::isfinite(chord_tol_m) && chord_tol_m >= 0.0, "range_jump.chord_tol_m",
               chord_tol_m, "allowed: >= 0");
}

std::vector<std::uint8_t> ShadowFilterLabels(const core::Scan& scan,
                                             const ShadowFilterConfig& config) {
    config.Validate();
    const std::size_t n = scan.beams.size();
    std::vector<std::uint8_t> keep(n, 1);
    const double lo = config.min_angle_deg * kDeg;
    const double hi = config.max_angle_deg * kDeg;
    const auto count = static_cast<std::ptrdiff_t>(n);
    for (std::ptrdiff_t i = 0; i < count; ++i) {
        if (!Valid(scan, static_cast<std::size_t>(i))) {
            continue;
        }
        const double ri = scan.beams[static_cast<std::size_t>(i)].range_m;
        bool shadow = false;
        for (std::ptrdiff_t j = std::max<std::ptrdiff_t>(0, i - config.window);
             j <= std::min(count - 1, i + config.window) && !shadow; ++j) {
            if (j == i || !Valid(scan, static_cast<std::size_t>(j))) {
                continue;
            }
            const double t = static_cast<double>(j - i) * scan.angle_step_rad;
            const double rj = scan.beams[static_cast<std::size_t>(j)].range_m;
            const double angle = std::atan2(std::abs(rj * std::sin(t)), ri - rj * std::cos(t));
            shadow = angle < lo || angle > hi;
        }
        if (!shadow) {
            continue;
        }
        for (std::ptrdiff_t k = std::max<std::ptrdiff_t>(0, i - config.neighbors);
             k <= std::min(count - 1, i + config.neighbors); ++k) {
            if (Valid(scan, static_cast<std::size_t>(k)) &&
                scan.beams[static_cast<std::size_t>(k)].range_m > ri) {
                keep[static_cast<std::size_t>(k)] = 0;  // farther than the edge point
            }
        }
        if (config.remove_start_point) {
            keep[static_cast<std::size_t>(i)] = 0;
        }
    }
    return keep;
}

std::vector<std::uint8_t> RangeJumpLabels(const core::Scan& scan, const RangeJumpConfig& config) {
    config.Validate();
    const std::size_t n = scan.beams.size();
    std::vector<std::uint8_t> keep(n, 1);
    for (std::size_t i = 1; i + 1 < n; ++i) {
        if (!Valid(scan, i) || !Valid(scan, i - 1) || !Valid(scan, i + 1)) {
            continue;
        }
        const double a = scan.beams[i - 1].range_m;
        const double b = scan.beams[i + 1].range_m;
        const double r = scan.beams[i].range_m;
        const double near = std::min(a, b);
        const double far = std::max(a, b);
        if (!(far - near > config.jump_min_m && r > near + config.margin_m &&
              r < far - config.margin_m)) {
            continue;
        }
        // Where beam i crosses the chord p_(i-1) p_(i+1), in the frame of beam i.
        const double t = scan.angle_step_rad;
        const double ax = a * std::cos(-t);
        const double ay = a * std::sin(-t);
        const double bx = b * std::cos(t);
        const double by = b * std::sin(t);
        // Point on the chord with y = 0: A + u (B - A), u = -ay / (by - ay).
        const double dy = by - ay;
        if (std::abs(dy) < 1e-12) {
            continue;  // chord parallel to the beam: no crossing
        }
        const double on_chord = ax - ay * (bx - ax) / dy;
        if (std::abs(r - on_chord) > config.chord_tol_m) {
            keep[i] = 0;
        }
    }
    return keep;
}

void RemovalScore::Add(const core::Scan& scan,
                       std::span<const std::uint8_t> keep,
                       std::span<const core::BeamLabel> labels) {
    const std::size_t n = scan.beams.size();
    if (keep.size() != n || labels.size() != n) {
        throw MakeInputError(
            "removal score", "labels",
            std::to_string(keep.size()) + "/" + std::to_string(labels.size()),
            "keep and truth labels need one entry per beam (" + std::to_string(n) + ")");
    }
    for (std::size_t i = 0; i < n; ++i) {
        if (scan.beams[i].status != core::BeamStatus::kOk) {
            continue;
        }
        const bool mixed = labels[i] == core::BeamLabel::kMixed;
        const bool rejected = keep[i] == 0;
        true_pos += static_cast<std::int64_t>(mixed && rejected);
        false_pos += static_cast<std::int64_t>(!mixed && rejected);
        false_neg += static_cast<std::int64_t>(mixed && !rejected);
        true_neg += static_cast<std::int64_t>(!mixed && !rejected);
    }
}

double RemovalScore::Precision() const {
    const std::int64_t rejected = true_pos + false_pos;
    return rejected > 0 ? static_cast<double>(true_pos) / static_cast<double>(rejected)
                        : std::numeric_limits<double>::quiet_NaN();
}

double RemovalScore::Recall() const {
    const std::int64_t mixed = true_pos + false_neg;
    return mixed > 0 ? static_cast<double>(true_pos) / static_cast<double>(mixed)
                     : std::numeric_limits<double>::quiet_NaN();
}

}  // namespace casmap::mapper
