// The wave-2 CAS variants on synthetic maps: cas_terrain on a slope and on a terrace,
// cas_trail on a pole with a mixed-pixel trail.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <cstring>

#include "casmap/mapper/filters.hpp"
#include "synthetic_maps.hpp"

namespace casmap::mapper {
namespace {

using test_maps::Noise;

// A sparsely observed surface (every cell one hit, c = 3 < A = 12, window sums below G): the
// regime where Eq. 7 removes what looks discontinuous.
struct Surface {
    core::MapF truth, h, c;
};

template <typename F>
Surface MakeSurface(int rows, int cols, F height) {
    Surface s{core::MapF(rows, cols), core::MapF(rows, cols), core::MapF(rows, cols, 3.0F)};
    for (int i = 0; i < rows; ++i) {
        for (int j = 0; j < cols; ++j) {
            s.truth.at(i, j) = height(i, j);
            s.h.at(i, j) = s.truth.at(i, j) + Noise(i, j);
        }
    }
    return s;
}

double MaxInteriorError(const core::MapF& out, const core::MapF& truth, int k) {
    double worst = 0.0;
    for (int i = k; i < truth.rows - k; ++i) {
        for (int j = k; j < truth.cols - k; ++j) {
            worst = std::max(worst, std::abs(static_cast<double>(out.at(i, j) - truth.at(i, j))));
        }
    }
    return worst;
}

TEST(CasTerrain, RemovesASpikeOnASlopeThatThePapersFormKeeps) {
    // 1 cm rise per 25 mm cell (22 deg), crossing 0 m at row 30; a 0.3 m spike at row 45.
    Surface s =
        MakeSurface(80, 40, [](int i, int) { return -0.3F + 0.01F * static_cast<float>(i); });
    s.h.at(45, 20) += 0.3F;
    FilterParams params;
    const FilterResult paper = RunFilter(FilterMethod::kCas, s.h, s.c, params);
    EXPECT_EQ(paper.elevation.at(45, 20), s.h.at(45, 20));  // |h| around it is large: "continuous"
    const FilterResult terrain = RunFilter(FilterMethod::kCasTerrain, s.h, s.c, params);
    EXPECT_EQ(terrain.classes.at(45, 20), static_cast<std::uint8_t>(PixelClass::kRemoved));
    EXPECT_NEAR(terrain.elevation.at(45, 20), s.truth.at(45, 20), 0.015);
    // Nowhere does the variant pull the slope towards 0 m.
    EXPECT_LT(MaxInteriorError(terrain.elevation, s.truth, 2), 0.015);
}

TEST(CasTerrain, KeepsATerraceAndRemovesASpikeOnIt) {
    // Terrace at 0.5 m, a 0.2 m step up at row 40, a 0.3 m spike on the lower level.
    Surface s = MakeSurface(80, 40, [](int i, int) { return i < 40 ? 0.5F : 0.7F; });
    s.h.at(30, 20) += 0.3F;
    FilterParams params;
    const FilterResult paper = RunFilter(FilterMethod::kCas, s.h, s.c, params);
    EXPECT_EQ(paper.elevation.at(30, 20), s.h.at(30, 20));
    const FilterResult terrain = RunFilter(FilterMethod::kCasTerrain, s.h, s.c, params);
    EXPECT_NEAR(terrain.elevation.at(30, 20), 0.5, 0.01);
    EXPECT_LT(MaxInteriorError(terrain.elevation, s.truth, 2), 0.01);  // the step edge survives
}

TEST(CasTerrain, FlatFloorBehavesAsThePapersForm) {
    Surface s = MakeSurface(60, 40, [](int, int) { return 0.0F; });
    s.h.at(30, 20) = 0.4F;  // spike on the floor
    FilterParams params;
    const FilterResult paper = RunFilter(FilterMethod::kCas, s.h, s.c, params);
    const FilterResult terrain = RunFilter(FilterMethod::kCasTerrain, s.h, s.c, params);
    EXPECT_EQ(paper.elevation.at(30, 20), 0.0F);
    EXPECT_NEAR(terrain.elevation.at(30, 20), 0.0, 0.003);
    EXPECT_LT(MaxInteriorError(terrain.elevation, s.truth, 2), 0.003);
}

// A well-observed floor (c = 36), a 0.914 m pole seen 8 times (c = 24) and behind it a
// mixed-pixel trail of one-hit cells (c = 3) with heights falling from the pole's to the floor.
struct PoleScene {
    core::MapF h = core::MapF(40, 40, 0.0F);
    core::MapF c = core::MapF(40, 40, 36.0F);
};

PoleScene PoleWithTrail() {
    PoleScene p;
    for (int i = 0; i < 40; ++i) {
        for (int j = 0; j < 40; ++j) {
            p.h.at(i, j) = Noise(i, j);
        }
    }
    p.h.at(15, 20) = 0.914F;
    p.c.at(15, 20) = 24.0F;
    const float trail[] = {0.72F, 0.55F, 0.41F, 0.3F, 0.17F};
    for (int n = 0; n < 5; ++n) {
        p.h.at(16 + n, 20) = trail[n];
        p.c.at(16 + n, 20) = 3.0F;
    }
    return p;
}

TEST(CasTrail, RemovesTheTrailAndKeepsThePole) {
    const PoleScene p = PoleWithTrail();
    FilterParams params;
    const FilterResult paper = RunFilter(FilterMethod::kCas, p.h, p.c, params);
    for (int n = 0; n < 5; ++n) {
        EXPECT_EQ(paper.elevation.at(16 + n, 20), p.h.at(16 + n, 20)) << n;  // Eq. 10: g_c = 1
    }
    const FilterResult trail = RunFilter(FilterMethod::kCasTrail, p.h, p.c, params);
    EXPECT_EQ(trail.elevation.at(15, 20), 0.914F);  // the pole, bit for bit
    for (int n = 0; n < 5; ++n) {
        EXPECT_EQ(trail.classes.at(16 + n, 20), static_cast<std::uint8_t>(PixelClass::kRemoved));
        EXPECT_EQ(trail.elevation.at(16 + n, 20), 0.0F) << n;
    }
    // Everything else as the paper's filter left it.
    int differ = 0;
    for (std::size_t n = 0; n < p.h.data.size(); ++n) {
        differ += std::memcmp(&paper.elevation.data[n], &trail.elevation.data[n], 4) != 0 ? 1 : 0;
    }
    EXPECT_EQ(differ, 5);
}

TEST(CasTrail, KeepsALowCertaintyCellOnTheFloor) {
    PoleScene p = PoleWithTrail();
    p.c.at(30, 10) = 3.0F;  // seen once, but at the floor's height among trusted floor cells
    const FilterResult trail = RunFilter(FilterMethod::kCasTrail, p.h, p.c, FilterParams{});
    EXPECT_EQ(trail.classes.at(30, 10), static_cast<std::uint8_t>(PixelClass::kUntouched));
    EXPECT_EQ(trail.elevation.at(30, 10), p.h.at(30, 10));
}

}  // namespace
}  // namespace casmap::mapper
