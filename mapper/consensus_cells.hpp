#pragma once

// The consensus cell height's per-cell arithmetic (mapper/consensus.hpp), shared by the
// offline TerrainMapper and the live ActiveWindow so both compute the same bits: Eq. 5-6 into
// the cell's Eq. 6 height and certainty, then the cell's sum, count, lowest and highest height,
// and the height the map shows (their mean when they agree, else Eq. 6's).

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <vector>

#include "casmap/mapper/beam_geometry.hpp"
#include "casmap/mapper/consensus.hpp"

namespace casmap::mapper::detail {

/// One consensus cell: `h` the shown height, `c` the certainty (Eq. 5, against Eq. 6's
/// height), `eq6` Eq. 6's height, and the sum, count, lowest and highest of the heights seen.
inline void UpdateConsensusCell(float& h,
                                float& c,
                                float& eq6,
                                double& sum_m,
                                std::uint32_t& hits,
                                float& low_m,
                                float& high_m,
                                double z,
                                double dz_max_m,
                                int a,
                                bool nan_unknown,
                                const ConsensusConfig& config) {
    UpdateCell(eq6, c, z, dz_max_m, a, nan_unknown);
    const auto zf = static_cast<float>(z);
    sum_m += z;
    const std::uint32_t n = ++hits;
    low_m = std::min(low_m, zf);
    high_m = std::max(high_m, zf);
    const bool agree = n >= static_cast<std::uint32_t>(config.min_hits) &&
                       static_cast<double>(high_m) - static_cast<double>(low_m) <= config.spread_m;
    h = agree ? static_cast<float>(sum_m / n) : eq6;
}

/// The consensus state of a raster of cells (index = the owner's cell or slot index); empty
/// when the owner maps with the paper's Eq. 6 only. A cleared cell has seen nothing.
struct ConsensusCells {
    std::vector<float> eq6_m;
    std::vector<double> sum_m;
    std::vector<std::uint32_t> hits;
    std::vector<float> low_m, high_m;

    void Assign(std::size_t cells) {
        eq6_m.assign(cells, 0.0F);
        sum_m.assign(cells, 0.0);
        hits.assign(cells, 0);
        low_m.assign(cells, std::numeric_limits<float>::infinity());
        high_m.assign(cells, -std::numeric_limits<float>::infinity());
    }
    [[nodiscard]] bool empty() const { return hits.empty(); }
    void Clear(std::size_t first, std::size_t count) {
        const auto f = static_cast<std::ptrdiff_t>(first);
        const auto n = static_cast<std::ptrdiff_t>(count);
        std::fill(eq6_m.begin() + f, eq6_m.begin() + f + n, 0.0F);
        std::fill(sum_m.begin() + f, sum_m.begin() + f + n, 0.0);
        std::fill(hits.begin() + f, hits.begin() + f + n, 0U);
        std::fill(low_m.begin() + f, low_m.begin() + f + n, std::numeric_limits<float>::infinity());
        std::fill(high_m.begin() + f, high_m.begin() + f + n,
                  -std::numeric_limits<float>::infinity());
    }
    void CopyCell(const ConsensusCells& from, std::size_t from_index, std::size_t to_index) {
        eq6_m[to_index] = from.eq6_m[from_index];
        sum_m[to_index] = from.sum_m[from_index];
        hits[to_index] = from.hits[from_index];
        low_m[to_index] = from.low_m[from_index];
        high_m[to_index] = from.high_m[from_index];
    }
    void Update(std::size_t i,
                float& h,
                float& c,
                double z,
                double dz_max_m,
                int a,
                bool nan_unknown,
                const ConsensusConfig& config) {
        UpdateConsensusCell(h, c, eq6_m[i], sum_m[i], hits[i], low_m[i], high_m[i], z, dz_max_m, a,
                            nan_unknown, config);
    }
    void swap(ConsensusCells& other) noexcept {
        eq6_m.swap(other.eq6_m);
        sum_m.swap(other.sum_m);
        hits.swap(other.hits);
        low_m.swap(other.low_m);
        high_m.swap(other.high_m);
    }
};

}  // namespace casmap::mapper::detail
