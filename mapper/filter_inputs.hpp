#pragma once

// The checks every filter input passes before RunFilter (`casmap filter`, the Python binding
// `casmap.filter`, anyone filtering maps they did not make): one place, one set of messages.

#include <string>

#include "casmap/core/grid.hpp"
#include "casmap/mapper/filter_params.hpp"

namespace casmap::mapper {

/// How the two maps are named in messages: their files (CLI) or argument names (Python).
struct FilterInputNames {
    std::string elevation = "elevation";
    std::string certainty = "certainty";
};

/// True for the methods that read a certainty map (cas, cas_terrain, cas_trail, cas_median,
/// cas_edge, cas_hybrid).
[[nodiscard]] bool NeedsCertainty(FilterMethod method);

/// Checks an elevation map H (m) and certainty map C (counts; empty = not given) for `method`:
/// a CAS method needs C; C has H's shape; H is finite (NaN = unknown only with
/// params.cas.unknown == nan; never +-inf); C is finite and >= 0. Throws InputError
/// "<map name>: pixel (row i, col j) = <value> (<rule>)", "<certainty name>: shape = RxC (...)"
/// or "certainty (required for method cas)".
void CheckFilterInputs(FilterMethod method,
                       const core::MapF& elevation,
                       const core::MapF& certainty,
                       const FilterParams& params,
                       const FilterInputNames& names = {});

}  // namespace casmap::mapper
