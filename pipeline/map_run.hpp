#pragma once

// Orchestration shared by `casmap map`, `simulate`, `bench` and `sweep`: scans + poses -> maps,
// grid choice, map files on disk, small deterministic text helpers. No simulator here (this
// file is part of the no-sim build).

#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "casmap/core/grid.hpp"
#include "casmap/core/scan.hpp"
#include "casmap/core/text.hpp"
#include "casmap/core/trajectory.hpp"
#include "casmap/mapper/filter_params.hpp"
#include "casmap/mapper/kalman_noise.hpp"
#include "casmap/mapper/scan_filters.hpp"
#include "casmap/mapper/sweep_jump.hpp"
#include "casmap/mapper/terrain_mapper.hpp"
#include "casmap/mapper/unknown.hpp"

namespace casmap::pipeline {

/// How cell heights are estimated: the paper's Eq. 1-6 (TerrainMapper), the Kalman fusion
/// of each scan's lowest point per cell (KalmanMapper, Fankhauser et al.), or Eq. 1-5 with the
/// consensus cell height (TerrainMapper with mapper::ConsensusConfig: the mean of a cell whose
/// heights agree, Eq. 6 elsewhere).
enum class MapperMode { kPaper, kKalman, kConsensus };
/// "paper" | "kalman" | "consensus"; throws InputError naming `field`.
[[nodiscard]] MapperMode ParseMapperMode(std::string_view text, const std::string& field);
[[nodiscard]] std::string_view ToString(MapperMode mode);

/// Optional scan-domain pre-filter run on every scan before the mapper; its per-beam labels
/// are the mapper's `keep` (mapper/scan_filters.hpp, mapper/sweep_jump.hpp).
enum class Prefilter { kNone, kShadow, kRangeJump, kSweepJump };
/// "none" | "shadow" | "range_jump" | "sweep_jump"; throws InputError naming `field`.
[[nodiscard]] Prefilter ParsePrefilter(std::string_view text, const std::string& field);
[[nodiscard]] std::string_view ToString(Prefilter prefilter);

/// Mapper settings a command may change (the rest of TerrainMapperConfig comes from the run).
/// The defaults are the paper's mapper (Eq. 1-6, unknown cells 0, no pre-filter).
struct MapSettings {
    int a = 3;                 // Eq. 5 certainty increment
    double delta_l_m = 0.032;  // Eq. 4 delta-l, the LMS 200's maximum range error
    MapperMode mode = MapperMode::kPaper;
    mapper::Unknown unknown = mapper::Unknown::kZero;  // never-observed elevation: 0 or NaN
    Prefilter prefilter = Prefilter::kNone;
    mapper::ShadowFilterConfig shadow;   // used when prefilter == kShadow
    mapper::RangeJumpConfig range_jump;  // used when prefilter == kRangeJump
    mapper::SweepJumpConfig sweep_jump;  // used when prefilter == kSweepJump
    mapper::KalmanNoiseConfig kalman;    // used when mode == kKalman
    mapper::ConsensusConfig consensus;   // used when mode == kConsensus
    /// Throws InputError naming the field (a, delta_l_m, shadow.<f>, range_jump.<f>,
    /// sweep_jump.<f>, kalman.<f>, consensus.<f>).
    void Validate() const;
};

/// The mapping-stage parameters of `params` (shadow.*, range_jump.*, sweep_jump.*, kalman.*,
/// consensus.*) into `settings`.
void SetStageParams(MapSettings& settings, const mapper::FilterParams& params);

/// True for a parameter of a mapping stage (a name starting shadow., range_jump., sweep_jump.,
/// kalman. or consensus.).
[[nodiscard]] bool IsStageParameter(std::string_view name);

/// True when a mapper in `mode` with `prefilter` runs the mapping stage `stage` (a section of
/// mapper::StageSections): "shadow", "range_jump", "sweep_jump" when that is the pre-filter,
/// "kalman" in the Kalman mode.
[[nodiscard]] bool RunsStage(MapperMode mode, Prefilter prefilter, std::string_view stage);

/// Applies NAME=VALUE assignments (FilterParams::Set's names and ranges) of mapping-stage
/// parameters to `settings`, then validates. Throws InputError naming `field` for an
/// assignment that is not NAME=VALUE, a parameter that is not a stage's (a map filter's
/// parameter) or a stage `settings` does not run (shadow.* without the shadow pre-filter,
/// range_jump.* / sweep_jump.* without that pre-filter, kalman.* / consensus.* without that
/// mapper mode), and
/// the parameter itself for a bad value.
void ApplyStageSettings(MapSettings& settings,
                        const std::vector<std::string>& assignments,
                        const std::string& field);

/// Elevation H (m) and certainty C (counts) of one run.
struct MappedRun {
    core::MapF elevation;
    core::MapF certainty;
    mapper::MapperStats stats;
    mapper::TerrainMapperConfig config;  // what was used (grid, a, delta-l, scan period)
    MapSettings settings;                // mode, pre-filter and unknown convention used
};

/// Time between consecutive scans: the median of the stamp differences (robust to dropped
/// scans), or the LMS 200's 1/75 s with fewer than two scans.
[[nodiscard]] double ScanPeriod(const std::vector<core::Scan>& scans);

/// Per-beam keep labels of `scan` for `settings.prefilter` (empty for kNone: keep all). The
/// sweep_jump pre-filter needs the neighbouring scans: use PrefilterRunLabels (InputError here).
[[nodiscard]] std::vector<std::uint8_t> PrefilterLabels(const core::Scan& scan,
                                                        const MapSettings& settings);

/// Keep labels of every scan of a run for `settings.prefilter`, in scan order (empty vectors
/// for kNone); the only form for kSweepJump, which compares each scan with its neighbours.
[[nodiscard]] std::vector<std::vector<std::uint8_t>> PrefilterRunLabels(
    const std::vector<core::Scan>& scans,
    const core::Trajectory& world_T_sensor,
    const MapSettings& settings);

/// Runs the mapper of `settings.mode` (Eq. 1-6 or Kalman) over every scan with the pose at
/// each beam's time, each scan first through `settings.prefilter`. Validates `settings`.
/// For kKalman, `certainty` is a per fused scan (KalmanMapper) and `config` holds the grid,
/// a and scan period used.
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

/// core::FormatNumber, the one number formatter ("0.025", "1e-05", ".nan").
using core::FormatNumber;

/// The settings that produced the maps of `run_path` (the file as given; `seed` null when the run
/// has none) as YAML: run, seed, grid, mapper {mode, unknown, prefilter, a, delta_l_m,
/// scan_period_s, and the parameters of the stages run: shadow, range_jump, sweep_jump, kalman},
/// stats.
[[nodiscard]] std::string MapConfigYaml(const std::string& run_path,
                                        std::optional<std::uint64_t> seed,
                                        const MappedRun& mapped);

/// YAML flow map for a grid: "{origin_x_m: .., origin_y_m: .., cell_m: .., rows: .., cols: ..}".
[[nodiscard]] std::string GridYaml(const core::GridGeometry& grid);

}  // namespace casmap::pipeline
