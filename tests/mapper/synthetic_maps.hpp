// Synthetic elevation/certainty maps shared by the CAS-variant tests (cas_median, cas_edge,
// cas_hybrid, cas_variants): a deterministic +-2 mm floor noise and a 40 x 40 well-observed
// noisy floor.
#pragma once

#include <cstdint>

#include "casmap/core/grid.hpp"

namespace casmap::mapper::test_maps {

// Deterministic +-2 mm "noise" from a counter hash.
inline float Noise(int i, int j) {
    std::uint32_t x = static_cast<std::uint32_t>(i * 7919 + j * 104729 + 17);
    x ^= x >> 13;
    x *= 0x5bd1e995U;
    x ^= x >> 15;
    return (static_cast<float>(x % 1001) / 1000.0F - 0.5F) * 0.004F;
}

// A 40 x 40 map pair: heights 0, every cell seen 36 times.
struct Maps {
    core::MapF h = core::MapF(40, 40, 0.0F);
    core::MapF c = core::MapF(40, 40, 36.0F);
};

// The well-observed floor with Noise() heights.
inline Maps NoisyFloor() {
    Maps p;
    for (int i = 0; i < 40; ++i) {
        for (int j = 0; j < 40; ++j) {
            p.h.at(i, j) = Noise(i, j);
        }
    }
    return p;
}

}  // namespace casmap::mapper::test_maps
