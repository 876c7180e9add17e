#pragma once

// Scan-domain pre-filters (issue 10 section 4): per-beam keep (1) / reject (0) labels for one
// core::Scan, to run before the mapper (TerrainMapper::AddScan's `keep`). They see ranges and
// beam angles only, as a filter on a real scanner's LaserScan does.

#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "casmap/core/scan.hpp"

namespace casmap::mapper {

/// Veiling / shadow points as ROS laser_filters' ScanShadowsFilter finds them: at the point
/// p_i of beam i, the angle between the line of sight (p_i back to the scanner) and the line
/// to a neighbour's point p_j (|i - j| <= window) is below min_angle or above max_angle, i.e.
/// the two points lie almost on one line of sight. Such a pair marks a jump edge; every point
/// within `neighbors` beams of i that is farther than p_i is rejected (the background side and
/// the veiling points in between), and p_i itself when remove_start_point is set.
struct ShadowFilterConfig {
    double min_angle_deg = 10.0;   // laser_filters' example configuration
    double max_angle_deg = 170.0;  // 180 - min_angle
    int window = 1;                // neighbours compared on each side
    int neighbors = 1;             // beams on each side rejected when farther than p_i
    bool remove_start_point = false;
    void Validate() const;  // throws InputError naming the field ("shadow.<field>")
};

/// Range-jump mixed-pixel test: beam i is rejected when its two direct neighbours' ranges
/// differ by more than jump_min_m (a depth edge the pulse may straddle), its own range lies
/// between them, more than margin_m from both (neither the foreground nor the background),
/// and its point lies off the chord between the neighbours' points by more than chord_tol_m
/// along its beam (a surface seen at a grazing angle has large range steps too, but its
/// points are collinear in the scan plane). Beams without two valid neighbours are kept.
struct RangeJumpConfig {
    double jump_min_m = 0.1;    // smallest neighbour gap treated as a depth edge
    double margin_m = 0.03;     // about the LMS 200's maximum range error (delta-l = 32 mm)
    double chord_tol_m = 0.05;  // off-chord distance along the beam that marks a mixed pixel
    void Validate() const;      // throws InputError naming the field ("range_jump.<field>")
};

/// Labels, one per beam: 1 keep, 0 reject. Beams whose status is not kOk are kept (the
/// mapper skips them anyway) and never serve as a neighbour.
[[nodiscard]] std::vector<std::uint8_t> ShadowFilterLabels(const core::Scan& scan,
                                                           const ShadowFilterConfig& config);
[[nodiscard]] std::vector<std::uint8_t> RangeJumpLabels(const core::Scan& scan,
                                                        const RangeJumpConfig& config);

/// How well a pre-filter's rejections match the simulator's mixed-pixel labels, over beams
/// with status kOk: a rejected mixed beam is a true positive, a rejected other beam a false
/// positive, a kept mixed beam a false negative.
struct RemovalScore {
    std::int64_t true_pos = 0;
    std::int64_t false_pos = 0;
    std::int64_t false_neg = 0;
    std::int64_t true_neg = 0;
    /// Adds one scan; labels as core::BeamLabel values, one per beam (InputError otherwise).
    void Add(const core::Scan& scan,
             std::span<const std::uint8_t> keep,
             std::span<const core::BeamLabel> labels);
    [[nodiscard]] double Precision() const;  // NaN when nothing was rejected
    [[nodiscard]] double Recall() const;     // NaN when there is no mixed beam
};

}  // namespace casmap::mapper
