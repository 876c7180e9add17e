// cas_hybrid on closed-form synthetic maps: a pole with a trail and a halo (pole kept bit for
// bit, trail and halo gone), a box's edges and corners (kept bit for bit), a box seen once
// whose corners cas_trail removes (cas_edge leaves the floor's median there, cas_hybrid the
// lower median of the corner's same-height cells, computed here independently), surface_prior
// and median_mix against their formulas, a flat floor, unknown = NaN, bit-determinism and
// parameter validation naming the field.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <string>
#include <utility>
#include <vector>

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

// A 10 x 10 box (rows 20-29, columns 10-19) at 0.3 m +- 2 mm on the noisy floor.
Maps NoisyBox(float certainty) {
    Maps p = NoisyFloor();
    for (int i = 0; i < 40; ++i) {
        for (int j = 0; j < 40; ++j) {
            p.c.at(i, j) = certainty;
            if (i >= 20 && i < 30 && j >= 10 && j < 20) {
                p.h.at(i, j) = 0.3F + Noise(j, i);
            }
        }
    }
    return p;
}

// The closed form of the surface rule: the lower median of the known cells of the 5 x 5
// window around (i, j) within tol of h(i, j).
float LowerMedianOfSameHeight(const Maps& p, int i, int j, float tol) {
    std::vector<float> v;
    for (int r = i - 2; r <= i + 2; ++r) {
        for (int s = j - 2; s <= j + 2; ++s) {
            if (r >= 0 && r < 40 && s >= 0 && s < 40 && p.c.at(r, s) > 0.0F &&
                std::abs(p.h.at(r, s) - p.h.at(i, j)) <= tol) {
                v.push_back(p.h.at(r, s));
            }
        }
    }
    std::sort(v.begin(), v.end());
    return v[(v.size() - 1) / 2];
}

constexpr std::pair<int, int> kCorners[] = {{20, 10}, {20, 19}, {29, 10}, {29, 19}};

TEST(CasHybrid, RemovesTrailAndHaloKeepsThePole) {
    const Maps p = PoleWithTrailAndHalo();
    const FilterParams params;
    const FilterResult out = RunFilter(FilterMethod::kCasHybrid, p.h, p.c, params);
    EXPECT_EQ(out.elevation.at(15, 20), 0.914F);                      // the pole, bit for bit
    EXPECT_LT(MedianFilter(p.h, params.baseline).at(15, 20), 0.05F);  // the median deletes it
    EXPECT_LT(out.elevation.at(15, 21), 0.05F);                       // the halo is gone
    EXPECT_LT(out.elevation.at(14, 20), 0.05F);
    for (int n = 0; n < 5; ++n) {
        EXPECT_LT(out.elevation.at(16 + n, 20), 0.05F) << n;  // the trail is gone
    }
    const FilterResult trail = RunFilter(FilterMethod::kCasTrail, p.h, p.c, params);
    EXPECT_EQ(out.classes.data, trail.classes.data);  // classes are cas_trail's
    // No trail cell is a surface (the trail's heights are 0.11-0.19 m apart): cas_edge's map.
    EXPECT_TRUE(
        SameBits(out.elevation, RunFilter(FilterMethod::kCasEdge, p.h, p.c, params).elevation));
    // With the preset's surface_prior and median_mix the pole keeps its height bit for bit.
    FilterParams tuned;
    tuned.Set("surface_prior", "1.5");
    tuned.Set("median_mix", "0.25");
    const FilterResult t = RunFilter(FilterMethod::kCasHybrid, p.h, p.c, tuned);
    EXPECT_EQ(t.elevation.at(15, 20), 0.914F);
    for (int n = 0; n < 5; ++n) {
        EXPECT_LT(t.elevation.at(16 + n, 20), 0.05F) << n;
    }
}

TEST(CasHybrid, SurfacePriorAndMedianMixFollowTheirFormulas) {
    // A noisy box whose corners are surfaces (9 same-height cells) and a dense trail beside a
    // pole whose cells the median of the raw map keeps high: B = M + mix (R - M) on every
    // non-object cell, B + c / (c + prior) (h - B) on a surface cell, all in float.
    Maps p = NoisyBox(36.0F);
    p.c.at(20, 10) = 6.0F;  // a corner seen twice
    p.h.at(5, 30) = 0.914F;
    p.c.at(5, 30) = 240.0F;
    int n = 0;
    for (int i = 6; i < 11; ++i) {
        for (int j = 29; j < 32; ++j) {
            p.h.at(i, j) = 0.1F + 0.053F * static_cast<float>((n * 7) % 15);
            p.c.at(i, j) = 3.0F;
            ++n;
        }
    }
    FilterParams params;
    params.Set("surface_prior", "1.5");
    params.Set("median_mix", "0.25");
    const FilterResult out = RunFilter(FilterMethod::kCasHybrid, p.h, p.c, params);
    const core::MapF m = MedianFilter(
        RunFilter(FilterMethod::kCasTrail, p.h, p.c, params).elevation, params.baseline);
    const core::MapF r = MedianFilter(p.h, params.baseline);
    const auto base = [&](int i, int j) { return m.at(i, j) + 0.25F * (r.at(i, j) - m.at(i, j)); };
    for (const auto& [i, j] : kCorners) {
        const float b = base(i, j);
        const float c = p.c.at(i, j);
        const float want = b + c / (c + 1.5F) * (p.h.at(i, j) - b);
        EXPECT_TRUE(SameBits(out.elevation.at(i, j), want)) << i << "," << j;
    }
    EXPECT_NEAR(out.elevation.at(20, 10), 0.3F * 6.0F / 7.5F, 0.01F);  // seen twice: 80 %
    EXPECT_NEAR(out.elevation.at(29, 19), 0.3F * 36.0F / 37.5F, 0.01F);
    EXPECT_LT(m.at(8, 30), 0.01F);  // cas_trail removed the trail: M is the floor
    EXPECT_GT(r.at(8, 30), 0.1F);   // the raw map's median keeps a trail height
    EXPECT_TRUE(SameBits(out.elevation.at(8, 30), base(8, 30)));
    EXPECT_TRUE(SameBits(out.elevation.at(35, 35), base(35, 35)));  // the floor
    EXPECT_EQ(out.elevation.at(5, 30), 0.914F);                     // the pole
}

TEST(CasHybrid, KeepsABoxsEdgesAndCornersBitForBit) {
    // An exact 0.2 m box on an exact floor: every cell, edges and corners included, as measured.
    Maps flat;
    for (int i = 20; i < 30; ++i) {
        for (int j = 10; j < 20; ++j) {
            flat.h.at(i, j) = 0.2F;
        }
    }
    const FilterParams params;
    EXPECT_TRUE(
        SameBits(RunFilter(FilterMethod::kCasHybrid, flat.h, flat.c, params).elevation, flat.h));
    // A noisy, well-observed box: each corner keeps its measured height although the median
    // returns the floor there (9 box cells of 25); the map is cas_edge's bit for bit (every
    // cell that stands out from the median is a cas_edge candidate).
    const Maps p = NoisyBox(36.0F);
    const FilterResult out = RunFilter(FilterMethod::kCasHybrid, p.h, p.c, params);
    const core::MapF median = MedianFilter(p.h, params.baseline);
    for (const auto& [i, j] : kCorners) {
        EXPECT_LT(median.at(i, j), 0.05F);
        EXPECT_TRUE(SameBits(out.elevation.at(i, j), p.h.at(i, j))) << i << "," << j;
    }
    EXPECT_TRUE(
        SameBits(out.elevation, RunFilter(FilterMethod::kCasEdge, p.h, p.c, params).elevation));
    EXPECT_EQ(out.elevation.at(25, 15), median.at(25, 15));  // inside: the median's
}

TEST(CasHybrid, RestoresABoxCornerCasTrailRemoved) {
    // The box and the floor seen once (c = 3 <= A): with h_sum_min 11 each corner window (9
    // box cells of 25) has too little height for Eq. 10's continuity and too little certainty
    // (75 < G), so cas_trail removes the four corners; their 5 x 5 median over cas_trail's
    // map is the floor. cas_edge leaves that; cas_hybrid sees a corner that stands out from it
    // with 9 known cells within surface_tol_m: the lower median of those.
    const Maps p = NoisyBox(3.0F);
    FilterParams params;
    params.Set("h_sum_min", "11");
    const FilterResult trail = RunFilter(FilterMethod::kCasTrail, p.h, p.c, params);
    const FilterResult edge = RunFilter(FilterMethod::kCasEdge, p.h, p.c, params);
    const FilterResult out = RunFilter(FilterMethod::kCasHybrid, p.h, p.c, params);
    const auto tol = static_cast<float>(params.cas.surface_tol_m);
    for (const auto& [i, j] : kCorners) {
        EXPECT_EQ(trail.classes.at(i, j), static_cast<std::uint8_t>(PixelClass::kRemoved));
        EXPECT_LT(std::abs(edge.elevation.at(i, j)), 0.01F) << i << "," << j;
        EXPECT_TRUE(SameBits(out.elevation.at(i, j), LowerMedianOfSameHeight(p, i, j, tol)))
            << i << "," << j << ": " << out.elevation.at(i, j);
        EXPECT_NEAR(out.elevation.at(i, j), 0.3F, 0.003F);
    }
    // Everywhere else cas_edge's map, bit for bit.
    int differ = 0;
    for (std::size_t n = 0; n < p.h.data.size(); ++n) {
        differ += std::memcmp(&edge.elevation.data[n], &out.elevation.data[n], 4) != 0 ? 1 : 0;
    }
    EXPECT_EQ(differ, 4);
    // surface_min above the corner's 9 same-height cells: no surface, cas_edge's floor.
    params.Set("surface_min", "10");
    const FilterResult strict = RunFilter(FilterMethod::kCasHybrid, p.h, p.c, params);
    EXPECT_LT(std::abs(strict.elevation.at(20, 10)), 0.01F);
}

TEST(CasHybrid, LeavesAFlatFloorAsTheMedianAndIsBitDeterministic) {
    Maps flat;  // exactly 0 m, all observed
    const FilterParams params;
    EXPECT_TRUE(
        SameBits(RunFilter(FilterMethod::kCasHybrid, flat.h, flat.c, params).elevation, flat.h));
    Maps p = NoisyFloor();
    for (int i = 0; i < 40; ++i) {
        for (int j = 0; j < 40; ++j) {
            p.c.at(i, j) = static_cast<float>(3 * (1 + (i + j) % 5));
        }
    }
    const FilterResult a = RunFilter(FilterMethod::kCasHybrid, p.h, p.c, params);
    const FilterResult b = RunFilter(FilterMethod::kCasHybrid, p.h, p.c, params);
    EXPECT_TRUE(SameBits(a.elevation, MedianFilter(p.h, params.baseline)));
    EXPECT_TRUE(SameBits(a.elevation, b.elevation));
    EXPECT_EQ(a.classes.data, b.classes.data);
}

TEST(CasHybrid, UnknownAsNaNFillsHolesAndNeverInventsTerrain) {
    Maps p = PoleWithTrailAndHalo();
    const float nan = std::numeric_limits<float>::quiet_NaN();
    p.h.at(8, 8) = nan;  // one never-observed floor cell: CAS's fill branch fills it
    p.c.at(8, 8) = 0.0F;
    for (int i = 26; i < 37; ++i) {  // an 11 x 11 never-observed patch
        for (int j = 26; j < 37; ++j) {
            p.h.at(i, j) = nan;
            p.c.at(i, j) = 0.0F;
        }
    }
    FilterParams params;
    params.Set("unknown", "nan");
    const FilterResult out = RunFilter(FilterMethod::kCasHybrid, p.h, p.c, params);
    EXPECT_EQ(out.elevation.at(15, 20), 0.914F);         // the pole
    EXPECT_LT(std::abs(out.elevation.at(8, 8)), 0.01F);  // the hole, from the floor around it
    EXPECT_TRUE(std::isnan(out.elevation.at(31, 31)));   // no terrain invented inside the patch
    for (int n = 0; n < 5; ++n) {
        const float v = out.elevation.at(16 + n, 20);  // the trail: unknown or floor
        EXPECT_TRUE(std::isnan(v) || v < 0.05F) << n << ": " << v;
    }
    // The removed box corner of the test above, unknown = NaN: cas_trail's removed corner is
    // unknown in T, the surface rule still restores it from the measured box cells.
    const Maps box = NoisyBox(3.0F);
    params.Set("h_sum_min", "11");
    const FilterResult corner = RunFilter(FilterMethod::kCasHybrid, box.h, box.c, params);
    const auto tol = static_cast<float>(params.cas.surface_tol_m);
    EXPECT_TRUE(SameBits(corner.elevation.at(29, 19), LowerMedianOfSameHeight(box, 29, 19, tol)));
}

TEST(CasHybrid, RejectsBadParametersNamingTheField) {
    for (const auto& [name, value] : {std::pair{"surface_min", "0"},
                                      {"surface_min", "226"},
                                      {"surface_min", "2.5"},
                                      {"surface_tol_m", "0"},
                                      {"surface_tol_m", "-0.01"},
                                      {"surface_tol_m", "nan"},
                                      {"edge_tol_m", "0"},
                                      {"surface_prior", "-1"},
                                      {"surface_prior", "2e6"},
                                      {"surface_prior", "nan"},
                                      {"median_mix", "-0.1"},
                                      {"median_mix", "1.5"}}) {
        ExpectSetRejects(name, value);
    }
    const Maps p = NoisyFloor();
    for (const char* field : {"surface_min", "edge_min", "surface_prior", "median_mix"}) {
        FilterParams bad;  // set directly: Validate (run by every filter) names it
        const std::string f = field;
        if (f == "surface_min" || f == "edge_min") {
            (f == "surface_min" ? bad.cas.surface_min : bad.cas.edge_min) = 0;
        } else {
            (f == "surface_prior" ? bad.cas.surface_prior : bad.cas.median_mix) = -1.0;
        }
        ExpectFilterRejects(FilterMethod::kCasHybrid, p.h, p.c, bad, field);
    }
    EXPECT_THROW((void)RunFilter(FilterMethod::kCasHybrid, p.h, core::MapF(3, 3), FilterParams{}),
                 InputError);
    EXPECT_EQ(ParseFilterMethod("cas_hybrid"), FilterMethod::kCasHybrid);
    EXPECT_EQ(ToString(FilterMethod::kCasHybrid), "cas_hybrid");
}

}  // namespace
}  // namespace casmap::mapper
