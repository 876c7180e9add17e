#pragma once

// Mapping a run file (`casmap map`): the elevation and certainty maps (Eq. 1-6, or the Kalman
// mapper; pipeline/map_run.hpp) of a run file's scans and poses, written as float TIFF +
// colour PNG (and the truth, when the run holds one on the same grid) with map.yaml and the
// run's configuration into an output folder, and stored back into the run file. Every output
// is checked before mapping and published at the end, the run file last (io::OutputSet).

#include <filesystem>
#include <optional>
#include <string>

#include "casmap/core/grid.hpp"
#include "casmap/pipeline/map_run.hpp"

namespace casmap::pipeline {

struct MapRunFileOptions {
    std::string run;  ///< run file (HDF5); its /maps are replaced
    std::string out;  ///< output folder; empty: "<run>_maps" beside the run file
    std::optional<core::GridGeometry> grid;  ///< default: the run's grid, else the beams' extent
    MapSettings settings;
};

struct MapRunFileResult {
    std::filesystem::path out_dir;
    core::GridGeometry grid;
    MappedRun mapped;
};

/// Maps `options.run` and writes the outputs. InputErrors: a run without scans or poses
/// (`<run>: /scans`, `/poses`), a `grid` that differs from the run's stored grid (`<run>:
/// grid`), an output that cannot be written (`<path>: out`, or the run file itself).
MapRunFileResult MapRunFile(const MapRunFileOptions& options);

}  // namespace casmap::pipeline
