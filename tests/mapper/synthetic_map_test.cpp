#include "casmap/mapper/synthetic_map.hpp"

#include <gtest/gtest.h>

#include "casmap/mapper/filters.hpp"
#include "casmap/mapper/metrics.hpp"

namespace casmap::mapper {
namespace {

TEST(SyntheticMap, SameSeedSameBytesOtherSeedOtherMap) {
    SyntheticMapConfig cfg;
    const SyntheticMap a = BuildSyntheticMap(cfg);
    const SyntheticMap b = BuildSyntheticMap(cfg);
    EXPECT_EQ(a.elevation.data, b.elevation.data);
    EXPECT_EQ(a.certainty.data, b.certainty.data);
    EXPECT_EQ(a.truth.data, b.truth.data);
    cfg.seed = 2;
    EXPECT_NE(BuildSyntheticMap(cfg).elevation.data, a.elevation.data);
    EXPECT_EQ(BuildSyntheticMap(cfg).truth.data, a.truth.data);  // truth does not depend on it
}

TEST(SyntheticMap, HasPolesHolesAndMixedPixels) {
    const SyntheticMap m = BuildSyntheticMap(SyntheticMapConfig{});
    int poles = 0;
    int holes_on_objects = 0;
    int phantoms = 0;
    for (std::size_t i = 0; i < m.truth.data.size(); ++i) {
        poles += m.truth.data[i] == 0.914F ? 1 : 0;
        holes_on_objects += (m.truth.data[i] > 0.1F && m.certainty.data[i] == 0.0F) ? 1 : 0;
        phantoms += (m.truth.data[i] == 0.0F && m.elevation.data[i] > 0.05F) ? 1 : 0;
    }
    EXPECT_EQ(poles, 9);
    EXPECT_GT(holes_on_objects, 50);
    EXPECT_GT(phantoms, 50);
}

TEST(SyntheticMap, CasImprovesOnRawAndKeepsEveryPole) {
    const SyntheticMap m = BuildSyntheticMap(SyntheticMapConfig{});
    const FilterResult cas = RunFilter(FilterMethod::kCas, m.elevation, m.certainty, {});
    const FilterMetrics metrics =
        EvaluateFilter(cas, m.elevation, m.truth, PaperRegion(m.truth.rows, m.truth.cols));
    EXPECT_LT(metrics.pi, 1.0);
    EXPECT_LT(metrics.spikes, metrics.raw_spikes);
    for (std::size_t i = 0; i < m.truth.data.size(); ++i) {
        if (m.truth.data[i] == 0.914F) {
            EXPECT_GT(cas.elevation.data[i], 0.9F) << "pole at " << i;
        }
    }
}

}  // namespace
}  // namespace casmap::mapper
