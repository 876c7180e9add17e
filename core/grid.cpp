#include "casmap/core/grid.hpp"

#include <string>

#include "casmap/core/input_error.hpp"
#include "casmap/core/limits.hpp"
#include "casmap/core/text.hpp"

namespace casmap::core {

void GridGeometry::Validate() const {
    if (!std::isfinite(x0_m) || !std::isfinite(y0_m)) {
        throw MakeInputError("grid", "x0_m/y0_m", "", "must be finite");
    }
    if (!(cell_m > 0.0) || !std::isfinite(cell_m)) {
        throw MakeInputError("grid", "cell_m", FormatNumber(cell_m), "must be > 0");
    }
    if (rows <= 0 || cols <= 0) {
        throw MakeInputError("grid", "rows/cols", std::to_string(rows) + "," + std::to_string(cols),
                             "must be > 0");
    }
    limits::CheckLimit("grid", "cells (rows x cols)", size(), limits::kMaxGridCells, "grid cell");
}

}  // namespace casmap::core
