#include "casmap/core/grid.hpp"

#include <string>

#include "casmap/core/check.hpp"
#include "casmap/core/input_error.hpp"
#include "casmap/core/limits.hpp"
#include "casmap/core/text.hpp"

namespace casmap::core {

void GridGeometry::Validate() const {
    const Check check("grid");
    check.That(std::isfinite(x0_m) && std::isfinite(y0_m), "x0_m/y0_m", "", "must be finite");
    check.Positive("cell_m", cell_m);
    check.That(rows > 0 && cols > 0, "rows/cols", std::to_string(rows) + "," + std::to_string(cols),
               "must be > 0");
    limits::CheckLimit("grid", "cells (rows x cols)", size(), limits::kMaxGridCells, "grid cell");
}

}  // namespace casmap::core
