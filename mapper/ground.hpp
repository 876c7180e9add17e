#pragma once

// Ground-relative pieces shared by the median-based CAS variants (docs/paper-notes.md
// "Ground-relative votes on terrain"). The paper's removal branch sets a cell to 0 m, which is
// its floor's height only because the paper's floor is the datum (and unknown cells hold 0 m).
// With unknown = nan a map makes no such claim: a removed cell must stand for the ground around
// it, not for a hole (which leaves a median to the obstacle cells that survived) or the datum.

#include "casmap/core/grid.hpp"
#include "casmap/mapper/filters.hpp"

namespace casmap::mapper {

/// Local ground estimate: per cell, the `quantile` (0..1, lower order statistic) of the known
/// heights (c > 0, not NaN) of the (2k+1)^2 window clipped to the map; 0 where the window has
/// none. cas_terrain uses it with k = ground_k (9 x 9), GroundRelativeVotes with the CAS window
/// (k, 5 x 5: on training terrain a 9 x 9 window rounded steps and slope ends in sparse scans).
/// Throws InputError for k < 0 or a quantile outside 0..1. Every function of this header throws
/// InputError naming the map whose size differs from `elevation`'s.
[[nodiscard]] core::MapF LocalGroundEstimate(const core::MapF& elevation,
                                             const core::MapF& certainty,
                                             int k,
                                             double quantile);

/// The map a median-based CAS variant takes its median of, given CAS's `cleaned` result on
/// (`elevation`, `certainty`) (e.g. cas_trail's, as cas_edge does):
/// - unknown = zero, or ground = local: cleaned.elevation as it is (a removed cell holds 0 m,
///   the paper's floor and datum, or cas_terrain's local ground);
/// - unknown = nan with ground = zero: a known cell (c > 0, not NaN) that CAS removed votes with
///   the local ground estimate of the CAS window (k = params.k, params.ground_quantile) instead
///   of NaN, and a never-observed cell CAS filled does not vote (NaN): the median then runs over
///   observed cells only, as the NaN-mode median does.
/// Same size as `elevation`; deterministic (no floating-point reduction).
[[nodiscard]] core::MapF GroundRelativeVotes(const core::MapF& elevation,
                                             const core::MapF& certainty,
                                             const CasParams& params,
                                             const FilterResult& cleaned);

/// Gives back its measured height to every known cell seen more than G times over
/// (c > params.EffectiveG(): the certainty Eq. 10 asks of a whole window) that `filtered`
/// moved by more than support_tol_m, unless a neighbour (3 x 3) that `filtered` kept at its
/// measured height, seen more often than the cell, lies within edge_tol_m of its height
/// (the halo of a pole the filter kept). Such a cell is a surface point, not a mixed pixel: on
/// terrain the face of a tall obstacle whose top was never observed, which a median sets to the
/// ground. NaN in `filtered` is left alone. cas_edge, cas_hybrid and cas_median end with it.
void RestoreTrustedCells(const core::MapF& elevation,
                         const core::MapF& certainty,
                         const CasParams& params,
                         core::MapF& filtered);

/// With unknown = nan (a no-op otherwise: the paper's benchmark mode stays bit-identical), holds
/// every known cell of `filtered` near its measurement (docs/paper-notes.md "Measurement bounds
/// on terrain"):
/// - never more than support_tol_m above it: a mixed pixel lies on its beam between the two
///   surfaces it straddles, above the farther one, so a measurement is too low only by the
///   sensor's noise; the median raises a known cell further only where, in a sparsely seen
///   window, the obstacle's cells outvote the ground (a dilation of the obstacle);
/// - a cell seen more than A times (c > EffectiveA(): outside Eq. 8's mixed-pixel class) that
///   `filtered` lowered by more than support_tol_m gets its measured height back, unless it is
///   the halo of a kept, better-seen neighbour (RestoreTrustedCells' test): on terrain the face
///   of an obstacle whose top was never observed, which the median sets to the ground.
/// NaN in `filtered` is left alone. cas_edge, cas_hybrid and cas_median end with it.
void BoundByMeasurement(const core::MapF& elevation,
                        const core::MapF& certainty,
                        const CasParams& params,
                        core::MapF& filtered);

/// With unknown = nan (a no-op otherwise), after BoundByMeasurement: a known cell whose
/// measured height lies within surface_tol_m of `median` (the median the variant took: no mixed
/// pixel, no object there) and of its value in `filtered` takes the Wiener estimate (WienerFilter
/// of the measured map with params.baseline) when that is within surface_tol_m of the measurement
/// too: noise-level smoothing only; poles, faces and other cells that stand out from the median
/// keep their value. On terrain the Wiener filter is the better noise smoother (below the raw
/// map's RMSE on every training terrain run; docs/paper-notes.md "Measurement bounds on
/// terrain").
void SmoothSurfaceCells(const core::MapF& elevation,
                        const core::MapF& certainty,
                        const core::MapF& median,
                        const FilterParams& params,
                        core::MapF& filtered);

}  // namespace casmap::mapper
