#pragma once

// Exact ground-truth elevation maps from scene geometry (DESIGN.md "Ground truth"): never from
// the simulated scanner.

#include <optional>

#include "casmap/core/grid.hpp"
#include "casmap/core/scene.hpp"

namespace casmap::sim {

/// Which surface point stands for a cell.
enum class TruthRule {
    kHighestInCell,  // highest surface point anywhere in the cell (DESIGN.md; the default)
    kCellCentre,     // highest surface point on the vertical line through the cell centre
};

struct GroundTruthOptions {
    TruthRule rule = TruthRule::kHighestInCell;
    double datum_m = 0.0;  // world z of the map datum
    // Clamp at the datum: max(datum, highest point), so cells with nothing above the datum
    // hold the datum (the paper's flat-floor setting, DESIGN.md). Unset (the default): clamp
    // only scenes without a `terrain: true` object (the obstacle courses, whose floor top is
    // the datum anyway); terrain scenes keep ground below the datum (ditches, hollows), so
    // RMSE on rough ground is not measured against a floor that is not there. Empty cells
    // (no surface at all) hold the datum either way.
    std::optional<bool> clamp_to_datum;
    int cylinder_segments = 1024;  // facets of a tilted cylinder (sagitta r (1 - cos(pi / n)));
                                   // vertical cylinders are exact discs
    void Validate() const;         // throws InputError naming the field
};

/// Elevation (m, world z) of every cell of `grid`: with kHighestInCell the supremum of z over
/// every surface point whose (x, y) lies in the half-open cell, computed by clipping each
/// triangle (boxes: 12, meshes: theirs, tilted cylinders: tessellated) to the cells it covers;
/// a vertical cylinder is its exact disc, so a 2.5 mm pole marks its cell. Rows run along
/// world x, columns along y (core::GridGeometry). Deterministic for any `threads` (0 = all).
[[nodiscard]] core::MapF GroundTruthElevation(const core::Scene& scene,
                                              const core::GridGeometry& grid,
                                              int threads);

/// Whether `options` clamp heights of `scene` at the datum (the rule of clamp_to_datum).
[[nodiscard]] bool ClampsToDatum(const core::Scene& scene, const GroundTruthOptions& options);

/// Same with explicit options (rule, datum, clamping).
[[nodiscard]] core::MapF GroundTruthElevation(const core::Scene& scene,
                                              const core::GridGeometry& grid,
                                              const GroundTruthOptions& options,
                                              int threads);

}  // namespace casmap::sim
