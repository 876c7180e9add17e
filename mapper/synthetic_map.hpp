#pragma once

#include <cstdint>

#include "casmap/core/grid.hpp"

namespace casmap::mapper {

/// Settings of the synthetic elevation/certainty pair (tests, benchmarks, `casmap demo`).
struct SyntheticMapConfig {
    int rows = 200;  // along-track cells
    int cols = 200;  // across-track cells
    double cell_m = 0.025;
    int a = 3;  // certainty increment per consistent hit (Eq. 5)
    std::uint64_t seed = 1;
};

/// A raw map pair as the mapper would build it, with its exact truth. Scene: a floor at 0 m
/// with three of the paper's parallelepipeds and its cylinder (Table I dimensions), thin poles
/// (914 mm), missing data on the object tops and in occlusion shadows, mixed-pixel streaks
/// behind the objects' far edges, random spikes, and an across-track fall of coverage (the
/// far columns are seen sparsely, as beyond ~1.4 m range in paper_reading.md).
struct SyntheticMap {
    core::GridGeometry grid;
    core::MapF truth;      // exact heights, metres
    core::MapF elevation;  // raw H, metres (0 where unknown)
    core::MapF certainty;  // raw C, counts (0 where unknown)
};

/// Builds the pair; same config, same maps (byte-identical).
[[nodiscard]] SyntheticMap BuildSyntheticMap(const SyntheticMapConfig& config);

}  // namespace casmap::mapper
