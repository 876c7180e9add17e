// cas_hybrid's nan_median_mix (docs/paper-notes.md "Median mix on terrain"): median_mix's value
// with unknown = nan only. On a synthetic NaN map of a slope with a never-observed patch and a
// trail of one-hit cells above the slope, and on a stepped map: unset, the output is
// bit-identical to today's; set, the NaN-mode output is exactly the one median_mix = that value
// gives, and the paper's mode (unknown = zero) never reads it; on the trail cells the value
// follows B = M + x (R - M) with M, R the two medians; on an exact step nothing moves.
// Validation names the field.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <string>
#include <utility>

#include "casmap/core/input_error.hpp"
#include "casmap/mapper/filters.hpp"
#include "casmap/mapper/ground.hpp"
#include "synthetic_maps.hpp"

namespace casmap::mapper {
namespace {

using test_maps::ExpectFilterRejects;
using test_maps::ExpectSetRejects;
using test_maps::Maps;
using test_maps::Noise;
using test_maps::SameBits;

constexpr float kSlope = 0.02F;  // m per cell along j

// A 40 x 40 slope h = 0.02 j + noise, every cell seen 4 times, a never-observed 6 x 6 patch
// (rows 30-35, columns 5-10) and a trail of one-hit cells standing 0.3-0.5 m above the slope
// (rows 12-16, columns 25-26), as a mixed-pixel trail beside a rock.
Maps SlopeWithTrail() {
    Maps p;
    const float nan = std::numeric_limits<float>::quiet_NaN();
    for (int i = 0; i < 40; ++i) {
        for (int j = 0; j < 40; ++j) {
            p.h.at(i, j) = kSlope * static_cast<float>(j) + Noise(i, j);
            p.c.at(i, j) = 4.0F;
            if (i >= 30 && i < 36 && j >= 5 && j < 11) {
                p.h.at(i, j) = nan;
                p.c.at(i, j) = 0.0F;
            }
        }
    }
    const float above[] = {0.5F, 0.45F, 0.4F, 0.35F, 0.3F};
    for (int n = 0; n < 5; ++n) {
        for (int j = 25; j < 27; ++j) {
            p.h.at(12 + n, j) = kSlope * static_cast<float>(j) + above[n];
            p.c.at(12 + n, j) = 1.0F;
        }
    }
    return p;
}

FilterParams Hybrid(const char* unknown, const char* mix, const char* nan_mix) {
    FilterParams params;
    params.Set("unknown", unknown);
    params.Set("median_mix", mix);
    if (nan_mix != nullptr) {
        params.Set("nan_median_mix", nan_mix);
    }
    return params;
}

core::MapF HybridMap(const Maps& p, const FilterParams& params) {
    return RunFilter(FilterMethod::kCasHybrid, p.h, p.c, params).elevation;
}

TEST(CasHybridTerrain, NanMedianMixUnsetOrMinusOneChangesNothing) {
    const Maps p = SlopeWithTrail();
    for (const char* unknown : {"zero", "nan"}) {
        const core::MapF today = HybridMap(p, Hybrid(unknown, "0.1875", nullptr));
        EXPECT_TRUE(SameBits(HybridMap(p, Hybrid(unknown, "0.1875", "-1")), today)) << unknown;
    }
    EXPECT_EQ(FilterParams{}.cas.nan_median_mix, -1.0);
}

TEST(CasHybridTerrain, NanMedianMixActsAsMedianMixInNanModeOnly) {
    const Maps p = SlopeWithTrail();
    for (const char* x : {"0", "0.5", "1"}) {
        // unknown = nan: exactly median_mix = x.
        EXPECT_TRUE(SameBits(HybridMap(p, Hybrid("nan", "0.1875", x)),
                             HybridMap(p, Hybrid("nan", x, nullptr))))
            << x;
        // unknown = zero (the paper's benchmark mode): never read.
        EXPECT_TRUE(SameBits(HybridMap(p, Hybrid("zero", "0.1875", x)),
                             HybridMap(p, Hybrid("zero", "0.1875", nullptr))))
            << x;
    }
}

TEST(CasHybridTerrain, TrailCellsFollowTheMixOfTheTwoMedians) {
    // The trail's cells are no object (one hit each): they take B = M + x (R - M), M the median
    // of cas_trail's votes (a removed cell votes with the local ground), R the raw map's median.
    const Maps p = SlopeWithTrail();
    const FilterParams zero_mix = Hybrid("nan", "0", nullptr);
    CasParams cas = zero_mix.cas;
    cas.support = Support::kHeight;
    const FilterResult trail = CasFilter(p.h, p.c, cas);
    const core::MapF m = MedianFilter(GroundRelativeVotes(p.h, p.c, cas, trail), zero_mix.baseline);
    const core::MapF r = MedianFilter(p.h, zero_mix.baseline);
    const int i = 14;  // the trail's middle cell
    const int j = 25;
    // R counts the trail's ten cells of 25: the window's 13th height is the slope two columns
    // further, 0.54 m; in M the removed trail votes with the local ground instead.
    EXPECT_NEAR(r.at(i, j), kSlope * 27.0F, 0.005F);
    EXPECT_NE(m.at(i, j), r.at(i, j));
    for (const float x : {0.0F, 0.5F, 1.0F}) {
        const core::MapF out = HybridMap(p, Hybrid("nan", "0.1875", std::to_string(x).c_str()));
        const float want = m.at(i, j) + x * (r.at(i, j) - m.at(i, j));
        EXPECT_TRUE(SameBits(out.at(i, j), want)) << x << ": " << out.at(i, j) << " vs " << want;
    }
}

TEST(CasHybridTerrain, AnExactStepKeepsItsHeightsAtAnyMix) {
    // A 0.1 m step (columns >= 20) on an exact floor, NaN mode: nothing is removed, both medians
    // agree, so every mix gives the same map, and cells three or more columns from the step keep
    // their exact heights (hand-computed: 0 and 0.1 m; nearer, the Wiener smoothing of
    // SmoothSurfaceCells moves them by less than surface_tol_m).
    Maps p;
    for (int i = 0; i < 40; ++i) {
        for (int j = 20; j < 40; ++j) {
            p.h.at(i, j) = 0.1F;
        }
    }
    const core::MapF today = HybridMap(p, Hybrid("nan", "0.1875", nullptr));
    for (int i = 0; i < 40; ++i) {
        for (int j = 0; j < 40; ++j) {
            const float h = j >= 20 ? 0.1F : 0.0F;
            if (j <= 16 || j >= 23) {
                ASSERT_EQ(today.at(i, j), h) << i << "," << j;
            } else {
                ASSERT_LE(std::abs(today.at(i, j) - h), 0.015F) << i << "," << j;
            }
        }
    }
    for (const char* x : {"0", "0.5", "1"}) {
        EXPECT_TRUE(SameBits(HybridMap(p, Hybrid("nan", "0.1875", x)), today)) << x;
    }
}

TEST(CasHybridTerrain, NanMedianMixIsValidated) {
    for (const char* value : {"-0.5", "-2", "1.5", "nan", "x"}) {
        ExpectSetRejects("nan_median_mix", value);
    }
    FilterParams bad;  // set directly: Validate (run by every filter) names it
    bad.cas.nan_median_mix = -0.25;
    const Maps p = SlopeWithTrail();
    ExpectFilterRejects(FilterMethod::kCasHybrid, p.h, p.c, bad, "nan_median_mix");
}

}  // namespace
}  // namespace casmap::mapper
