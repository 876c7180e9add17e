// BoundByMeasurement (mapper/ground.hpp): with unknown = nan the median-based CAS variants hold
// every known cell near its measurement (never raised by more than support_tol_m; cells seen
// more than A times not lowered by more than it), and nothing changes with unknown = zero.
// Closed-form cells, then the terrain cases that motivated it: a tall block on a slope seen only
// on its face (kept), the ground beside a densely seen obstacle in a sparse scan (not raised onto
// it), and a pole with a trail on a slope (trail removed, pole kept) for all three variants.
// SmoothSurfaceCells: the Wiener estimate for noise-level cells only, with unknown = nan.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <string>

#include "casmap/mapper/filters.hpp"
#include "casmap/mapper/ground.hpp"
#include "synthetic_maps.hpp"

namespace casmap::mapper {
namespace {

using test_maps::Noise;
using test_maps::SameBits;

constexpr float kNaN = std::numeric_limits<float>::quiet_NaN();
constexpr FilterMethod kVariants[] = {FilterMethod::kCasEdge, FilterMethod::kCasHybrid,
                                      FilterMethod::kCasMedian};

FilterParams NanParams() {
    FilterParams params;
    params.Set("unknown", "nan");
    return params;
}

TEST(BoundByMeasurement, HoldsKnownCellsNearTheirMeasurementOnlyWithUnknownNan) {
    // Default CAS parameters: A = 12, support_tol_m = 0.05. A 6 x 6 floor seen 30 times and a
    // "filtered" map that moved some cells.
    core::MapF h(6, 6, 0.0F);
    core::MapF c(6, 6, 30.0F);
    h.at(2, 2) = 0.5F;  // seen 30 times (> A), lowered to the floor
    h.at(3, 3) = 0.5F;  // seen 9 times (not > A), lowered to the floor
    c.at(3, 3) = 9.0F;
    h.at(1, 4) = 0.5F;  // lowered by 4 cm only
    h.at(5, 5) = kNaN;  // never observed, filled
    c.at(5, 5) = 0.0F;
    core::MapF filtered(6, 6, 0.0F);
    filtered.at(1, 1) = 0.4F;  // raised from 0 m by 0.4 m
    filtered.at(1, 4) = 0.46F;
    filtered.at(4, 4) = kNaN;
    filtered.at(5, 5) = 0.3F;
    CasParams params;
    ASSERT_EQ(params.EffectiveA(), 12.0);
    core::MapF out = filtered;
    BoundByMeasurement(h, c, params, out);  // unknown = zero: nothing
    EXPECT_TRUE(SameBits(out, filtered));
    params.unknown = Unknown::kNaN;
    BoundByMeasurement(h, c, params, out);
    EXPECT_EQ(out.at(1, 1), 0.0F + static_cast<float>(params.support_tol_m));  // at most h + tol
    EXPECT_EQ(out.at(2, 2), 0.5F);   // seen more than A times: its measurement
    EXPECT_EQ(out.at(3, 3), 0.0F);   // a possible mixed pixel: the filter's value
    EXPECT_EQ(out.at(1, 4), 0.46F);  // within support_tol_m: left
    EXPECT_TRUE(std::isnan(out.at(4, 4)));
    EXPECT_EQ(out.at(5, 5), 0.3F);  // not a measured cell: left
    EXPECT_EQ(out.at(0, 0), 0.0F);
}

// A 39 deg slope (2 cm per 25 mm row) from -0.6 m, scanned every `step`-th row (the rows between
// never observed), every cell of a line hit once (c = 3) with +-2 mm noise.
struct Terrain {
    core::MapF truth, h, c;
};

float SlopeZ(int i) { return -0.6F + 0.02F * static_cast<float>(i); }

Terrain SparseSlope(int step) {
    Terrain t{core::MapF(60, 40), core::MapF(60, 40, kNaN), core::MapF(60, 40, 0.0F)};
    for (int i = 0; i < 60; ++i) {
        for (int j = 0; j < 40; ++j) {
            t.truth.at(i, j) = SlopeZ(i);
            if (i % step == 0) {
                t.h.at(i, j) = SlopeZ(i) + Noise(i, j);
                t.c.at(i, j) = 3.0F;
            }
        }
    }
    return t;
}

TEST(BoundByMeasurement, VariantsKeepTheFaceOfABlockWhoseTopWasNeverSeen) {
    // A 0.8 m block at rows 30-44, columns 15-24 of a slope scanned every 2nd row; only its front
    // face was hit, on scan line 30 (0.3-0.66 m above the slope, each cell seen 10 times: more
    // than A = 12 / 3 hits, fewer than G = 120, so RestoreTrustedCells leaves it to the median).
    Terrain t = SparseSlope(2);
    for (int i = 30; i <= 44; ++i) {
        for (int j = 15; j <= 24; ++j) {
            t.truth.at(i, j) = SlopeZ(i) + 0.8F;
            t.h.at(i, j) = kNaN;
            t.c.at(i, j) = 0.0F;
        }
    }
    for (int j = 15; j <= 24; ++j) {
        t.h.at(30, j) = SlopeZ(30) + 0.3F + 0.04F * static_cast<float>(j - 15);
        t.c.at(30, j) = 30.0F;
    }
    for (const FilterMethod method : kVariants) {
        const FilterResult out = RunFilter(method, t.h, t.c, NanParams());
        int lowered = 0;
        for (int j = 15; j <= 24; ++j) {
            // Kept, or moved by the median within support_tol_m (never to the slope).
            EXPECT_NEAR(out.elevation.at(30, j), t.h.at(30, j), 0.05) << ToString(method) << j;
            lowered += out.elevation.at(30, j) < t.h.at(30, j) - 0.05F ? 1 : 0;
        }
        EXPECT_EQ(lowered, 0) << ToString(method);
        for (int i = 0; i < 60; ++i) {
            for (int j = 0; j < 40; ++j) {
                const bool block = i >= 30 && i <= 44 && j >= 15 && j <= 24;
                if (t.c.at(i, j) > 0.0F && !block) {  // the slope: at most 5 cm off
                    EXPECT_NEAR(out.elevation.at(i, j), t.truth.at(i, j), 0.055)
                        << ToString(method) << " " << i << "," << j;
                }
            }
        }
    }
}

TEST(BoundByMeasurement, GroundBesideADenselySeenObstacleIsNotRaisedOntoIt) {
    // Flat ground seen on every 3rd row (c = 3) and a 0.5 m platform (rows 20-39, columns
    // 20-39) whose top was seen on every row, 30 times per cell. A ground cell on row 18 or 21
    // beside the platform's corner has more platform than ground cells in its 5 x 5 window: the
    // median of the known cells is the platform's height.
    Terrain t = SparseSlope(3);
    for (int i = 0; i < 60; ++i) {
        for (int j = 0; j < 40; ++j) {
            t.truth.at(i, j) = 0.0F;
            if (t.c.at(i, j) > 0.0F) {
                t.h.at(i, j) = Noise(i, j);
            }
            if (i >= 20 && i <= 39 && j >= 20) {
                t.truth.at(i, j) = 0.5F;
                t.h.at(i, j) = 0.5F + Noise(i, j);
                t.c.at(i, j) = 30.0F;
            }
        }
    }
    for (const FilterMethod method : kVariants) {
        const FilterResult out = RunFilter(method, t.h, t.c, NanParams());
        for (int i = 0; i < 60; ++i) {
            for (int j = 0; j < 40; ++j) {
                if (t.c.at(i, j) > 0.0F) {
                    EXPECT_LE(out.elevation.at(i, j), t.h.at(i, j) + 0.05F + 1e-6F)
                        << ToString(method) << " " << i << "," << j;
                }
            }
        }
        // The platform's edge, seen more than A times, keeps its height.
        for (int j = 20; j < 40; ++j) {
            EXPECT_NEAR(out.elevation.at(20, j), 0.5F, 0.05) << ToString(method) << j;
        }
    }
}

TEST(BoundByMeasurement, VariantsRemoveAPolesTrailOnASlopeAndKeepThePole) {
    // The slope seen on every row; a one-cell pole seen 80 times at (39, 20) and five one-hit
    // mixed pixels behind it, falling from its top to the slope.
    Terrain t = SparseSlope(1);
    t.h.at(39, 20) = SlopeZ(39) + 0.914F;
    t.c.at(39, 20) = 240.0F;
    const float trail[] = {0.72F, 0.55F, 0.41F, 0.3F, 0.17F};
    for (int n = 0; n < 5; ++n) {
        t.h.at(40 + n, 20) = SlopeZ(40 + n) + trail[n];
    }
    for (const FilterMethod method : kVariants) {
        const FilterResult out = RunFilter(method, t.h, t.c, NanParams());
        EXPECT_EQ(out.elevation.at(39, 20), t.h.at(39, 20)) << ToString(method);  // the pole
        // The trail: on the slope, within one row's rise (cas_median's median of the raw map
        // counts the trail's cells among its 25 votes and lands one row up the slope).
        for (int n = 0; n < 5; ++n) {
            EXPECT_NEAR(out.elevation.at(40 + n, 20), SlopeZ(40 + n), 0.025)
                << ToString(method) << " " << n;
        }
    }
}

TEST(SmoothSurfaceCells, GivesNoiseLevelCellsTheWienerEstimateOnlyWithUnknownNan) {
    // A noisy 20 x 20 floor (+-2 mm), a 0.9 m pole at (10, 10) and a 1 cm bump at (4, 4); the
    // "median" and "filtered" maps are the variant's: the floor's median, the pole kept.
    core::MapF h(20, 20);
    for (int i = 0; i < 20; ++i) {
        for (int j = 0; j < 20; ++j) {
            h.at(i, j) = Noise(i, j);
        }
    }
    h.at(10, 10) = 0.9F;
    h.at(4, 4) = 0.01F;
    const core::MapF c(20, 20, 30.0F);
    FilterParams params;
    const core::MapF median = MedianFilter(h, params.baseline);
    core::MapF filtered = median;
    filtered.at(10, 10) = 0.9F;
    core::MapF out = filtered;
    SmoothSurfaceCells(h, c, median, params, out);  // unknown = zero: nothing
    EXPECT_TRUE(SameBits(out, filtered));
    params.Set("unknown", "nan");
    const core::MapF w = WienerFilter(h, params.baseline);
    const core::MapF nan_median = MedianFilter(h, params.baseline);
    filtered = nan_median;
    filtered.at(10, 10) = 0.9F;
    out = filtered;
    SmoothSurfaceCells(h, c, nan_median, params, out);
    EXPECT_EQ(out.at(10, 10), 0.9F);  // the pole stands out from the median: kept
    int smoothed = 0;
    for (int i = 0; i < 20; ++i) {
        for (int j = 0; j < 20; ++j) {
            const float d = 0.015F;  // surface_tol_m
            const bool near = std::abs(filtered.at(i, j) - h.at(i, j)) <= d &&
                              std::abs(nan_median.at(i, j) - h.at(i, j)) <= d &&
                              std::abs(w.at(i, j) - h.at(i, j)) <= d;
            EXPECT_EQ(out.at(i, j), near ? w.at(i, j) : filtered.at(i, j)) << i << "," << j;
            smoothed += near ? 1 : 0;
        }
    }
    EXPECT_GT(smoothed, 300);  // the floor away from the pole
}

TEST(SmoothSurfaceCells, VariantsFollowANoisySlopeCloserThanTheRawMap) {
    // The slope seen on every row with +-8 mm noise. The 5 x 5 median of a 2 cm-per-row slope is
    // the median of the centre row's five cells: 0.45 of the raw map's squared error; with the
    // Wiener estimate on the noise-level cells each variant is below 0.2 of it (0.05).
    Terrain t = SparseSlope(1);
    double raw_se = 0.0;
    for (int i = 0; i < 60; ++i) {
        for (int j = 0; j < 40; ++j) {
            t.h.at(i, j) = SlopeZ(i) + 4.0F * Noise(i, j);
            t.c.at(i, j) = 30.0F;
            if (i >= 2 && i < 58 && j >= 2 && j < 38) {
                raw_se += std::pow(static_cast<double>(t.h.at(i, j) - t.truth.at(i, j)), 2);
            }
        }
    }
    for (const FilterMethod method : kVariants) {
        const FilterResult out = RunFilter(method, t.h, t.c, NanParams());
        double se = 0.0;
        for (int i = 2; i < 58; ++i) {
            for (int j = 2; j < 38; ++j) {
                se += std::pow(static_cast<double>(out.elevation.at(i, j) - t.truth.at(i, j)), 2);
            }
        }
        EXPECT_LT(se, 0.2 * raw_se) << ToString(method);
    }
}

}  // namespace
}  // namespace casmap::mapper
