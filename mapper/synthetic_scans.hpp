#pragma once

// Analytic LMS 200 scans of a flat floor (z = 0) with upright boxes, from a sensor driven along
// a straight line or an arc: exact ranges, no simulator. For the active window's tests and
// benchmark, and for examples that need scans without Embree.

#include <vector>

#include "casmap/core/scan.hpp"
#include "casmap/core/trajectory.hpp"

namespace casmap::mapper {

struct SyntheticBox {
    double x0_m, x1_m, y0_m, y1_m, height_m;  // world extent; bottom on the floor
};

struct SyntheticDrive {
    double start_x_m = 0.0;
    double start_y_m = 0.0;
    double start_yaw_rad = 0.0;
    double speed_m_s = 1.0;
    double yaw_rate_rad_s = 0.0;             // 0: straight; else an arc of radius speed / yaw rate
    double height_m = 0.6;                   // sensor origin above the floor
    double pitch_rad = 0.19198621771937624;  // 11 deg nose down (the paper's vehicle)
    double duration_s = 4.0;
    double pose_rate_hz = 1000.0;
    std::vector<SyntheticBox> boxes;
    int spike_every = 0;  // every n-th valid beam reported 0.3 m short (a mixed pixel); 0: none
    // The first return of a beam that passed a box top's far edge since the last scan (the top
    // then, the floor now) reported halfway between the top's plane and the floor: the mixed
    // pixel across scans that the sweep_jump pre-filter removes.
    bool mixed_far_edges = false;
    double range_noise_m = 0.0;  // every valid range plus uniform noise in [-n, n] (fixed seed)
};

struct SyntheticRun {
    core::Trajectory poses;         // world_T_sensor at pose_rate_hz
    std::vector<core::Scan> scans;  // 181 beams over 180 deg, 75 Hz, stamps from 0
};

/// Builds the run: each beam is cast from the pose at its own time; beams that hit nothing
/// within 8 m are kNoReturn.
[[nodiscard]] SyntheticRun BuildSyntheticRun(const SyntheticDrive& drive);

}  // namespace casmap::mapper
