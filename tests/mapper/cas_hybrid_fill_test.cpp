// cas_hybrid's edge_fill (docs/paper-notes.md "cas_hybrid", occluded box edges) on closed-form
// synthetic maps: a box whose far side lies in a four-cell shadow (the first shadow column takes
// edge_fill of the step, bit for bit; nothing else changes), edge_fill_run (a one-cell spur of
// the box is not filled beside, the straight edge is), the same box seen more than A
// times (no fill), a one-cell gap with the floor seen beyond it (no fill), a pole with its
// trail and an unknown cell beside it (pole kept, trail gone, the pole's shadow not filled),
// unknown = NaN (no observed cell changes), validation naming the field.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <limits>
#include <string>
#include <utility>

#include "casmap/core/input_error.hpp"
#include "casmap/mapper/filters.hpp"
#include "synthetic_maps.hpp"

namespace casmap::mapper {
namespace {

using test_maps::CellsThatDiffer;
using test_maps::ExpectFilterRejects;
using test_maps::ExpectSetRejects;
using test_maps::Maps;
using test_maps::Noise;
using test_maps::NoisyFloor;
using test_maps::PoleWithTrailAndHalo;
using test_maps::SameBits;

// A 20 x 10 box (rows 10-29, columns 10-19) at 0.3 m +- 2 mm on the noisy floor, every cell
// seen `certainty` times, and its shadow: columns 20-23 of the box's rows never observed.
Maps ShadowedBox(float certainty) {
    Maps p = NoisyFloor();
    for (int i = 0; i < 40; ++i) {
        for (int j = 0; j < 40; ++j) {
            p.c.at(i, j) = certainty;
            if (i >= 10 && i < 30 && j >= 10 && j < 20) {
                p.h.at(i, j) = 0.3F + Noise(j, i);
            }
            if (i >= 10 && i < 30 && j >= 20 && j < 24) {
                p.h.at(i, j) = 0.0F;
                p.c.at(i, j) = 0.0F;
            }
        }
    }
    return p;
}

FilterParams Params(const char* fill) {
    FilterParams params;
    params.Set("A", "25");
    params.Set("edge_fill", fill);
    return params;
}

TEST(CasHybridFill, TheFirstShadowColumnTakesItsShareOfTheStep) {
    const Maps p = ShadowedBox(6.0F);  // seen twice: at most A
    const core::MapF off = RunFilter(FilterMethod::kCasHybrid, p.h, p.c, Params("0")).elevation;
    const core::MapF on = RunFilter(FilterMethod::kCasHybrid, p.h, p.c, Params("0.5")).elevation;
    for (int i = 10; i < 30; ++i) {
        const float base = off.at(i, 20);  // the shadow's fill: the floor
        const float top = off.at(i, 19);   // the box's edge, a surface
        EXPECT_LT(std::abs(base), 0.05F) << i;
        EXPECT_NEAR(top, 0.3F, 0.01F) << i;
        EXPECT_TRUE(SameBits(on.at(i, 20), base + 0.5F * (top - base)))
            << i << ": " << on.at(i, 20);
        EXPECT_TRUE(SameBits(on.at(i, 21), off.at(i, 21))) << i;  // beside no surface
    }
    EXPECT_EQ(CellsThatDiffer(on, off), 20);  // nothing else changes
    // edge_fill 1: the box's height.
    const core::MapF full = RunFilter(FilterMethod::kCasHybrid, p.h, p.c, Params("1")).elevation;
    EXPECT_TRUE(SameBits(full.at(20, 20), off.at(20, 19)));
}

TEST(CasHybridFill, EdgeFillRunNeedsTheEdgeToContinue) {
    // A one-cell spur of the box into its shadow at (20, 20): a surface (its window holds the
    // box) whose neighbours along the edge, (19, 20) and (21, 20), are unknown. edge_fill_run 0
    // fills (20, 21) beside it; 1 does not (a smeared protrusion, not the box's edge line), and
    // still fills the straight edge; 2 also leaves the two corner rows (one neighbour along).
    Maps p = ShadowedBox(6.0F);
    p.c.at(20, 20) = 6.0F;
    p.h.at(20, 20) = 0.3F + Noise(20, 20);
    FilterParams any = Params("0.5");
    FilterParams one = Params("0.5");
    FilterParams two = Params("0.5");
    one.Set("edge_fill_run", "1");
    two.Set("edge_fill_run", "2");
    const core::MapF off = RunFilter(FilterMethod::kCasHybrid, p.h, p.c, Params("0")).elevation;
    const core::MapF a = RunFilter(FilterMethod::kCasHybrid, p.h, p.c, any).elevation;
    const core::MapF b = RunFilter(FilterMethod::kCasHybrid, p.h, p.c, one).elevation;
    const core::MapF c = RunFilter(FilterMethod::kCasHybrid, p.h, p.c, two).elevation;
    EXPECT_GT(a.at(20, 21), off.at(20, 21) + 0.1F);
    EXPECT_TRUE(SameBits(b.at(20, 21), off.at(20, 21)));
    for (int i = 10; i < 30; ++i) {
        if (i == 20) {
            continue;
        }
        EXPECT_TRUE(SameBits(b.at(i, 20), a.at(i, 20))) << i;  // the straight edge: filled
        EXPECT_GT(b.at(i, 20), off.at(i, 20) + 0.1F) << i;
        const bool corner = i == 10 || i == 29;
        EXPECT_EQ(SameBits(c.at(i, 20), off.at(i, 20)), corner) << i;
    }
}

TEST(CasHybridFill, NoFillBesideAWellSeenSurfaceOrAGapWithTheFloorBeyond) {
    // The same box seen 60 times (> A = 25): a sliver of the box in the unknown cell would
    // have been hit; the fill leaves the map as it is.
    const Maps seen = ShadowedBox(60.0F);
    EXPECT_EQ(CellsThatDiffer(
                  RunFilter(FilterMethod::kCasHybrid, seen.h, seen.c, Params("0.5")).elevation,
                  RunFilter(FilterMethod::kCasHybrid, seen.h, seen.c, Params("0")).elevation),
              0);
    // A one-cell gap beside the box with the floor observed beyond it: no shadow.
    Maps gap = ShadowedBox(6.0F);
    for (int i = 10; i < 30; ++i) {
        for (int j = 20; j < 24; ++j) {
            gap.c.at(i, j) = 6.0F;
        }
    }
    gap.c.at(15, 20) = 0.0F;
    EXPECT_EQ(
        CellsThatDiffer(RunFilter(FilterMethod::kCasHybrid, gap.h, gap.c, Params("0.5")).elevation,
                        RunFilter(FilterMethod::kCasHybrid, gap.h, gap.c, Params("0")).elevation),
        0);
}

TEST(CasHybridFill, KeepsThePoleRemovesTheTrailAndDoesNotGrowThePole) {
    Maps p = PoleWithTrailAndHalo();
    p.c.at(15, 19) = 0.0F;  // the pole's "shadow": two unknown cells beside it
    p.h.at(15, 19) = 0.0F;
    p.c.at(15, 18) = 0.0F;
    p.h.at(15, 18) = 0.0F;
    const FilterResult out = RunFilter(FilterMethod::kCasHybrid, p.h, p.c, Params("1"));
    EXPECT_EQ(out.elevation.at(15, 20), 0.914F);  // the pole, bit for bit
    for (int n = 0; n < 5; ++n) {
        EXPECT_LT(out.elevation.at(16 + n, 20), 0.05F) << n;  // the trail is gone
    }
    // The pole is no surface (3 cells within edge_tol_m of its top): no fill beside it.
    EXPECT_LT(out.elevation.at(15, 19), 0.05F);
    EXPECT_EQ(CellsThatDiffer(out.elevation,
                              RunFilter(FilterMethod::kCasHybrid, p.h, p.c, Params("0")).elevation),
              0);
    // At the preset's values (config/presets/cas_hybrid.yaml, v4): the same.
    FilterParams preset = Params("0.5");
    for (const auto& [name, value] : {std::pair{"h_sum_min", "9"},
                                      {"support_min", "5"},
                                      {"support_tol_m", "0.13"},
                                      {"edge_min", "9"},
                                      {"edge_tol_m", "0.1"},
                                      {"surface_prior", "0.75"},
                                      {"median_mix", "0.1875"},
                                      {"edge_fill_run", "1"}}) {
        preset.Set(name, value);
    }
    const FilterResult v4 = RunFilter(FilterMethod::kCasHybrid, p.h, p.c, preset);
    EXPECT_EQ(v4.elevation.at(15, 20), 0.914F);
    for (int n = 0; n < 5; ++n) {
        EXPECT_LT(v4.elevation.at(16 + n, 20), 0.05F) << n;
    }
    EXPECT_LT(v4.elevation.at(15, 19), 0.05F);
}

TEST(CasHybridFill, UnknownAsNaNChangesNoObservedCell) {
    Maps p = ShadowedBox(6.0F);
    for (int i = 10; i < 30; ++i) {
        for (int j = 20; j < 24; ++j) {
            p.h.at(i, j) = std::numeric_limits<float>::quiet_NaN();
        }
    }
    FilterParams off = Params("0");
    FilterParams on = Params("0.5");
    off.Set("unknown", "nan");
    on.Set("unknown", "nan");
    const core::MapF a = RunFilter(FilterMethod::kCasHybrid, p.h, p.c, off).elevation;
    const core::MapF b = RunFilter(FilterMethod::kCasHybrid, p.h, p.c, on).elevation;
    for (int i = 0; i < 40; ++i) {
        for (int j = 0; j < 40; ++j) {
            if (p.c.at(i, j) > 0.0F) {
                EXPECT_TRUE(SameBits(a.at(i, j), b.at(i, j))) << i << "," << j;
            } else if (!std::isnan(b.at(i, j))) {
                EXPECT_GE(b.at(i, j), a.at(i, j)) << i << "," << j;  // only ever raised
            }
        }
    }
}

TEST(CasHybridFill, RejectsBadValuesNamingTheField) {
    for (const char* value : {"-0.1", "1.5", "nan", "x"}) {
        ExpectSetRejects("edge_fill", value);
    }
    for (const char* value : {"-1", "3", "1.5", "x"}) {
        ExpectSetRejects("edge_fill_run", value);
    }
    FilterParams run;
    run.cas.edge_fill_run = 3;
    ExpectFilterRejects(FilterMethod::kCasHybrid, NoisyFloor().h, NoisyFloor().c, run,
                        "edge_fill_run");
    FilterParams bad;
    bad.cas.edge_fill = 2.0;  // set directly: Validate (run by every filter) names it
    const Maps p = NoisyFloor();
    ExpectFilterRejects(FilterMethod::kCasHybrid, p.h, p.c, bad, "edge_fill");
}

}  // namespace
}  // namespace casmap::mapper
