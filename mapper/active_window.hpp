#pragma once

// The paper's real-time scheme (Sec. IV.B): an elevation + certainty "active window" of
// R x C cells travels with the vehicle, the scanner at the centre of its first row. Each scan
// updates only rows R-m .. R-1 ahead of the scanner (Eq. 1-6 with per-beam poses, the same
// arithmetic as TerrainMapper); then each row reaching index R-m is CAS-filtered and its cells
// registered into a world-fixed ObstacleMap. docs/api/mapper-active-window.md and
// docs/paper-notes.md "Sec. IV.B" state every choice made here.
//
// Frame: window cells are cells of a lattice of `cell_m` squares anchored at the world point
// (origin_x_m, origin_y_m) and rotated by the frame heading psi: lattice cell (a, b) covers
// the points whose frame coordinates R(-psi) (p - origin) lie in [a s, (a+1) s) x [b s,
// (b+1) s). With psi = 0 it is exactly core::GridGeometry's grid with the same origin.
// Storage is a ring buffer in both directions: lattice cell (a, b) lives at slot
// (a mod R, b mod C), so following the vehicle moves no memory; rows/columns that enter are
// cleared to unknown (elevation 0, certainty 0).

#include <Eigen/Core>
#include <cstdint>
#include <optional>
#include <span>
#include <vector>

#include "casmap/core/grid.hpp"
#include "casmap/core/pose.hpp"
#include "casmap/core/scan.hpp"
#include "casmap/core/trajectory.hpp"
#include "casmap/mapper/consensus.hpp"
#include "casmap/mapper/consensus_cells.hpp"
#include "casmap/mapper/filter_params.hpp"
#include "casmap/mapper/filters.hpp"
#include "casmap/mapper/obstacle_map.hpp"
#include "casmap/mapper/terrain_mapper.hpp"

namespace casmap::mapper {

struct ActiveWindowConfig {
    int rows = 200;  // R, along the heading (the paper's 200)
    int cols = 400;  // C, across (the paper's 400); the scanner sits in column C / 2
    // m: rows R-m .. R-1 are updated and row R-m is filtered. Default 142 for the paper's
    // vehicle (scanner about 0.6 m up, 11 deg nose down, rig/vehicle.hpp): the scan plane
    // meets the top of a 0.3 m obstacle (0.6 - 0.3) / tan(11 deg) = 1.54 m = 61 rows ahead,
    // so filtering row 61 - k - 1 = 58 = R - m keeps every beam up to that height out of the
    // filtered rows' 5 x 5 neighbourhoods, while the floor's scan line (3.1 m, row 124) lies
    // well inside the updated rows. At 1 m/s a cell is filtered 1.65 s after the floor scan
    // line first sees it. LookAheadRows() computes m for other rigs and heights.
    int m = 142;
    double cell_m = 0.025;
    double origin_x_m = 0.0;  // lattice origin (use the offline map's x0, y0 to compare)
    double origin_y_m = 0.0;
    // Frame headings are multiples of this step (so a heading-0 run uses exactly the offline
    // grid); the frame turns to the nearest multiple, resampling the window, when the
    // scanner's heading is more than 0.75 step from it (hysteresis). 5 deg: at most 3.75 deg
    // of skew, and a turn of 90 deg resamples 18 times.
    double heading_step_rad = 0.087266462599716474;  // 5 deg
    double delta_l_m = 0.032;                        // Eq. 4, as TerrainMapperConfig
    int a = 3;                                       // Eq. 5
    double scan_period_s = 1.0 / 75.0;               // Eq. 4
    CasParams cas;                                   // cas.a and cas.cell_m must equal a and cell_m
    double obstacle_cell_m = 0.1;                    // obstacle-negotiation map cell
    // Rows filtered per scan at most: after a turn the cells that moved behind row R-m are
    // filtered over the following scans instead of in one (bounds the per-scan cost; the
    // vehicle adds about half a row per scan at 1 m/s, so a backlog clears quickly).
    int max_rows_per_scan = 4;
    // Unset: Eq. 6 (the paper). Set: the consensus cell height (mapper/consensus.hpp), as
    // TerrainMapperConfig::consensus: a cell whose heights lie within spread_m over at least
    // min_hits points holds their mean, else Eq. 6's height; certainty is Eq. 5's either way.
    std::optional<ConsensusConfig> consensus;
    void Validate() const;  // throws InputError naming "active window.<field>"
};

/// The m that keeps beams at heights up to `max_height_m` (above the ground at z = 0) out of
/// the filtered rows' CAS neighbourhood, for a scanner `height_m` up and `pitch_rad` nose
/// down: R - (floor(d / s) - k - 1) with d = (height - max_height) / tan(pitch), clamped to
/// [1, R - k]. Ignores roll and the vehicle's own pitching.
[[nodiscard]] int LookAheadRows(const ActiveWindowConfig& config,
                                double height_m,
                                double pitch_rad,
                                double max_height_m);

/// One row the window filtered: lattice row `row`, lattice columns first_col .. first_col + C.
struct FilteredRow {
    std::int64_t row = 0;
    std::int64_t first_col = 0;
    double heading_rad = 0.0;
    std::vector<float> elevation;       // CAS output (m); the k border columns as they were
    std::vector<float> raw;             // the unfiltered elevation of the row (m)
    std::vector<float> certainty;       // counts
    std::vector<std::uint8_t> classes;  // PixelClass
};

struct ActiveWindowStats {
    MapperStats beams;                // seen / not ok / rejected / no pose / outside / mapped
    std::uint64_t beams_behind = 0;   // landed in the window behind row R-m: not mapped
    std::uint64_t beams_late = 0;     // mapped into rows R-m..R-m+k-1 after a neighbour row
                                      // was filtered (m too small for the scene)
    std::uint64_t scans = 0;          // scans given to AddScan
    std::uint64_t scans_no_pose = 0;  // no pose at beam 0: nothing done
    std::uint64_t rows_filtered = 0;
    std::uint64_t rows_skipped = 0;  // left the window unfiltered (a jump of > R - m rows)
    std::uint64_t turns = 0;         // frame re-anchored to a new heading (resampled)
};

class ActiveWindow {
public:
    explicit ActiveWindow(const ActiveWindowConfig& config);  // validates

    /// Moves the window to the scanner pose at the scan's beam-0 time, maps every beam (Eq.
    /// 1-6, per-beam poses) that lands in rows R-m..R-1, then filters and registers each row
    /// that reached index R-m. Returns the rows filtered by this call (valid until the next).
    /// `keep` (empty, or one label per beam, e.g. a SweepJumpStream's) skips beams labelled 0,
    /// counted in stats().beams.beams_rejected; InputError if its size differs from the scan's.
    std::span<const FilteredRow> AddScan(const core::Scan& scan,
                                         const core::Trajectory& world_T_sensor,
                                         std::span<const std::uint8_t> keep = {});

    /// Moves the window so the scanner at `world_T_sensor` is in row 0, column C/2,
    /// re-anchoring (resampling) the frame if the heading left the tolerance.
    void MoveTo(const core::Pose& world_T_sensor);

    /// The window as rasters in window order: row 0 = the scanner's row, column C/2 = its
    /// column (elevation m, certainty counts).
    void Snapshot(core::MapF& elevation, core::MapF& certainty) const;

    /// World centre of lattice cell (a, b) in the current frame.
    [[nodiscard]] Eigen::Vector2d CellCentre(std::int64_t a, std::int64_t b) const;

    [[nodiscard]] const ObstacleMap& obstacles() const { return obstacles_; }
    [[nodiscard]] const ActiveWindowStats& stats() const { return stats_; }
    [[nodiscard]] const ActiveWindowConfig& config() const { return config_; }
    [[nodiscard]] double heading_rad() const { return heading_rad_; }  // frame heading
    [[nodiscard]] std::int64_t first_row() const { return a0_; }       // lattice row of row 0
    [[nodiscard]] std::int64_t first_col() const { return b0_; }       // lattice col of column 0
    [[nodiscard]] bool placed() const { return placed_; }

private:
    [[nodiscard]] std::size_t Slot(std::int64_t a, std::int64_t b) const;
    void Place(double heading_rad, std::int64_t a0, std::int64_t b0);
    void Advance(std::int64_t a0, std::int64_t b0);
    void Resample(double heading_rad, std::int64_t a0, std::int64_t b0);
    [[nodiscard]] bool SourceRowsHoldData(double x_rel, double sd, std::int64_t b0) const;
    void ClearRow(std::int64_t a);
    void ClearCol(std::int64_t b);
    void MapPoint(const Eigen::Vector3d& p_world, double dz_max_m);
    void FilterRow(std::int64_t a, FilteredRow& out);
    void FilterDueRows();

    ActiveWindowConfig config_;
    int filter_index_ = 0;  // R - m
    std::vector<float> h_, c_;
    std::vector<std::uint8_t> registered_;
    std::vector<float> h_back_, c_back_;  // resampling target, swapped in
    std::vector<std::uint8_t> registered_back_;
    // Per row slot: 0 means every cell of the row is zero (and unregistered), so clearing
    // and resampling can skip it.
    std::vector<std::uint8_t> row_data_, row_data_back_;
    // Consensus mode only (empty otherwise): per slot, cleared with its row or column and
    // carried by resampling with the cell.
    detail::ConsensusCells cons_, cons_back_;
    bool placed_ = false;
    double heading_rad_ = 0.0;
    double cos_ = 1.0, sin_ = 0.0;
    std::int64_t a0_ = 0, b0_ = 0;
    std::int64_t next_filter_row_ = 0;
    ObstacleMap obstacles_;
    ActiveWindowStats stats_;
    BeamDirections dirs_;
    std::vector<FilteredRow> filtered_;  // rows of the last AddScan
    std::size_t n_filtered_ = 0;
    core::MapF band_h_, band_c_;  // the 2k+1 rows around a filtered row, unrolled
    FilterResult band_out_;
};

}  // namespace casmap::mapper
