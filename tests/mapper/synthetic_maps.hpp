// Synthetic elevation/certainty maps shared by the CAS-variant tests (cas_median, cas_edge,
// cas_hybrid, cas_variants, ground): a deterministic +-2 mm floor noise, a 40 x 40 well-observed
// noisy floor, the pole-with-trail case and a bit-for-bit map comparison.
#pragma once

#include <gtest/gtest.h>

#include <cstdint>
#include <cstring>
#include <string>

#include "casmap/core/grid.hpp"
#include "casmap/core/input_error.hpp"
#include "casmap/mapper/filter_params.hpp"
#include "casmap/mapper/filters.hpp"

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

// The noisy floor with a one-cell pole at (15, 20) seen 240 times, two halo cells holding its
// top (seen 120 and 90 times), and a five-cell trail of one-hit cells falling from the pole's
// height to the floor.
inline Maps PoleWithTrailAndHalo() {
    Maps p = NoisyFloor();
    p.h.at(15, 20) = 0.914F;
    p.c.at(15, 20) = 240.0F;
    p.h.at(15, 21) = 0.91F;
    p.c.at(15, 21) = 120.0F;
    p.h.at(14, 20) = 0.905F;
    p.c.at(14, 20) = 90.0F;
    const float trail[] = {0.72F, 0.55F, 0.41F, 0.3F, 0.17F};
    for (int n = 0; n < 5; ++n) {
        p.h.at(16 + n, 20) = trail[n];
        p.c.at(16 + n, 20) = 3.0F;
    }
    return p;
}

// Bit equality of two floats (NaN payloads and signed zeros included).
inline bool SameBits(float a, float b) { return std::memcmp(&a, &b, sizeof(float)) == 0; }

// True when both maps hold the same floats bit for bit (NaN payloads included).
inline bool SameBits(const core::MapF& a, const core::MapF& b) {
    return a.data.size() == b.data.size() &&
           std::memcmp(a.data.data(), b.data.data(), 4 * a.data.size()) == 0;
}

// Cells whose bits differ between two maps of the same shape (NaN equal to the same NaN).
inline int CellsThatDiffer(const core::MapF& a, const core::MapF& b) {
    int n = 0;
    for (std::size_t k = 0; k < a.data.size(); ++k) {
        n += SameBits(a.data[k], b.data[k]) ? 0 : 1;
    }
    return n;
}

// FilterParams::Set(name, value) must throw an InputError that names the parameter.
inline void ExpectSetRejects(const std::string& name, const std::string& value) {
    FilterParams params;
    try {
        params.Set(name, value);
        ADD_FAILURE() << name << "=" << value << " accepted";
    } catch (const InputError& e) {
        EXPECT_NE(std::string(e.what()).find(name), std::string::npos) << e.what();
    }
}

// RunFilter(method, h, c, params) must throw an InputError that names `field` (a value set
// directly on the struct, past Set's checks: Validate, run by every filter, catches it).
inline void ExpectFilterRejects(FilterMethod method,
                                const core::MapF& h,
                                const core::MapF& c,
                                const FilterParams& params,
                                const std::string& field) {
    try {
        (void)RunFilter(method, h, c, params);
        ADD_FAILURE() << field << " accepted";
    } catch (const InputError& e) {
        EXPECT_NE(std::string(e.what()).find(field), std::string::npos) << e.what();
    }
}

}  // namespace casmap::mapper::test_maps
