#pragma once

// Orchestration shared by `casmap map`, `simulate`, `bench` and `sweep`: scans + poses -> maps,
// grid choice, map files on disk, small deterministic text helpers. No simulator here (this
// file is part of the no-sim build).

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "casmap/core/grid.hpp"
#include "casmap/core/scan.hpp"
#include "casmap/core/trajectory.hpp"
#include "casmap/mapper/terrain_mapper.hpp"

namespace casmap::pipeline {

/// Mapper settings a command may change (the rest of TerrainMapperConfig comes from the run).
struct MapSettings {
    int a = 3;                 // Eq. 5 certainty increment
    double delta_l_m = 0.032;  // Eq. 4 delta-l, the LMS 200's maximum range error
};

/// Elevation H (m) and certainty C (counts) of one run.
struct MappedRun {
    core::MapF elevation;
    core::MapF certainty;
    mapper::MapperStats stats;
    mapper::TerrainMapperConfig config;  // what was used (grid, a, delta-l, scan period)
};

/// Time between consecutive scans: the median of the stamp differences (robust to dropped
/// scans), or the LMS 200's 1/75 s with fewer than two scans.
[[nodiscard]] double ScanPeriod(const std::vector<core::Scan>& scans);

/// Runs the terrain mapper (Eq. 1-6) over every scan with the pose at each beam's time.
[[nodiscard]] MappedRun MapScans(const std::vector<core::Scan>& scans,
                                 const core::Trajectory& world_T_sensor,
                                 const core::GridGeometry& grid,
                                 const MapSettings& settings = {});

/// The smallest grid of `cell_m` cells (origin on a multiple of cell_m) holding the world
/// x, y of every valid beam. Throws InputError naming `where` when no beam has a pose or the
/// grid would exceed 4000 x 4000 cells (then the caller must choose a grid).
[[nodiscard]] core::GridGeometry GridCoveringBeams(const std::vector<core::Scan>& scans,
                                                   const core::Trajectory& world_T_sensor,
                                                   double cell_m,
                                                   const std::string& where);

/// Parses "X0,Y0,CELL_M,ROWS,COLS"; throws InputError naming `field`.
[[nodiscard]] core::GridGeometry ParseGrid(const std::string& text, const std::string& field);

/// Unknown-cell mask (certainty == 0) for the PNGs.
[[nodiscard]] core::Raster<std::uint8_t> UnknownMask(const core::MapF& certainty);

/// Writes DIR/<stem>.tiff (32-bit float) and DIR/<stem>.png (colour, legend), atomically.
void WriteMapFiles(const std::filesystem::path& dir,
                   const std::string& stem,
                   const core::MapF& map,
                   const std::string& title,
                   const std::string& unit,
                   const core::Raster<std::uint8_t>* unknown);

/// Shortest text that reads back as the same double ("0.025", "1e-05", "nan").
[[nodiscard]] std::string FormatNumber(double value);

/// YAML block for a grid: "{origin_x_m: .., origin_y_m: .., cell_m: .., rows: .., cols: ..}".
[[nodiscard]] std::string GridYaml(const core::GridGeometry& grid);

}  // namespace casmap::pipeline
