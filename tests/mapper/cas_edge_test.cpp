// cas_edge on closed-form synthetic maps: a pole with a trail and a halo beside it (pole kept bit
// for bit, trail and halo gone), a dense trail the plain median lets vote (gone), a box whose
// corner the median rounds (kept as measured), a flat floor (unchanged / the median's),
// bit-determinism, and parameter validation naming the field.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <string>

#include "casmap/core/input_error.hpp"
#include "casmap/mapper/filters.hpp"
#include "synthetic_maps.hpp"

namespace casmap::mapper {
namespace {

using test_maps::ExpectFilterRejects;
using test_maps::ExpectSetRejects;
using test_maps::Maps;
using test_maps::Noise;
using test_maps::NoisyFloor;
using test_maps::PoleWithTrailAndHalo;
using test_maps::SameBits;

TEST(CasEdge, RemovesTrailAndHaloKeepsThePole) {
    const Maps p = PoleWithTrailAndHalo();
    const FilterParams params;
    const FilterResult out = RunFilter(FilterMethod::kCasEdge, p.h, p.c, params);
    EXPECT_EQ(out.elevation.at(15, 20), 0.914F);                      // the pole, bit for bit
    EXPECT_LT(MedianFilter(p.h, params.baseline).at(15, 20), 0.05F);  // the median deletes it
    EXPECT_LT(out.elevation.at(15, 21), 0.05F);                       // the halo is gone
    EXPECT_LT(out.elevation.at(14, 20), 0.05F);
    for (int n = 0; n < 5; ++n) {
        EXPECT_LT(out.elevation.at(16 + n, 20), 0.05F) << n;  // the trail is gone
    }
    const FilterResult trail = RunFilter(FilterMethod::kCasTrail, p.h, p.c, params);
    EXPECT_EQ(out.classes.data, trail.classes.data);  // classes are cas_trail's
}

TEST(CasEdge, KeepsAPoleAtTheCentroidOfItsTopBlock) {
    // The pole's top smeared over four cells: the most-seen cell (15, 20) is at the block's
    // edge; the certainty-weighted centroid (row 15, column 19.29) is in cell (15, 19).
    Maps p = NoisyFloor();
    const struct {
        int i, j;
        float h, c;
    } block[] = {{15, 20, 0.914F, 100.0F},
                 {15, 19, 0.912F, 90.0F},
                 {14, 19, 0.91F, 80.0F},
                 {16, 19, 0.911F, 80.0F}};
    for (const auto& b : block) {
        p.h.at(b.i, b.j) = b.h;
        p.c.at(b.i, b.j) = b.c;
    }
    const FilterParams params;
    const FilterResult out = RunFilter(FilterMethod::kCasEdge, p.h, p.c, params);
    EXPECT_EQ(out.elevation.at(15, 19), 0.912F);  // the centroid's cell, its own height
    for (const auto& b : block) {
        if (b.j == 20 || b.i != 15) {
            EXPECT_LT(out.elevation.at(b.i, b.j), 0.05F) << b.i << "," << b.j;
        }
    }
}

TEST(CasEdge, ADenseTrailDoesNotVote) {
    // A 3 x 5 block of one-hit mixed pixels beside a pole, every height 0.053 m from the next
    // (beyond support_tol_m, so cas_trail removes them all); in the raw map it fills more than
    // half of the windows around its centre, so the plain median returns a trail height there.
    Maps p = NoisyFloor();
    p.h.at(10, 20) = 0.914F;
    p.c.at(10, 20) = 240.0F;
    int n = 0;
    for (int i = 11; i < 16; ++i) {
        for (int j = 19; j < 22; ++j) {
            p.h.at(i, j) = 0.1F + 0.053F * static_cast<float>((n * 7) % 15);
            p.c.at(i, j) = 3.0F;
            ++n;
        }
    }
    const FilterParams params;
    const core::MapF median = MedianFilter(p.h, params.baseline);
    const FilterResult out = RunFilter(FilterMethod::kCasEdge, p.h, p.c, params);
    EXPECT_GT(median.at(13, 20), 0.1F);  // the plain median keeps a trail height
    for (int i = 11; i < 16; ++i) {
        for (int j = 19; j < 22; ++j) {
            EXPECT_LT(out.elevation.at(i, j), 0.01F) << i << "," << j;
        }
    }
    EXPECT_EQ(out.elevation.at(10, 20), 0.914F);
}

TEST(CasEdge, KeepsABoxCornerTheMedianRounds) {
    Maps p = NoisyFloor();
    for (int i = 20; i < 30; ++i) {
        for (int j = 10; j < 20; ++j) {
            p.h.at(i, j) = 0.3F + Noise(j, i);
        }
    }
    const FilterParams params;
    const FilterResult out = RunFilter(FilterMethod::kCasEdge, p.h, p.c, params);
    const FilterResult cm = RunFilter(FilterMethod::kCasMedian, p.h, p.c, params);
    const core::MapF median = MedianFilter(p.h, params.baseline);
    // Each corner has 9 box cells in its 5 x 5 window: the median returns the floor there.
    for (const auto& [i, j] : {std::pair{20, 10}, {20, 19}, {29, 10}, {29, 19}}) {
        EXPECT_LT(median.at(i, j), 0.05F);
        EXPECT_EQ(out.elevation.at(i, j), p.h.at(i, j)) << i << "," << j;  // kept as measured
    }
    // cas_median's surface rule keeps the corner too, at the lower median of its same-height
    // known cells (not bit for bit: the box is noisy).
    EXPECT_NEAR(cm.elevation.at(20, 19), 0.3F, 0.01F);
    // Inside the box and on the floor the output is the median's.
    EXPECT_EQ(out.elevation.at(25, 15), median.at(25, 15));
    EXPECT_EQ(out.elevation.at(5, 5), median.at(5, 5));
}

TEST(CasEdge, LeavesAFlatFloorAsTheMedianAndIsBitDeterministic) {
    Maps flat;  // exactly 0 m, all observed
    const FilterParams params;
    const FilterResult zero = RunFilter(FilterMethod::kCasEdge, flat.h, flat.c, params);
    EXPECT_TRUE(SameBits(zero.elevation, flat.h));
    Maps p = NoisyFloor();
    for (int i = 0; i < 40; ++i) {
        for (int j = 0; j < 40; ++j) {
            p.c.at(i, j) = static_cast<float>(3 * (1 + (i + j) % 5));
        }
    }
    const FilterResult a = RunFilter(FilterMethod::kCasEdge, p.h, p.c, params);
    const FilterResult b = RunFilter(FilterMethod::kCasEdge, p.h, p.c, params);
    EXPECT_TRUE(SameBits(a.elevation, MedianFilter(p.h, params.baseline)));
    EXPECT_TRUE(SameBits(a.elevation, b.elevation));
    EXPECT_EQ(a.classes.data, b.classes.data);
}

TEST(CasEdge, UnknownAsNaNFillsHolesAndNeverInventsTerrain) {
    Maps p = PoleWithTrailAndHalo();
    const float nan = std::numeric_limits<float>::quiet_NaN();
    p.h.at(8, 8) = nan;  // one never-observed cell in the floor: CAS's fill branch fills it
    p.c.at(8, 8) = 0.0F;
    for (int i = 26; i < 37; ++i) {  // an 11 x 11 never-observed patch
        for (int j = 26; j < 37; ++j) {
            p.h.at(i, j) = nan;
            p.c.at(i, j) = 0.0F;
        }
    }
    FilterParams params;
    params.Set("unknown", "nan");
    const FilterResult out = RunFilter(FilterMethod::kCasEdge, p.h, p.c, params);
    EXPECT_EQ(out.elevation.at(15, 20), 0.914F);         // the pole
    EXPECT_LT(std::abs(out.elevation.at(8, 8)), 0.01F);  // the hole, from the floor around it
    EXPECT_TRUE(std::isnan(out.elevation.at(31, 31)));   // no terrain invented inside the patch
    for (int n = 0; n < 5; ++n) {
        const float v = out.elevation.at(16 + n, 20);  // the trail: unknown or floor
        EXPECT_TRUE(std::isnan(v) || v < 0.05F) << n << ": " << v;
    }
    EXPECT_LT(out.elevation.at(15, 21), 0.05F);  // the halo takes the floor's median
}

TEST(CasEdge, RejectsBadParametersNamingTheField) {
    FilterParams params;
    for (const auto& [name, value] : {std::pair{"edge_min", "0"},
                                      {"edge_min", "226"},
                                      {"edge_min", "2.5"},
                                      {"edge_tol_m", "0"},
                                      {"edge_tol_m", "-0.1"},
                                      {"edge_tol_m", "nan"}}) {
        ExpectSetRejects(name, value);
    }
    params.cas.edge_min = 0;  // set directly: Validate (run by every filter) names it
    const Maps p = NoisyFloor();
    ExpectFilterRejects(FilterMethod::kCasEdge, p.h, p.c, params, "edge_min");
    EXPECT_THROW((void)RunFilter(FilterMethod::kCasEdge, p.h, core::MapF(3, 3), FilterParams{}),
                 InputError);
    EXPECT_EQ(ParseFilterMethod("cas_edge"), FilterMethod::kCasEdge);
    EXPECT_EQ(ToString(FilterMethod::kCasEdge), "cas_edge");
}

}  // namespace
}  // namespace casmap::mapper
