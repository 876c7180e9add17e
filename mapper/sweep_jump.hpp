#pragma once

// The sweep-jump pre-filter: a mixed-pixel test across consecutive scans (issue 10 section 4).
//
// A pulse that straddles an edge parallel to the scan line (a box's far edge seen from the
// front, which every beam of a scan crosses at about the same time) returns a range between
// the edge and the surface behind it. Its two neighbours in the scan straddle the same edge, so
// the in-scan tests (shadow, range_jump) cannot see it; its neighbours in time can. Beam i of
// scan k is compared with beam i of scans k-1 and k+1, as world points through the poses:
// with o and d the origin and direction of beam i of scan k and p-, p+ the neighbours' points,
// the beam is rejected when
//   1. its neighbours lie at depths (p -/+ - o) . d that differ by more than jump_min_m,
//   2. its own range lies between those depths, more than margin_m from both, and
//   3. the chord p- p+ runs within max_angle_deg of its line of sight (the veiling geometry of
//      ROS laser_filters' ScanShadowsFilter, taken across scans): the three points lie on one
//      line of sight, so the middle one is in mid-air between a near and a far surface; and
//      within depression_share times the beam's depression below the horizon: ground seen at
//      a grazing angle delta makes a chord about delta from the line of sight, so a chord must
//      be much closer than the ground's own grazing angle to mark a veil.
// Test 3 keeps a floor seen by a rolling scanner: its consecutive points also change depth
// fast, but along the floor, far from the line of sight; its depression part keeps the ground
// of a pitching vehicle seen 7-12 degrees from the horizontal. docs/paper-notes.md
// "Sweep jump".

#include <Eigen/Core>
#include <cstdint>
#include <span>
#include <vector>

#include "casmap/core/scan.hpp"
#include "casmap/core/trajectory.hpp"

namespace casmap::mapper {

struct SweepJumpConfig {
    double jump_min_m = 0.1;         // smallest depth gap between the neighbours (a depth edge)
    double margin_m = 0.05;          // distance from both neighbours' depths (> LMS 200 noise)
    double max_angle_deg = 10.0;     // chord within this angle of the line of sight
    double depression_share = 0.35;  // ... and within this share of the beam's depression
                                     // below the horizon (0: no such limit)
    int reach = 1;                   // also test with scans k -/+ 2 .. k -/+ reach as the
                                     // neighbours (1..3): a mixed return repeated in consecutive
                                     // scans (a slow sweep over an edge) has mixed neighbours
    void Validate() const;           // throws InputError naming the field ("sweep_jump.<field>")
};

/// One scan's beams in the world, as the test needs them: origin and unit direction of each
/// beam's line of sight (the pose at the beam's own time), its range, and whether it counts
/// (status kOk, a finite positive range and a pose at its time).
struct SweepJumpBeams {
    std::vector<Eigen::Vector3d> origin, direction;
    std::vector<double> range;
    std::vector<std::uint8_t> valid;
};

/// The world beams of `scan` through `world_T_sensor` (poses covering its beams' times).
[[nodiscard]] SweepJumpBeams SweepJumpWorldBeams(const core::Scan& scan,
                                                 const core::Trajectory& world_T_sensor);

/// A neighbour scan of the one being labelled (scan k - s or k + s); null: there is none
/// (before the first scan, after the last).
struct SweepJumpNeighbour {
    const core::Scan* scan = nullptr;
    const SweepJumpBeams* beams = nullptr;
};

/// The per-scan step of SweepJumpLabels, shared by the offline filter and the live stream
/// (mapper/sweep_jump_stream.hpp): keep labels of `scan` (world beams `beams`) from its
/// neighbours `before[s - 1]` = scan k - s and `after[s - 1]` = scan k + s, s = 1 ..
/// config.reach (both spans config.reach long). A pair counts only when both exist and are
/// usable (same beam grid, at most s + 0.5 `median_gap_s` away in time). Does not validate.
[[nodiscard]] std::vector<std::uint8_t> SweepJumpScanLabels(
    const core::Scan& scan,
    const SweepJumpBeams& beams,
    std::span<const SweepJumpNeighbour> before,
    std::span<const SweepJumpNeighbour> after,
    double median_gap_s,
    const SweepJumpConfig& config);

/// Keep labels (1 keep, 0 reject) for every beam of every scan of a run, in scan order. Beams
/// with status != kOk, without a pose at their time, and the first and last scan's beams are
/// kept; a neighbour scan with another beam count, start angle or angle step, or more than 1.5
/// median scan gaps away in time (a dropped scan between), counts as missing. With reach r > 1
/// the test runs again with scans k - s and k + s as the neighbours for s = 2 .. r (each at most
/// s + 0.5 median gaps away) and a beam any of them rejects is rejected. Deterministic: each
/// label depends only on the 2 reach + 1 scans around it and the trajectory.
[[nodiscard]] std::vector<std::vector<std::uint8_t>> SweepJumpLabels(
    std::span<const core::Scan> scans,
    const core::Trajectory& world_T_sensor,
    const SweepJumpConfig& config);

}  // namespace casmap::mapper
