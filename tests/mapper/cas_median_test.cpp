// cas_median on synthetic maps: a pole with a mixed-pixel trail and a halo (trail and halo
// go, the pole stays at its height), a flat noisy floor (smoothed exactly as the median does),
// bit-determinism.
#include <gtest/gtest.h>

#include <cstdint>
#include <cstring>
#include <string>

#include "casmap/core/input_error.hpp"
#include "casmap/mapper/filters.hpp"
#include "synthetic_maps.hpp"

namespace casmap::mapper {
namespace {

using test_maps::Maps;
using test_maps::Noise;
using test_maps::NoisyFloor;
using test_maps::PoleWithTrailAndHalo;

TEST(CasMedian, RemovesTrailAndHaloKeepsThePole) {
    const Maps p = PoleWithTrailAndHalo();
    const FilterParams params;
    const FilterResult trail = RunFilter(FilterMethod::kCasTrail, p.h, p.c, params);
    EXPECT_EQ(trail.elevation.at(15, 21), p.h.at(15, 21));  // cas_trail keeps the halo
    const FilterResult out = RunFilter(FilterMethod::kCasMedian, p.h, p.c, params);
    const core::MapF median = MedianFilter(p.h, params.baseline);
    EXPECT_EQ(out.elevation.at(15, 20), 0.914F);  // the pole, bit for bit
    EXPECT_LT(median.at(15, 20), 0.05F);          // which the median alone deletes
    EXPECT_LT(out.elevation.at(15, 21), 0.05F);   // the halo is gone
    EXPECT_LT(out.elevation.at(14, 20), 0.05F);
    for (int n = 0; n < 5; ++n) {
        EXPECT_LT(out.elevation.at(16 + n, 20), 0.05F) << n;  // the trail is gone
    }
    // Every other cell is the median's, bit for bit.
    int differ = 0;
    for (std::size_t n = 0; n < p.h.data.size(); ++n) {
        differ += std::memcmp(&median.data[n], &out.elevation.data[n], 4) != 0 ? 1 : 0;
    }
    EXPECT_EQ(differ, 1);
    EXPECT_EQ(out.classes.data, trail.classes.data);  // classes are cas_trail's
}

TEST(CasMedian, SmoothsAFlatNoisyFloorAsTheMedian) {
    Maps p;
    for (int i = 0; i < 40; ++i) {
        for (int j = 0; j < 40; ++j) {
            p.h.at(i, j) = Noise(i, j);
            p.c.at(i, j) = static_cast<float>(3 * (1 + (i + j) % 5));
        }
    }
    const FilterParams params;
    const FilterResult out = RunFilter(FilterMethod::kCasMedian, p.h, p.c, params);
    const core::MapF median = MedianFilter(p.h, params.baseline);
    ASSERT_EQ(out.elevation.data.size(), median.data.size());
    EXPECT_EQ(std::memcmp(out.elevation.data.data(), median.data.data(), 4 * median.data.size()),
              0);
}

TEST(CasMedian, KeepsAWideBoxTopAndIsBitDeterministic) {
    Maps p = PoleWithTrailAndHalo();
    for (int i = 25; i < 35; ++i) {
        for (int j = 5; j < 15; ++j) {
            p.h.at(i, j) = 0.2F + Noise(i, j);  // a 10 x 10 box: the median keeps its inside
        }
    }
    FilterParams params;
    params.Set("support_tol_m", "0.09");
    const FilterResult a = RunFilter(FilterMethod::kCasMedian, p.h, p.c, params);
    const FilterResult b = RunFilter(FilterMethod::kCasMedian, p.h, p.c, params);
    EXPECT_NEAR(a.elevation.at(30, 10), 0.2F, 0.005F);
    EXPECT_EQ(a.elevation.at(15, 20), 0.914F);
    ASSERT_EQ(a.elevation.data.size(), b.elevation.data.size());
    EXPECT_EQ(
        std::memcmp(a.elevation.data.data(), b.elevation.data.data(), 4 * a.elevation.data.size()),
        0);
}

// A flat 0.2 m box top, 10 x 10 cells, on the noisy floor (the pole and its trail stay too):
// the median rounds its corners to the floor (a corner has 9 top cells of 25); cas_median
// keeps every box cell at 0.2 m bit for bit (the surface test: 9 >= surface_min same-height
// known cells), keeps the pole, removes the trail, and leaves the floor as the median has it.
TEST(CasMedian, KeepsABoxsEdgesAndCornersBitForBit) {
    Maps p = PoleWithTrailAndHalo();
    for (int i = 25; i < 35; ++i) {
        for (int j = 5; j < 15; ++j) {
            p.h.at(i, j) = 0.2F;
        }
    }
    FilterParams params;
    params.Set("support_tol_m", "0.09");
    const core::MapF median = MedianFilter(p.h, params.baseline);
    EXPECT_LT(median.at(25, 5), 0.01F);  // the median cuts the corner off
    EXPECT_LT(median.at(34, 14), 0.01F);
    for (const char* unknown : {"zero", "nan"}) {
        params.Set("unknown", unknown);
        const FilterResult out = RunFilter(FilterMethod::kCasMedian, p.h, p.c, params);
        for (int i = 25; i < 35; ++i) {
            for (int j = 5; j < 15; ++j) {
                EXPECT_EQ(out.elevation.at(i, j), 0.2F) << unknown << " " << i << "," << j;
            }
        }
        EXPECT_EQ(out.elevation.at(15, 20), 0.914F) << unknown;  // the pole
        for (int n = 0; n < 5; ++n) {
            EXPECT_LT(out.elevation.at(16 + n, 20), 0.05F) << unknown << " trail " << n;
        }
        // Off the box's outline and the pole, every cell is the median's (floor cells next to
        // the box do not stand out from the median); with unknown = nan, SmoothSurfaceCells
        // (mapper/ground.hpp) gives a floor cell the Wiener estimate instead when both lie
        // within surface_tol_m of its measurement.
        const core::MapF m = MedianFilter(p.h, params.baseline);
        const core::MapF w = WienerFilter(p.h, params.baseline);
        const bool nan_mode = std::string(unknown) == "nan";
        for (int i = 0; i < 40; ++i) {
            for (int j = 0; j < 40; ++j) {
                const bool box = i >= 25 && i < 35 && j >= 5 && j < 15;
                if (!box && !(i == 15 && j == 20)) {
                    const float v = out.elevation.at(i, j);
                    EXPECT_TRUE(v == m.at(i, j) || (nan_mode && v == w.at(i, j)))
                        << unknown << " " << i << "," << j << ": " << v;
                }
            }
        }
    }
}

// A box edge needs surface_min same-height cells: with surface_min above what a corner has
// (9 in a 5 x 5 window) the corner falls back to the median (the first version's behaviour).
TEST(CasMedian, SurfaceMinDecidesTheCorner) {
    Maps p = PoleWithTrailAndHalo();
    for (int i = 25; i < 35; ++i) {
        for (int j = 5; j < 15; ++j) {
            p.h.at(i, j) = 0.2F;
        }
    }
    FilterParams params;
    params.Set("support_tol_m", "0.09");
    params.Set("surface_min", "10");
    const FilterResult out = RunFilter(FilterMethod::kCasMedian, p.h, p.c, params);
    const core::MapF median = MedianFilter(p.h, params.baseline);
    EXPECT_EQ(out.elevation.at(34, 14), median.at(34, 14));  // 9 < 10: the median's corner
    EXPECT_EQ(out.elevation.at(34, 10), 0.2F);               // an edge cell has 15
}

TEST(CasMedian, NeedsTheCertaintyMap) {
    const Maps p = PoleWithTrailAndHalo();
    EXPECT_THROW((void)RunFilter(FilterMethod::kCasMedian, p.h, core::MapF(3, 3), FilterParams{}),
                 InputError);
    EXPECT_EQ(ParseFilterMethod("cas_median"), FilterMethod::kCasMedian);
    EXPECT_EQ(ToString(FilterMethod::kCasMedian), "cas_median");
}

}  // namespace
}  // namespace casmap::mapper
