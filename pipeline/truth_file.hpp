#pragma once

// The exact ground-truth elevation map of a scene written to files (`casmap truth`): a 32-bit
// float TIFF in metres (rows along world x, columns along y) and optionally a colour PNG, both
// checked before the scene is loaded and published together (io::OutputSet). Prints nothing.

#include <string>

#include "casmap/core/grid.hpp"
#include "casmap/sim/ground_truth.hpp"

namespace casmap::pipeline {

struct TruthFileOptions {
    std::string scene;  ///< scene YAML
    core::GridGeometry grid;
    std::string out;  ///< .tiff or .tif
    std::string png;  ///< optional colour PNG (.png); empty: none
    sim::GroundTruthOptions truth;

    /// out ends in .tiff/.tif, png (if given) in .png, grid and truth valid: InputError naming
    /// the field (out, png, grid fields as core::GridGeometry names them).
    void Validate() const;
};

struct TruthFileResult {
    core::MapF map;
    float min_m = 0.0F;  ///< lowest and highest cell of the map
    float max_m = 0.0F;
};

/// Validates, checks both output paths (io::CheckOutputPath: `where` is the path, the field
/// "out" or "png"), loads the scene, computes the map on `threads` threads (0: all cores) and
/// publishes TIFF and PNG together.
[[nodiscard]] TruthFileResult WriteTruthFiles(const TruthFileOptions& options, int threads);

}  // namespace casmap::pipeline
