// CAS filter (Eq. 7-10) behaviours required by issue 2, on hand-built maps.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <random>
#include <vector>

#include "casmap/core/input_error.hpp"
#include "casmap/mapper/filters.hpp"

namespace casmap::mapper {
namespace {

constexpr float kPlateau = 0.414F;

core::MapF Filled(int rows, int cols, float v) { return core::MapF(rows, cols, v); }

PixelClass ClassAt(const FilterResult& r, int i, int j) {
    return static_cast<PixelClass>(r.classes.at(i, j));
}

TEST(CasParams, DerivesAAndGFromEq8) {
    CasParams p;
    EXPECT_DOUBLE_EQ(p.EffectiveA(), 12.0);  // 3 * (round(0.025 / (1 * 1/75)) + 2) = 3 * 4
    EXPECT_DOUBLE_EQ(p.EffectiveG(), 120.0);
    p.speed_m_s = 0.5;  // 0.025 / (0.5 / 75) = 3.75 -> 4
    EXPECT_DOUBLE_EQ(p.EffectiveA(), 18.0);
    p.A = 5.0;
    EXPECT_DOUBLE_EQ(p.EffectiveA(), 5.0);
    EXPECT_DOUBLE_EQ(p.EffectiveG(), 50.0);
    p.G = 7.0;
    EXPECT_DOUBLE_EQ(p.EffectiveG(), 7.0);
}

TEST(CasFilter, PixelsAboveAAreBitIdentical) {
    const unsigned seed = 42;
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> h(-0.5F, 1.0F);
    std::uniform_int_distribution<int> hits(0, 12);
    core::MapF elevation(40, 50);
    core::MapF certainty(40, 50);
    for (std::size_t i = 0; i < elevation.data.size(); ++i) {
        certainty.data[i] = static_cast<float>(3 * hits(rng));
        elevation.data[i] = certainty.data[i] > 0 ? h(rng) : 0.0F;
    }
    std::vector<CasParams> variants(5);
    variants[1].gs_mode = GsMode::kVariance;
    variants[2].normalise = Normalise::kGlobal;
    variants[3].e_term = true;
    variants[4].wm_empty = WmEmpty::kSkip;
    for (const CasParams& p : variants) {
        const FilterResult r = CasFilter(elevation, certainty, p);
        int checked = 0;
        for (std::size_t i = 0; i < elevation.data.size(); ++i) {
            if (certainty.data[i] > p.EffectiveA()) {
                ASSERT_EQ(std::memcmp(&r.elevation.data[i], &elevation.data[i], sizeof(float)), 0)
                    << "seed " << seed << " pixel " << i;
                ++checked;
            }
        }
        EXPECT_GT(checked, 500);
    }
}

TEST(CasFilter, RemovesIsolatedSpikeInSparseArea) {
    // Every cell seen once (c = a = 3): the window sum 75 < G = 120, so g_c = 0.
    core::MapF h = Filled(9, 9, 0.002F);
    core::MapF c = Filled(9, 9, 3.0F);
    h.at(4, 4) = 0.5F;
    const FilterResult r = CasFilter(h, c, CasParams{});
    EXPECT_EQ(r.elevation.at(4, 4), 0.0F);
    EXPECT_EQ(ClassAt(r, 4, 4), PixelClass::kRemoved);
}

TEST(CasFilter, KeepsSameSpikeAmidWellObservedGround) {
    // Neighbours seen five times (c = 15): window sum 363 >= G, g_c = 1, Eq. 7 keeps it.
    core::MapF h = Filled(9, 9, 0.002F);
    core::MapF c = Filled(9, 9, 15.0F);
    h.at(4, 4) = 0.5F;
    c.at(4, 4) = 3.0F;
    const FilterResult r = CasFilter(h, c, CasParams{});
    EXPECT_EQ(r.elevation.at(4, 4), 0.5F);
    EXPECT_EQ(ClassAt(r, 4, 4), PixelClass::kUntouched);
}

TEST(CasFilter, FillsZeroCertaintyHoleInPlateauWithPlateauHeight) {
    core::MapF h = Filled(9, 9, kPlateau);
    core::MapF c = Filled(9, 9, 15.0F);
    h.at(4, 4) = 0.0F;
    c.at(4, 4) = 0.0F;
    h.at(4, 5) = 0.0F;  // a two-cell hole
    c.at(4, 5) = 0.0F;
    const FilterResult r = CasFilter(h, c, CasParams{});
    EXPECT_EQ(r.elevation.at(4, 4), kPlateau);
    EXPECT_EQ(r.elevation.at(4, 5), kPlateau);
    EXPECT_EQ(ClassAt(r, 4, 4), PixelClass::kFilled);
}

TEST(CasFilter, OneCellPoleLineSurvives) {
    for (const float floor_c : {3.0F, 15.0F}) {  // sparse and well-observed surroundings
        core::MapF h = Filled(11, 11, 0.001F);
        core::MapF c = Filled(11, 11, floor_c);
        for (int i = 3; i <= 7; ++i) {
            h.at(i, 5) = 0.914F;
            c.at(i, 5) = 24.0F;
        }
        const FilterResult r = CasFilter(h, c, CasParams{});
        for (int i = 3; i <= 7; ++i) {
            EXPECT_EQ(r.elevation.at(i, 5), 0.914F) << "floor c " << floor_c << " row " << i;
            EXPECT_EQ(ClassAt(r, i, 5), PixelClass::kUntouched);
        }
    }
}

TEST(CasFilter, BorderIsUnprocessed) {
    core::MapF h = Filled(8, 8, 0.0F);
    core::MapF c = Filled(8, 8, 0.0F);
    h.at(0, 0) = 0.7F;  // would be removed if processed
    h.at(1, 6) = 0.7F;
    const FilterResult r = CasFilter(h, c, CasParams{});
    EXPECT_EQ(r.elevation.at(0, 0), 0.7F);
    EXPECT_EQ(r.elevation.at(1, 6), 0.7F);
    EXPECT_EQ(ClassAt(r, 1, 6), PixelClass::kBorder);
    EXPECT_EQ(ClassAt(r, 2, 2), PixelClass::kRemoved);  // never observed, empty window
    EXPECT_EQ(ClassAt(r, 2, 5), PixelClass::kRemoved);
    EXPECT_EQ(ClassAt(r, 2, 6), PixelClass::kBorder);
}

TEST(CasFilter, WeightedMedianFollowsFig5Skeleton) {
    // Hole at the centre (h = 0), its four neighbours low (0.5), 8 of the 20 outer/diagonal
    // cells low, 12 high (1.0). Plain 5x5 median: 13 of 25 low -> 0.5. Fig. 5 skeleton:
    // 1 + 4 + 2*8 = 21 of 45 low -> the 23rd sample is high -> 1.0.
    core::MapF h = Filled(5, 5, 1.0F);
    core::MapF c = Filled(5, 5, 15.0F);
    h.at(2, 2) = 0.0F;
    c.at(2, 2) = 0.0F;
    for (const auto& [i, j] : std::vector<std::pair<int, int>>{{1, 2}, {3, 2}, {2, 1}, {2, 3}}) {
        h.at(i, j) = 0.5F;
    }
    int low = 0;
    for (int i = 0; i < 5 && low < 8; ++i) {
        for (int j = 0; j < 5 && low < 8; ++j) {
            if (std::abs(i - 2) + std::abs(j - 2) > 1) {
                h.at(i, j) = 0.5F;
                ++low;
            }
        }
    }
    const FilterResult r = CasFilter(h, c, CasParams{});
    EXPECT_EQ(ClassAt(r, 2, 2), PixelClass::kFilled);
    EXPECT_EQ(r.elevation.at(2, 2), 1.0F);
    BaselineParams plain;
    plain.center_weight = 1;
    EXPECT_EQ(CwmFilter(h, plain).at(2, 2), 0.5F);
}

TEST(CasFilter, FilledPixelsAreThe23rdOfTheFig5Samples) {
    // Random maps with many holes: every filled pixel (fast 8-lane network path) must equal
    // the 23rd of its 45 skeleton samples sorted by brute force.
    const unsigned seed = 2026;
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> u(0.0F, 1.0F);
    core::MapF h(30, 37);
    core::MapF c(30, 37);
    for (std::size_t i = 0; i < h.data.size(); ++i) {
        const bool hole = u(rng) < 0.3F;
        c.data[i] = hole ? 0.0F : 15.0F;
        h.data[i] = hole ? 0.0F : std::round(u(rng) * 8.0F) / 8.0F;  // ties on purpose
    }
    const FilterResult r = CasFilter(h, c, CasParams{});
    int filled = 0;
    for (int i = 2; i < h.rows - 2; ++i) {
        for (int j = 2; j < h.cols - 2; ++j) {
            if (ClassAt(r, i, j) != PixelClass::kFilled) {
                continue;
            }
            std::vector<float> s;
            for (int di = -2; di <= 2; ++di) {
                for (int dj = -2; dj <= 2; ++dj) {
                    const int copies = std::abs(di) + std::abs(dj) <= 1 ? 1 : 2;
                    s.insert(s.end(), static_cast<std::size_t>(copies), h.at(i + di, j + dj));
                }
            }
            ASSERT_EQ(s.size(), 45U);
            std::sort(s.begin(), s.end());
            ASSERT_EQ(r.elevation.at(i, j), s[22]) << "seed " << seed << " at " << i << "," << j;
            ++filled;
        }
    }
    EXPECT_GT(filled, 100);
}

TEST(CasFilter, WmEmptySkipLeavesEmptyCellsOut) {
    // The centre and 11 weight-2 cells are empty (h = 0, c = 0): 1 + 2 * 11 = 23 of the 45
    // samples are 0, so the literal skeleton's 23rd sample is 0, while skipping empty cells
    // leaves plateau samples only. The sum of H-bar is 13 >= 7: g_s = 1, filled either way.
    core::MapF h = Filled(5, 5, kPlateau);
    core::MapF c = Filled(5, 5, 15.0F);
    int empty = 0;
    for (int i = 0; i < 5; ++i) {
        for (int j = 0; j < 5; ++j) {
            if (std::abs(i - 2) + std::abs(j - 2) > 1 && empty < 11) {
                h.at(i, j) = 0.0F;
                c.at(i, j) = 0.0F;
                ++empty;
            }
        }
    }
    h.at(2, 2) = 0.0F;
    c.at(2, 2) = 0.0F;
    CasParams include;
    CasParams skip;
    skip.wm_empty = WmEmpty::kSkip;
    EXPECT_EQ(CasFilter(h, c, include).elevation.at(2, 2), 0.0F);
    EXPECT_EQ(CasFilter(h, c, skip).elevation.at(2, 2), kPlateau);
}

TEST(CasFilter, VarianceFormFlagsEdgesNotSpikes) {
    // Eq. 9 taken literally: next to an edge the window's H-bar variance is ~0.24 > B, so the
    // variance form flags it discontinuous while the sum form (sum of H-bar = 10 >= 7) does not.
    core::MapF h = Filled(9, 9, 0.0F);
    const core::MapF c = Filled(9, 9, 3.0F);
    for (int i = 0; i < 9; ++i) {
        for (int j = 0; j < 4; ++j) {
            h.at(i, j) = 0.4F;
        }
    }
    CasParams variance;
    variance.gs_mode = GsMode::kVariance;
    // Centre (4, 4) on the low side of the edge: H-bar sum = 10 >= 7 -> sum form keeps it.
    h.at(4, 4) = 0.01F;
    EXPECT_EQ(ClassAt(CasFilter(h, c, CasParams{}), 4, 4), PixelClass::kUntouched);
    EXPECT_EQ(ClassAt(CasFilter(h, c, variance), 4, 4), PixelClass::kRemoved);
}

TEST(CasFilter, ETermRemovesSpikeAmidUnevenCertainty) {
    core::MapF h = Filled(9, 9, 0.002F);
    core::MapF c = Filled(9, 9, 3.0F);
    for (int i = 0; i < 9; ++i) {
        for (int j = 0; j < 4; ++j) {
            c.at(i, j) = 60.0F;  // half the window well observed: sum >= G, C-bar variance high
        }
    }
    h.at(4, 4) = 0.5F;
    CasParams with_e;
    with_e.e_term = true;
    EXPECT_EQ(CasFilter(h, c, CasParams{}).elevation.at(4, 4), 0.5F);
    EXPECT_EQ(CasFilter(h, c, with_e).elevation.at(4, 4), 0.0F);
}

TEST(CasFilter, GlobalNormalisationRemovesLowBoxTopsInSparseArea) {
    // A tall pole elsewhere makes every normalised height in a low, sparsely seen area small.
    core::MapF h = Filled(12, 12, 0.1F);
    core::MapF c = Filled(12, 12, 3.0F);
    h.at(10, 10) = 1.0F;
    c.at(10, 10) = 30.0F;
    CasParams global;
    global.normalise = Normalise::kGlobal;
    EXPECT_EQ(ClassAt(CasFilter(h, c, CasParams{}), 4, 4), PixelClass::kUntouched);
    EXPECT_EQ(ClassAt(CasFilter(h, c, global), 4, 4), PixelClass::kRemoved);
}

TEST(CasFilter, OtherWindowSizesFollowTheSameRules) {
    for (const int k : {1, 3}) {
        const int n = 4 * k + 3;
        core::MapF h = Filled(n, n, 0.002F);
        core::MapF c = Filled(n, n, 3.0F);
        const int mid = n / 2;
        h.at(mid, mid) = 0.5F;          // spike in a sparse area
        h.at(mid + k, mid + k) = 0.0F;  // a never-observed cell next to it
        c.at(mid + k, mid + k) = 0.0F;
        CasParams p;
        p.k = k;
        p.G = 1000.0;  // any window is "sparse"
        const FilterResult r = CasFilter(h, c, p);
        EXPECT_EQ(r.elevation.at(mid, mid), 0.0F) << "k " << k;
        EXPECT_EQ(ClassAt(r, mid, mid), PixelClass::kRemoved) << "k " << k;
        EXPECT_EQ(ClassAt(r, k - 1, mid), PixelClass::kBorder) << "k " << k;
        EXPECT_EQ(ClassAt(r, k, k), PixelClass::kUntouched) << "k " << k;
    }
}

TEST(CasFilter, RejectsMismatchedSizes) {
    EXPECT_THROW((void)CasFilter(Filled(5, 5, 0.0F), Filled(5, 6, 0.0F), CasParams{}), InputError);
}

}  // namespace
}  // namespace casmap::mapper
