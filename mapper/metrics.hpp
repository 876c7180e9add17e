#pragma once

#include <cstdint>

#include "casmap/core/grid.hpp"
#include "casmap/mapper/filters.hpp"

namespace casmap::mapper {

/// A sub-rectangle of a map in cells: rows [row0, row0 + rows), cols [col0, col0 + cols).
struct Region {
    int row0 = 0;
    int col0 = 0;
    int rows = 0;
    int cols = 0;
};

/// The paper's evaluation region (Eq. 11: N = 200 along-track rows x M = 80 across-track
/// cols), clipped to the map and centred in it.
[[nodiscard]] Region PaperRegion(int map_rows, int map_cols);
/// The whole map.
[[nodiscard]] Region FullRegion(int map_rows, int map_cols);

/// Eq. 11: sum (h_f - h_t)^2 / sum (h_r - h_t)^2 over the cells of `region` where the filtered,
/// raw and truth maps are all known (not NaN); with the paper's 0-for-unknown maps that is
/// every cell of the region. NaN if the denominator is 0. Throws InputError if the maps differ
/// in size or the region leaves the map.
[[nodiscard]] double PerformanceIndex(const core::MapF& filtered,
                                      const core::MapF& raw,
                                      const core::MapF& truth,
                                      const Region& region);

/// Root-mean-square of (a - b) over the cells of `region` where both are known (not NaN),
/// metres; NaN if there is none.
[[nodiscard]] double Rmse(const core::MapF& a, const core::MapF& b, const Region& region);

/// Table II shares (percent) of the CAS classes over the processed interior (cells that are
/// not kBorder).
struct ClassShares {
    std::int64_t cells = 0;
    double removed_pct = 0.0;
    double filled_pct = 0.0;
    double untouched_pct = 0.0;
};
struct ClassReport {
    ClassShares all;       // every processed cell
    ClassShares observed;  // without never-observed cells (c = 0) that were not filled
};
[[nodiscard]] ClassReport ClassPercentages(const ClassMap& classes, const core::MapF& certainty);

/// A surviving spike (NaN cells never are; NaN truth cells are left out of the maximum): a
/// cell where the map exceeds the highest truth height within
/// `radius_cells` (Chebyshev) by more than `threshold_m`: a phantom that no registration
/// error of up to radius_cells can explain.
struct SpikeRule {
    double threshold_m = 0.05;
    int radius_cells = 1;
};
[[nodiscard]] std::int64_t CountSpikes(const core::MapF& map,
                                       const core::MapF& truth,
                                       const Region& region,
                                       const SpikeRule& rule = {});

/// Everything one filter run is judged by (DESIGN.md "Metrics").
struct FilterMetrics {
    double pi = 0.0;                // Eq. 11 over the scored cells
    double rmse_m = 0.0;            // filtered vs truth over the scored cells
    double raw_rmse_m = 0.0;        // raw vs truth over the same cells
    std::int64_t cells = 0;         // scored cells: region cells where filtered, raw and truth
                                    // are all known (all region cells for 0-for-unknown maps)
    double coverage = 0.0;          // scored cells / region cells the raw map knows (1 unless
                                    // the filter turned known cells into NaN)
    std::int64_t spikes = 0;        // surviving spikes in the filtered map (CountSpikes)
    std::int64_t raw_spikes = 0;    // the same count in the raw map
    std::int64_t filled_cells = 0;  // CAS kFilled cells in the region (0 for baselines)
    double filled_rmse_m = 0.0;     // filtered vs truth over those cells (NaN if none)
    double edge_rmse_m = 0.0;       // filtered vs truth on truth edges (a 4-neighbour differs
                                    // by more than SpikeRule::threshold_m); NaN if none
    double open_rmse_m = 0.0;       // the same on the other scored cells (open floor, tops of
                                    // obstacles away from their edges); NaN if none
    std::int64_t edge_cells = 0;    // scored cells on truth edges
    std::int64_t open_cells = 0;    // scored cells off them
};
[[nodiscard]] FilterMetrics EvaluateFilter(const FilterResult& result,
                                           const core::MapF& raw,
                                           const core::MapF& truth,
                                           const Region& region);

}  // namespace casmap::mapper
