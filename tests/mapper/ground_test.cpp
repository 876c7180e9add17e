// Ground-relative removal (mapper/ground.hpp) and cas_edge on closed-form terrain with unknown =
// nan: a slope crossing 0 m, a step, a ditch (none flattened, every observed cell stays known)
// and a pole on a slope (pole kept bit for bit, its trail set to the slope, not to NaN or 0 m).
#include "casmap/mapper/ground.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <string>
#include <vector>

#include "casmap/mapper/filters.hpp"
#include "synthetic_maps.hpp"

namespace casmap::mapper {
namespace {

using test_maps::Noise;
using test_maps::SameBits;

constexpr float kNaN = std::numeric_limits<float>::quiet_NaN();

// Terrain as a vehicle's scanner sees it: one scan line every 3rd row (`line_step`; the rows
// between never observed: NaN, c = 0), every cell of a line hit once (c = 3), +-2 mm noise. On a
// slope of 2 cm per row the lines are 6 cm apart in height, so a cell has only its own line's 4
// neighbours within cas_trail's support_tol_m (5 cm) and cas_trail removes it as unsupported: the
// case where cas_edge's median, with removed cells left unknown (NaN), lost the terrain.
struct Terrain {
    core::MapF truth, h, c;
};

template <typename F>
Terrain MakeTerrain(int rows, int cols, F height, int line_step = 3) {
    Terrain t{core::MapF(rows, cols), core::MapF(rows, cols), core::MapF(rows, cols, 3.0F)};
    for (int i = 0; i < rows; ++i) {
        for (int j = 0; j < cols; ++j) {
            t.truth.at(i, j) = height(i, j);
            t.h.at(i, j) = t.truth.at(i, j) + Noise(i, j);
            if (i % line_step != 0) {
                t.h.at(i, j) = kNaN;
                t.c.at(i, j) = 0.0F;
            }
        }
    }
    return t;
}

FilterParams NanParams() {
    FilterParams params;
    params.Set("unknown", "nan");
    return params;
}

bool Known(const Terrain& t, int i, int j) {
    return t.c.at(i, j) > 0.0F && !std::isnan(t.h.at(i, j));
}

// Largest |out - truth| over the interior cells the raw map knows; also counts the ones the
// output lost (NaN where the raw map had a height).
struct Check {
    double worst_m = 0.0;
    int lost = 0;
};

template <typename Skip>
Check Compare(const core::MapF& out, const Terrain& t, int margin, Skip skip) {
    Check r;
    for (int i = margin; i < t.truth.rows - margin; ++i) {
        for (int j = margin; j < t.truth.cols - margin; ++j) {
            if (!Known(t, i, j) || skip(i, j)) {
                continue;
            }
            if (std::isnan(out.at(i, j))) {
                ++r.lost;
                continue;
            }
            r.worst_m = std::max(r.worst_m, std::abs(static_cast<double>(out.at(i, j)) -
                                                     static_cast<double>(t.truth.at(i, j))));
        }
    }
    return r;
}

const auto kNone = [](int, int) { return false; };

// A 39 deg slope (2 cm per 25 mm row) from -0.6 m to +0.6 m.
Terrain Slope(int line_step = 3) {
    return MakeTerrain(
        60, 40, [](int i, int) { return -0.6F + 0.02F * static_cast<float>(i); }, line_step);
}

CasParams TrailParams(Unknown unknown, Ground ground) {
    CasParams cas;
    cas.support = Support::kHeight;
    cas.unknown = unknown;
    cas.ground = ground;
    return cas;
}

TEST(GroundRelativeVotes, AreCasOutputInThePapersConventionAndWithLocalGround) {
    const Terrain t = Slope();
    for (const CasParams& p :
         {TrailParams(Unknown::kZero, Ground::kZero), TrailParams(Unknown::kNaN, Ground::kLocal)}) {
        const FilterResult out = CasFilter(t.h, t.c, p);
        int removed = 0;
        for (std::size_t n = 0; n < out.classes.data.size(); ++n) {
            removed += out.classes.data[n] == static_cast<std::uint8_t>(PixelClass::kRemoved);
        }
        EXPECT_GT(removed, 0);  // the cells the rule is about exist here too
        EXPECT_TRUE(SameBits(GroundRelativeVotes(t.h, t.c, p, out), out.elevation));
    }
}

TEST(GroundRelativeVotes, RemovedCellsVoteTheirWindowsGroundFilledCellsNot) {
    const Terrain t = Slope();
    const CasParams cas = TrailParams(Unknown::kNaN, Ground::kZero);
    const FilterResult out = CasFilter(t.h, t.c, cas);
    const core::MapF votes = GroundRelativeVotes(t.h, t.c, cas, out);
    int removed = 0;
    int filled = 0;
    std::vector<float> v;
    for (int i = 0; i < t.h.rows; ++i) {
        for (int j = 0; j < t.h.cols; ++j) {
            const auto cls = static_cast<PixelClass>(out.classes.at(i, j));
            if (cls == PixelClass::kRemoved && Known(t, i, j)) {
                v.clear();  // the CAS window's known heights, clipped to the map
                for (int r = std::max(0, i - 2); r <= std::min(t.h.rows - 1, i + 2); ++r) {
                    for (int s = std::max(0, j - 2); s <= std::min(t.h.cols - 1, j + 2); ++s) {
                        if (Known(t, r, s)) {
                            v.push_back(t.h.at(r, s));
                        }
                    }
                }
                std::sort(v.begin(), v.end());
                EXPECT_EQ(votes.at(i, j), v[(v.size() - 1) / 2]) << i << "," << j;
                EXPECT_TRUE(std::isnan(out.elevation.at(i, j)));  // CAS left a hole there
                ++removed;
            } else if (cls == PixelClass::kFilled) {
                EXPECT_FALSE(std::isnan(out.elevation.at(i, j)));
                EXPECT_TRUE(std::isnan(votes.at(i, j))) << i << "," << j;
                ++filled;
            } else {
                const float a = votes.at(i, j);
                const float b = out.elevation.at(i, j);
                EXPECT_TRUE(std::memcmp(&a, &b, 4) == 0) << i << "," << j;
            }
        }
    }
    EXPECT_GT(removed, 100);  // on this slope cas_trail removes most observed cells
    EXPECT_GT(filled, 0);
}

TEST(CasEdgeOnTerrain, KeepsEveryObservedCellOfASlopeAtItsHeight) {
    const Terrain t = Slope();
    const FilterResult out = CasEdgeFilter(t.h, t.c, NanParams());
    const Check r = Compare(out.elevation, t, 0, kNone);
    EXPECT_EQ(r.lost, 0);
    EXPECT_LT(r.worst_m, 0.015);  // the slope stays a slope (not pulled to 0 m, not flattened)
}

TEST(CasEdgeOnTerrain, KeepsAStepOnASlope) {
    // A 0.2 m step down at column 20 along the slope (a vertical wall).
    const Terrain t = MakeTerrain(60, 40, [](int i, int j) {
        return -0.6F + 0.02F * static_cast<float>(i) - (j >= 20 ? 0.2F : 0.0F);
    });
    const FilterResult out = CasEdgeFilter(t.h, t.c, NanParams());
    // Every observed cell keeps its height within 1.5 cm, the two sides of the step included:
    // the step is not rounded into a ramp.
    const Check r = Compare(out.elevation, t, 0, kNone);
    EXPECT_EQ(r.lost, 0);
    EXPECT_LT(r.worst_m, 0.015);
    EXPECT_NEAR(out.elevation.at(30, 19), t.truth.at(30, 19), 0.015);  // high side
    EXPECT_NEAR(out.elevation.at(30, 20), t.truth.at(30, 20), 0.015);  // low side
}

TEST(CasEdgeOnTerrain, KeepsADitchAcrossASlope) {
    // A 7-row-wide, 0.3 m deep ditch across rows 27-33 (vertical walls; scan lines 27, 30 and
    // 33 in it).
    const Terrain t = MakeTerrain(60, 40, [](int i, int) {
        const float z = -0.6F + 0.02F * static_cast<float>(i);
        return i >= 27 && i <= 33 ? z - 0.3F : z;
    });
    const FilterResult out = CasEdgeFilter(t.h, t.c, NanParams());
    const Check r = Compare(out.elevation, t, 0, kNone);
    EXPECT_EQ(r.lost, 0);
    EXPECT_LT(r.worst_m, 0.015);  // not filled, its walls not rounded
    EXPECT_NEAR(out.elevation.at(30, 10), t.truth.at(30, 10), 0.015);  // its bottom
    EXPECT_NEAR(out.elevation.at(27, 10), t.truth.at(27, 10), 0.015);  // its first line
    EXPECT_NEAR(out.elevation.at(24, 10), t.truth.at(24, 10), 0.015);  // the line before it
}

TEST(CasEdgeOnTerrain, KeepsAPoleOnASlopeAndSetsItsTrailToTheSlope) {
    // The slope seen on every row (a table run). A ground estimate from the 5 x 5 window needs
    // the trail to be less than half of the window's known cells: in a scan every 3rd row a
    // five-cell trail is 4 of 9 known cells around its middle and raises the estimate.
    Terrain t = Slope(1);
    t.h.at(39, 20) = t.truth.at(39, 20) + 0.914F;  // a one-cell pole seen 80 times
    t.c.at(39, 20) = 240.0F;
    // One-hit mixed pixels behind it along the beams (rows 40-44 of its column), falling from
    // its top to the slope: cas_trail removes them (no known neighbour at their height).
    const float trail[] = {0.72F, 0.55F, 0.41F, 0.3F, 0.17F};
    for (int n = 0; n < 5; ++n) {
        t.h.at(40 + n, 20) = t.truth.at(40 + n, 20) + trail[n];
    }
    const FilterResult out = CasEdgeFilter(t.h, t.c, NanParams());
    for (int n = 0; n < 5; ++n) {
        EXPECT_EQ(out.classes.at(40 + n, 20), static_cast<std::uint8_t>(PixelClass::kRemoved));
    }
    EXPECT_EQ(out.elevation.at(39, 20), t.h.at(39, 20));  // the pole, bit for bit
    for (int n = 0; n < 5; ++n) {
        const float v = out.elevation.at(40 + n, 20);
        EXPECT_FALSE(std::isnan(v)) << n;                    // not a hole
        EXPECT_NEAR(v, t.truth.at(40 + n, 20), 0.015) << n;  // the slope under the trail
    }
    // The rest of the slope as in the plain case (the 2 outermost rows and columns left out:
    // on a densely seen 39 deg slope the median clipped at the map edge is 2 cm off).
    const Check r =
        Compare(out.elevation, t, 2, [](int i, int j) { return j == 20 && i >= 39 && i <= 44; });
    EXPECT_EQ(r.lost, 0);
    EXPECT_LT(r.worst_m, 0.015);
}

TEST(RestoreTrustedCells, GivesWellSeenCellsBackTheirHeightButNotAHalo) {
    // Default CAS parameters: A = 12, G = 120. A 12 x 12 floor (c = 30) and a "filtered" map
    // that set four cells to the floor: (2, 2) seen 400 times, (2, 8) seen 100 times (not more
    // than G), (8, 2) seen 300 times beside a kept neighbour (8, 3) seen more often at its
    // height (a halo), (8, 8) seen 200 times, filtered NaN.
    core::MapF h(12, 12, 0.0F);
    core::MapF c(12, 12, 30.0F);
    const struct {
        int i, j;
        float h, c;
    } cells[] = {{2, 2, 0.5F, 400.0F},
                 {2, 8, 0.5F, 100.0F},
                 {8, 2, 0.9F, 300.0F},
                 {8, 3, 0.91F, 500.0F},
                 {8, 8, 0.5F, 200.0F}};
    for (const auto& x : cells) {
        h.at(x.i, x.j) = x.h;
        c.at(x.i, x.j) = x.c;
    }
    core::MapF filtered(12, 12, 0.0F);
    filtered.at(8, 3) = 0.91F;  // kept as measured: the pole
    filtered.at(8, 8) = kNaN;
    const CasParams params;
    ASSERT_EQ(params.EffectiveG(), 120.0);
    core::MapF out = filtered;
    RestoreTrustedCells(h, c, params, out);
    EXPECT_EQ(out.at(2, 2), 0.5F);          // seen more than G times: its measured height
    EXPECT_EQ(out.at(2, 8), 0.0F);          // not more than G: the filter's value
    EXPECT_EQ(out.at(8, 2), 0.0F);          // the halo of a kept, better-seen neighbour
    EXPECT_TRUE(std::isnan(out.at(8, 8)));  // NaN left alone
    EXPECT_EQ(out.at(8, 3), 0.91F);         // the pole as it was
    out.data.assign(filtered.data.begin(), filtered.data.end());
    out.at(2, 2) = 0.47F;  // moved by 3 cm only (not more than support_tol_m): left
    RestoreTrustedCells(h, c, params, out);
    EXPECT_EQ(out.at(2, 2), 0.47F);
}

TEST(RestoreTrustedCells, KeepsTheFaceOfAnObstacleWhoseTopWasNeverSeen) {
    // A slope scanned every 2nd row, and a 0.8 m block at rows 30-44, columns 15-24 whose top
    // was never observed: only its front face, on scan line 30, was hit (heights 0.3-0.66 m
    // above the slope, each seen 300 times). Half the known cells around the face are the
    // slope, so the median puts it between; the face's measured heights are closer to the
    // truth (the block's top).
    Terrain t = MakeTerrain(
        60, 40,
        [](int i, int j) {
            const float z = -0.6F + 0.02F * static_cast<float>(i);
            return i >= 30 && i <= 44 && j >= 15 && j <= 24 ? z + 0.8F : z;
        },
        2);
    for (int i = 30; i <= 44; ++i) {
        for (int j = 15; j <= 24; ++j) {
            t.h.at(i, j) = kNaN;
            t.c.at(i, j) = 0.0F;
        }
    }
    const float ground = -0.6F + 0.02F * 30.0F;
    for (int j = 15; j <= 24; ++j) {
        t.h.at(30, j) = ground + 0.3F + 0.04F * static_cast<float>(j - 15);
        t.c.at(30, j) = 300.0F;
    }
    for (const FilterMethod method : {FilterMethod::kCasEdge, FilterMethod::kCasMedian}) {
        const FilterResult out = RunFilter(method, t.h, t.c, NanParams());
        for (int j = 15; j <= 24; ++j) {
            EXPECT_EQ(out.elevation.at(30, j), t.h.at(30, j)) << ToString(method) << " " << j;
        }
        // The slope around it within 3 cm (the cells beside the face see it in their window).
        const Check r = Compare(out.elevation, t, 0, [](int i, int j) {
            return i >= 30 && i <= 44 && j >= 15 && j <= 24;
        });
        EXPECT_EQ(r.lost, 0) << ToString(method);
        EXPECT_LT(r.worst_m, 0.03) << ToString(method);
    }
}

}  // namespace
}  // namespace casmap::mapper
