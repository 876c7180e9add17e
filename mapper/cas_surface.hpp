#pragma once

// Implementation detail shared by cas_median and cas_hybrid (docs/paper-notes.md
// "cas_median", "cas_hybrid"): the value a surface cell (a box edge or corner) takes.

#include <optional>
#include <vector>

#include "casmap/core/grid.hpp"

namespace casmap::mapper::detail {

/// The lower median of the known cells (c > 0, not NaN) of the (2k+1)^2 window around (i, j),
/// inside the map, whose height is within tol of h(i, j) (itself included); nullopt if fewer
/// than min_cells. `samples` is scratch space. No floating-point arithmetic: the value is one
/// of the measured heights.
[[nodiscard]] std::optional<float> SurfaceMedian(const core::MapF& elevation,
                                                 const core::MapF& certainty,
                                                 int i,
                                                 int j,
                                                 int k,
                                                 float tol,
                                                 int min_cells,
                                                 std::vector<float>& samples);

}  // namespace casmap::mapper::detail
