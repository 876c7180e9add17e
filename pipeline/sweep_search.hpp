#pragma once

// Choosing among a sweep's scored points and growing its grid (sweep_run.cpp): the best point,
// the Pareto front, and the growth of axes whose edge holds the best point. Internal to the
// sweep; not installed.

#include <cstddef>
#include <vector>

#include "casmap/pipeline/sweep.hpp"

namespace casmap::pipeline::detail {

/// The chosen point: lowest finite mean PI among points keeping every pole in every run; if
/// none does, the most poles kept, then the lowest mean PI. First in grid order on ties.
void ChooseBest(SweepResult& result);

/// Points not dominated in (mean PI lower, poles kept higher, spikes lower).
[[nodiscard]] std::vector<std::size_t> ParetoFront(const std::vector<SweepPoint>& points);

/// Extends every axis (or only `only_axis` when >= 0) whose edge holds the best point, when
/// the value beyond is allowed and the grid stays <= 10000 points; returns the growth records
/// (empty: nothing grew, `opt` unchanged).
[[nodiscard]] std::vector<SweepGrowth> Grow(SweepOptions& opt,
                                            const SweepPoint& best,
                                            int round,
                                            int only_axis = -1);

}  // namespace casmap::pipeline::detail
