// Unknown cells as NaN (grid_map convention): the mapper, CAS, the baselines and the metrics.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <limits>

#include "casmap/mapper/filters.hpp"
#include "casmap/mapper/metrics.hpp"
#include "casmap/mapper/synthetic_map.hpp"
#include "casmap/mapper/terrain_mapper.hpp"

namespace casmap::mapper {
namespace {

constexpr float kNaN = std::numeric_limits<float>::quiet_NaN();

TEST(NanMaps, MapperLeavesUnseenCellsNaNAndTakesTheFirstHeight) {
    TerrainMapperConfig cfg;
    cfg.grid = core::GridGeometry{0.0, 0.0, 0.025, 4, 4};
    cfg.unknown = Unknown::kNaN;
    TerrainMapper m(cfg);
    EXPECT_TRUE(std::isnan(m.elevation().at(1, 1)));
    ASSERT_TRUE(m.AddPoint(Eigen::Vector3d(0.03, 0.03, -0.02), 0.01));  // below the datum
    EXPECT_FLOAT_EQ(m.elevation().at(1, 1), -0.02F);
    EXPECT_EQ(m.certainty().at(1, 1), 3.0F);
    ASSERT_TRUE(m.AddPoint(Eigen::Vector3d(0.03, 0.03, -0.05), 0.01));  // Eq. 6: larger |z|
    EXPECT_FLOAT_EQ(m.elevation().at(1, 1), -0.05F);
    ASSERT_TRUE(m.AddPoint(Eigen::Vector3d(0.06, 0.06, 0.0), 0.01));  // a first hit at 0 m
    EXPECT_EQ(m.elevation().at(2, 2), 0.0F);
    EXPECT_TRUE(std::isnan(m.elevation().at(0, 3)));
}

// The synthetic pair with NaN where c = 0.
struct NanPair {
    core::MapF h, c, truth;
};
NanPair SyntheticNaN() {
    const SyntheticMap m = BuildSyntheticMap({});
    NanPair p{m.elevation, m.certainty, m.truth};
    for (std::size_t n = 0; n < p.h.data.size(); ++n) {
        if (p.c.data[n] == 0.0F) {
            p.h.data[n] = kNaN;
        }
    }
    return p;
}

TEST(NanMaps, CasRemovesToNaNAndMatchesTheZeroFormElsewhere) {
    const NanPair p = SyntheticNaN();
    const SyntheticMap z = BuildSyntheticMap({});
    FilterParams zero_params;
    zero_params.cas.wm_empty = WmEmpty::kSkip;  // the NaN form never puts unknowns in a median
    FilterParams nan_params = zero_params;
    nan_params.Set("unknown", "nan");
    const FilterResult a = RunFilter(FilterMethod::kCas, z.elevation, z.certainty, zero_params);
    const FilterResult b = RunFilter(FilterMethod::kCas, p.h, p.c, nan_params);
    EXPECT_EQ(a.classes.data, b.classes.data);
    int removed = 0;
    for (std::size_t n = 0; n < p.h.data.size(); ++n) {
        const auto cls = static_cast<PixelClass>(b.classes.data[n]);
        if (cls == PixelClass::kRemoved) {
            EXPECT_TRUE(std::isnan(b.elevation.data[n])) << n;
            ++removed;
        } else if (cls == PixelClass::kFilled) {
            EXPECT_FALSE(std::isnan(b.elevation.data[n])) << n;
            EXPECT_EQ(b.elevation.data[n], a.elevation.data[n]) << n;
        } else if (p.c.data[n] == 0.0F) {
            EXPECT_TRUE(std::isnan(b.elevation.data[n])) << n;  // unknown stays unknown
        } else {
            EXPECT_EQ(std::memcmp(&b.elevation.data[n], &p.h.data[n], 4), 0) << n;
        }
    }
    EXPECT_GT(removed, 0);
}

TEST(NanMaps, BaselinesUseOnlyKnownCells) {
    core::MapF h(5, 5, kNaN);
    h.at(2, 2) = 1.0F;
    h.at(2, 1) = 3.0F;
    h.at(1, 2) = 2.0F;
    BaselineParams p;
    p.unknown = Unknown::kNaN;
    p.window = 3;
    const core::MapF med = MedianFilter(h, p);
    EXPECT_FLOAT_EQ(med.at(2, 2), 2.0F);    // median of {1, 2, 3}
    EXPECT_FLOAT_EQ(med.at(2, 1), 2.0F);    // {1, 2, 3} around (2, 1) too
    EXPECT_TRUE(std::isnan(med.at(0, 0)));  // unknown stays unknown
    EXPECT_FLOAT_EQ(AverageFilter(h, p).at(2, 2), 2.0F);
    p.center_weight = 3;
    EXPECT_FLOAT_EQ(CwmFilter(h, p).at(2, 2), 1.0F);  // {1, 1, 1, 2, 3}
    const core::MapF w = WienerFilter(h, p);
    EXPECT_FALSE(std::isnan(w.at(2, 2)));
    EXPECT_TRUE(std::isnan(w.at(4, 4)));
}

TEST(NanMaps, MetricsScoreJointlyKnownCellsAndReportCoverage) {
    core::MapF truth(2, 2, 0.0F);
    core::MapF raw(2, 2, 0.1F);
    raw.at(0, 0) = kNaN;  // never observed
    FilterResult f{core::MapF(2, 2, 0.05F), {}};
    f.elevation.at(1, 1) = kNaN;  // the filter removed a known cell
    const Region all = FullRegion(2, 2);
    EXPECT_NEAR(Rmse(raw, truth, all), 0.1, 1e-7);  // over the 3 known cells
    EXPECT_NEAR(PerformanceIndex(f.elevation, raw, truth, all), 0.25, 1e-6);  // 2 cells
    const FilterMetrics m = EvaluateFilter(f, raw, truth, all);
    EXPECT_EQ(m.cells, 2);
    EXPECT_NEAR(m.coverage, 2.0 / 3.0, 1e-12);
    EXPECT_NEAR(m.rmse_m, 0.05, 1e-7);
    EXPECT_NEAR(m.raw_rmse_m, 0.1, 1e-7);
    EXPECT_EQ(CountSpikes(raw, truth, all, SpikeRule{0.05, 0}), 3);  // NaN is no spike
}

TEST(NanMaps, ZeroMapsScoreEveryCell) {
    const SyntheticMap z = BuildSyntheticMap({});
    const FilterResult r = RunFilter(FilterMethod::kCas, z.elevation, z.certainty, FilterParams{});
    const Region region = PaperRegion(z.truth.rows, z.truth.cols);
    const FilterMetrics m = EvaluateFilter(r, z.elevation, z.truth, region);
    EXPECT_EQ(m.cells, static_cast<std::int64_t>(region.rows) * region.cols);
    EXPECT_EQ(m.coverage, 1.0);
}

}  // namespace
}  // namespace casmap::mapper
