#pragma once

// The maps of one benchmark run as float TIFFs plus a maps.json index, for `casmap bench
// --maps` and the interactive run view of `casmap view`:
//   DIR/raw.tif  certainty.tif  truth.tif  cas_classes.tif
//   DIR/<pipeline>.tif: every pipeline scored but raw (the paper's five first)
//   DIR/maps.json  {"grid": {x0_m, y0_m, cell_m, rows, cols}, "layers": [{name, label, kind,
//                  unit, file}]}   kind: elevation | certainty | classes
// cas_classes.tif holds mapper::PixelClass values (0 untouched, 1 removed, 2 filled, 3 border)
// as floats. Every file is written atomically.

#include <filesystem>

#include "casmap/core/grid.hpp"
#include "casmap/pipeline/benchmark_report.hpp"

namespace casmap::pipeline {

/// Writes the run's maps into `dir` (created if missing). `grid` places cell (row, col) in
/// the world (row along x, col along y). Throws InputError if `dir` cannot be written.
void WriteBenchMaps(const std::filesystem::path& dir,
                    const SheetMaps& maps,
                    const core::GridGeometry& grid);

}  // namespace casmap::pipeline
