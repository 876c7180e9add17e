// cas_hybrid's spill rule (edge_spill_c, edge_spill_drop_m, edge_spill; docs/paper-notes.md
// "cas_hybrid", spills) on closed-form synthetic maps: a box whose far side has a one-hit
// column 2 cm below the top, one cell past the edge, before a three-cell shadow. The spill
// column takes out(f) + edge_spill (out(s) - out(f)) bit for bit, f the first shadow cell;
// nothing else changes; no edge_fill grows from it. Not a spill: the column at the top's
// height (the box's edge), a column seen twice with edge_spill_c 3, a column whose next cell
// beyond is observed. Off (edge_spill_c 0) whatever edge_spill says; validation naming the field.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <string>
#include <utility>
#include <vector>

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
using test_maps::SameBits;

// A 20 x 10 box (rows 10-29, columns 10-19) at 0.3 m +- 2 mm on the noisy floor, seen twice
// per cell; column 20 of the box's rows seen `spill_c` times at `spill_h` (+- 2 mm); columns
// 21-23 of those rows never observed.
Maps SpilledBox(float spill_h, float spill_c) {
    Maps p = NoisyFloor();
    for (int i = 0; i < 40; ++i) {
        for (int j = 0; j < 40; ++j) {
            p.c.at(i, j) = 6.0F;
            if (i >= 10 && i < 30 && j >= 10 && j < 20) {
                p.h.at(i, j) = 0.3F + Noise(j, i);
            }
            if (i >= 10 && i < 30 && j == 20) {
                p.h.at(i, j) = spill_h + Noise(j, i);
                p.c.at(i, j) = spill_c;
            }
            if (i >= 10 && i < 30 && j >= 21 && j < 24) {
                p.h.at(i, j) = 0.0F;
                p.c.at(i, j) = 0.0F;
            }
        }
    }
    return p;
}

FilterParams Params(const char* spill_c, const char* spill, const char* fill = "0") {
    FilterParams params;
    params.Set("A", "25");
    params.Set("edge_fill", fill);
    params.Set("edge_spill_c", spill_c);
    params.Set("edge_spill", spill);
    return params;
}

core::MapF Hybrid(const Maps& p, const FilterParams& params) {
    return RunFilter(FilterMethod::kCasHybrid, p.h, p.c, params).elevation;
}

TEST(CasHybridSpill, AOneHitCellBelowTheTopTakesItsShareOfTheStepDown) {
    const Maps p = SpilledBox(0.28F, 3.0F);
    const core::MapF off = Hybrid(p, Params("0", "0"));
    for (const char* share : {"0", "0.25", "1"}) {
        const core::MapF on = Hybrid(p, Params("3", share));
        const float s = std::stof(share);
        for (int i = 10; i < 30; ++i) {
            const float top = off.at(i, 20);   // kept near its measured height by the filter
            const float base = off.at(i, 21);  // the shadow's value: the floor
            EXPECT_NEAR(top, 0.28F, 0.03F) << i;
            EXPECT_LT(std::abs(base), 0.05F) << i;
            EXPECT_TRUE(SameBits(on.at(i, 20), base + s * (top - base)))
                << share << " " << i << ": " << on.at(i, 20);
        }
        const int changed = CellsThatDiffer(on, off);  // column 20 only (s = 1: rounding)
        EXPECT_TRUE(s == 1.0F ? changed <= 20 : changed == 20) << share << ": " << changed;
    }
    // edge_spill without edge_spill_c: off.
    EXPECT_EQ(CellsThatDiffer(Hybrid(p, Params("0", "0.25")), off), 0);
}

TEST(CasHybridSpill, NoEdgeFillGrowsFromASpill) {
    const Maps p = SpilledBox(0.28F, 3.0F);
    const core::MapF fill = Hybrid(p, Params("0", "0", "0.5"));
    const core::MapF plain = Hybrid(p, Params("0", "0"));
    const core::MapF both = Hybrid(p, Params("3", "0.25", "0.5"));
    for (int i = 10; i < 30; ++i) {
        EXPECT_GT(fill.at(i, 21), plain.at(i, 21) + 0.1F) << i;       // filled beside column 20
        EXPECT_TRUE(SameBits(both.at(i, 21), plain.at(i, 21))) << i;  // not beside a spill
        EXPECT_TRUE(
            SameBits(both.at(i, 20), plain.at(i, 21) + 0.25F * (plain.at(i, 20) - plain.at(i, 21))))
            << i;
    }
}

TEST(CasHybridSpill, TheEdgeAWellSeenCellAndAnObservedBeyondAreNoSpills) {
    // Column 20 at the top's height: the box's own edge cell, kept; the fill still grows.
    const Maps edge = SpilledBox(0.3F, 3.0F);
    EXPECT_EQ(CellsThatDiffer(Hybrid(edge, Params("3", "0.25", "0.5")),
                              Hybrid(edge, Params("0", "0", "0.5"))),
              0);
    // Seen twice with edge_spill_c 3: kept.
    const Maps twice = SpilledBox(0.28F, 6.0F);
    EXPECT_EQ(CellsThatDiffer(Hybrid(twice, Params("3", "0.25")), Hybrid(twice, Params("0", "0"))),
              0);
    // ... spills with edge_spill_c 6.
    EXPECT_EQ(CellsThatDiffer(Hybrid(twice, Params("6", "0.25")), Hybrid(twice, Params("0", "0"))),
              20);
    // The floor observed two cells beyond (column 22): no continuing shadow, no spill.
    Maps seen = SpilledBox(0.28F, 3.0F);
    for (int i = 10; i < 30; ++i) {
        seen.c.at(i, 22) = 6.0F;
    }
    EXPECT_EQ(CellsThatDiffer(Hybrid(seen, Params("3", "0.25")), Hybrid(seen, Params("0", "0"))),
              0);
    // A drop larger than the cell's: no spill.
    FilterParams deep = Params("3", "0.25");
    deep.Set("edge_spill_drop_m", "0.03");
    const Maps p = SpilledBox(0.28F, 3.0F);
    EXPECT_EQ(CellsThatDiffer(Hybrid(p, deep), Hybrid(p, Params("0", "0"))), 0);
}

TEST(CasHybridSpill, RejectsBadValuesNamingTheField) {
    const std::pair<const char*, std::vector<const char*>> cases[] = {
        {"edge_spill_c", {"-1", "2e6", "nan", "x"}},
        {"edge_spill_drop_m", {"-0.01", "1.5", "nan", "x"}},
        {"edge_spill", {"-0.1", "1.5", "nan", "x"}}};
    for (const auto& [name, values] : cases) {
        for (const char* value : values) {
            ExpectSetRejects(name, value);
        }
    }
    const Maps p = NoisyFloor();
    FilterParams bad;
    bad.cas.edge_spill = -0.5;  // set directly: Validate (run by every filter) names it
    ExpectFilterRejects(FilterMethod::kCasHybrid, p.h, p.c, bad, "edge_spill");
    FilterParams bad_c;
    bad_c.cas.edge_spill_c = -3.0;
    ExpectFilterRejects(FilterMethod::kCasHybrid, p.h, p.c, bad_c, "edge_spill_c");
}

}  // namespace
}  // namespace casmap::mapper
