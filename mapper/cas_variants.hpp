#pragma once

// Implementation detail of the CAS filter (not a user API): the wave-2 forms, run by
// CasFilterInto when CasParams asks for unknown = nan, ground = local or support = height.

#include "casmap/core/grid.hpp"
#include "casmap/mapper/filters.hpp"

namespace casmap::mapper::detail {

/// Local ground estimate of cas_terrain: per cell, the `quantile` of the known heights (c > 0,
/// not NaN) in the (2k+1)^2 window clipped to the map; 0 where the window has none.
[[nodiscard]] core::MapF LocalGround(const core::MapF& elevation,
                                     const core::MapF& certainty,
                                     int k,
                                     double quantile);

/// The CAS filter with the wave-2 options (docs/paper-notes.md "Beyond the paper").
void CasVariantInto(const core::MapF& elevation,
                    const core::MapF& certainty,
                    const CasParams& params,
                    FilterResult& out);

}  // namespace casmap::mapper::detail
