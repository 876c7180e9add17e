#pragma once

// Implementation detail of TerrainMapper::AddScan (not a user API): Eq. 1-4 for every beam of a
// scan as structure-of-arrays loops the compiler vectorises (AVX2 clone picked at load time),
// so the cost per beam stays within the DESIGN.md budget (>= 25 M beams/s per core).

#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "casmap/core/scan.hpp"
#include "casmap/core/trajectory.hpp"
#include "casmap/mapper/terrain_mapper.hpp"

namespace casmap::mapper::detail {

/// Per-beam inputs (sensor state at the beam's time and one scan period before) and outputs.
struct BeamBatch {
    // Inputs, one entry per beam to map. q: interpolated, not normalised, orientation at the
    // beam's time (w, x, y, z); q0: the same one scan period earlier; o - o0: displacement.
    std::vector<double> qw, qx, qy, qz, q0w, q0x, q0y, q0z;
    std::vector<double> ox, oy, oz, dx, dy, dz;
    std::vector<double> cos_a, sin_a, range_m;
    std::vector<std::uint32_t> beam;  // index of the beam in its scan
    // Outputs: world point (Eq. 1), Delta z_max (Eq. 4), dz/dl (the unit beam direction's
    // world z), and 1 where the small-angle series did not apply (ComputeBatch redoes those
    // entries with atan2).
    std::vector<double> x, y, z, dz_max, beam_z, redo;
    std::vector<double> row, col;  // floor((x - x0) / cell), floor((y - y0) / cell) when asked
    std::size_t size = 0;

    void Resize(std::size_t n);
};

/// Counts of FillBatch (added to the caller's statistics).
struct FillCounts {
    std::uint64_t not_ok = 0;    // status != kOk
    std::uint64_t rejected = 0;  // keep[i] == 0 (a scan pre-filter's label)
    std::uint64_t no_pose = 0;   // beam time outside the trajectory
};

/// Fills the inputs for every beam of `scan` with status kOk, keep[i] != 0 (when `keep` is
/// not empty) and a pose at its time; the pose one `scan_period_s` earlier is clipped to the
/// trajectory's start. Orientation by nlerp between samples. `dirs` must be Update()d for
/// the scan.
FillCounts FillBatch(const core::Scan& scan,
                     const core::Trajectory& world_T_sensor,
                     const BeamDirections& dirs,
                     double scan_period_s,
                     std::span<const std::uint8_t> keep,
                     BeamBatch& batch);

/// Fills x, y, z, dz_max (with Eq. 4's delta-l) and beam_z for entries [0, batch.size), and
/// row, col of `grid` when it is given (the same values as GridGeometry::CellOf computes;
/// they may lie outside the grid).
void ComputeBatch(double delta_l_m, BeamBatch& batch, const core::GridGeometry* grid = nullptr);

}  // namespace casmap::mapper::detail
