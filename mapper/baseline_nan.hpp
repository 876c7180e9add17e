#pragma once

// Implementation detail of the baselines (filters.hpp) with BaselineParams::unknown = kNaN:
// every statistic over the window's known (non-NaN) cells inside the map; an unknown centre
// stays NaN (a denoising filter does not invent terrain).

#include "casmap/core/grid.hpp"
#include "casmap/mapper/filter_params.hpp"

namespace casmap::mapper::detail {

[[nodiscard]] core::MapF NanAverage(const core::MapF& h, const BaselineParams& p);
/// Median of the known cells with the centre counted `centre_weight` times (1: plain median);
/// an even count takes the mean of the two middle values (numpy.nanmedian).
[[nodiscard]] core::MapF NanWeightedMedian(const core::MapF& h, int window, int centre_weight);
/// Adaptive Wiener over known cells; noise = p.noise or the mean local variance of known cells.
[[nodiscard]] core::MapF NanWiener(const core::MapF& h, const BaselineParams& p);
[[nodiscard]] double NanWienerNoise(const core::MapF& h, const BaselineParams& p);

}  // namespace casmap::mapper::detail
