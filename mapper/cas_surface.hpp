#pragma once

// Implementation detail shared by cas_median and cas_hybrid (docs/paper-notes.md
// "cas_median", "cas_hybrid"): the value a surface cell (a box edge or corner) takes, and
// cas_hybrid's fill of the never-observed cells in a surface's shadow.

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

/// FillShadowEdges' parameters (from CasParams: k, edge_tol_m, edge_min, support_tol_m,
/// EffectiveA(), edge_fill, edge_fill_run, edge_spill_c, edge_spill_drop_m, edge_spill).
struct ShadowEdgeParams {
    int k = 2;                    // window half-width of the surface test
    float edge_tol = 0.06F;       // "same height" of the surface test
    int edge_min = 7;             // known same-height window cells of a surface
    float step_min = 0.13F;       // the neighbour must stand above the cell by more than this
    float max_certainty = 25.0F;  // the neighbour was seen at most this often (A)
    float fill = 0.0F;            // share of the step the cell takes (0: off)
    int along_min = 0;  // surface cells at the neighbour's height beside it along the edge
    float spill_max_certainty = 0.0F;  // a spill is seen at most this often (0: no spills)
    float spill_drop = 0.01F;          // ... and lies this far below its surface's median
    float spill = 0.0F;                // share of the step down a spill keeps
};

/// cas_hybrid's edge_fill (docs/paper-notes.md "cas_hybrid"): every cell that is not known
/// (c <= 0 or NaN height) whose output is not NaN, with a 4-neighbour that is a surface seen at
/// most max_certainty times (known, 0 < c <= max_certainty, out within edge_tol of its measured
/// height, >= edge_min known cells of its (2k+1)^2 window within edge_tol of it) and whose cell
/// on the opposite side is not known either (or outside the map), and with at least along_min
/// of its two neighbours along the edge (across the step) surfaces within edge_tol of its
/// output, takes out + fill (top - out)
/// where top is the highest such neighbour's out and top - out > step_min.
/// With spill_max_certainty > 0, first the spills (docs/paper-notes.md "cas_hybrid"): a
/// surface cell s (as above) with c(s) <= spill_max_certainty, a known 4-neighbour p on one side
/// whose out is within edge_tol of out(s), the cells f and g beyond s on the other side (s + (s -
/// p), s + 2 (s - p)) both not known (g may lie outside the map, f not), out(s) - out(f) >
/// step_min, and elevation(s) <= m - spill_drop, m the lower median of the known cells of p's
/// (2k+1)^2 window within edge_tol of elevation(p) (detail::SurfaceMedian): s takes out(f) + spill
/// (out(s) - out(f)) (sides tried in the order +row, -row, +col, -col; the first that qualifies),
/// and no unknown cell takes edge_fill from s. Every decision and value reads the input out (before
/// any write): the result does not depend on the visiting order.
void FillShadowEdges(const core::MapF& elevation,
                     const core::MapF& certainty,
                     const ShadowEdgeParams& params,
                     core::MapF& out);

}  // namespace casmap::mapper::detail
