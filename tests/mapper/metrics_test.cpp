#include "casmap/mapper/metrics.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "casmap/core/input_error.hpp"

namespace casmap::mapper {
namespace {

TEST(Metrics, PerformanceIndexHandComputed) {
    core::MapF truth(2, 2, 0.0F);
    core::MapF raw(2, 2, 0.0F);
    core::MapF filtered(2, 2, 0.0F);
    raw.at(0, 0) = 1.0F;  // raw errors: 1^2 + 2^2 = 5
    raw.at(1, 1) = 2.0F;
    filtered.at(0, 1) = 0.5F;  // filtered errors: 0.25 + 1 = 1.25
    filtered.at(1, 1) = 1.0F;
    EXPECT_DOUBLE_EQ(PerformanceIndex(filtered, raw, truth, FullRegion(2, 2)), 0.25);
    EXPECT_DOUBLE_EQ(PerformanceIndex(raw, raw, truth, FullRegion(2, 2)), 1.0);
    // Region = the top row only: raw 1, filtered 0.25.
    EXPECT_DOUBLE_EQ(PerformanceIndex(filtered, raw, truth, Region{0, 0, 1, 2}), 0.25);
    EXPECT_TRUE(std::isnan(PerformanceIndex(filtered, truth, truth, FullRegion(2, 2))));
    EXPECT_DOUBLE_EQ(Rmse(filtered, truth, FullRegion(2, 2)), std::sqrt(1.25 / 4));
    EXPECT_THROW((void)PerformanceIndex(filtered, raw, truth, Region{1, 1, 2, 2}), InputError);
}

TEST(Metrics, PaperRegionIs200By80Centred) {
    const Region r = PaperRegion(240, 200);
    EXPECT_EQ(r.rows, 200);
    EXPECT_EQ(r.cols, 80);
    EXPECT_EQ(r.row0, 20);
    EXPECT_EQ(r.col0, 60);
    const Region small = PaperRegion(50, 40);
    EXPECT_EQ(small.rows, 50);
    EXPECT_EQ(small.cols, 40);
}

TEST(Metrics, ClassPercentagesWithAndWithoutNeverObservedCells) {
    ClassMap classes(1, 5);
    core::MapF certainty(1, 5, 6.0F);
    classes.data = {static_cast<std::uint8_t>(PixelClass::kBorder),
                    static_cast<std::uint8_t>(PixelClass::kRemoved),
                    static_cast<std::uint8_t>(PixelClass::kRemoved),
                    static_cast<std::uint8_t>(PixelClass::kFilled),
                    static_cast<std::uint8_t>(PixelClass::kUntouched)};
    certainty.data[2] = 0.0F;  // a never-observed cell taking the removal branch
    certainty.data[3] = 0.0F;  // filled cells always have c = 0
    const ClassReport r = ClassPercentages(classes, certainty);
    EXPECT_EQ(r.all.cells, 4);
    EXPECT_DOUBLE_EQ(r.all.removed_pct, 50.0);
    EXPECT_DOUBLE_EQ(r.all.filled_pct, 25.0);
    EXPECT_DOUBLE_EQ(r.all.untouched_pct, 25.0);
    EXPECT_EQ(r.observed.cells, 3);
    EXPECT_NEAR(r.observed.removed_pct, 100.0 / 3, 1e-12);
}

TEST(Metrics, SpikeIsAPhantomAboveEveryNearbyTruth) {
    core::MapF truth(7, 7, 0.0F);
    truth.at(3, 3) = 0.9F;  // a pole
    core::MapF map = truth;
    map.at(3, 4) = 0.9F;   // the pole one cell off: not a spike (radius 1)
    map.at(0, 0) = 0.3F;   // phantom on open floor: a spike
    map.at(6, 6) = 0.04F;  // below the 5 cm threshold
    EXPECT_EQ(CountSpikes(map, truth, FullRegion(7, 7)), 1);
    EXPECT_EQ(CountSpikes(map, truth, FullRegion(7, 7), SpikeRule{0.01, 0}), 3);
}

TEST(Metrics, EvaluateFilterReportsFilledAndEdgeErrors) {
    core::MapF truth(5, 5, 0.0F);
    truth.at(2, 2) = 0.4F;
    FilterResult r;
    r.elevation = truth;
    r.elevation.at(2, 2) = 0.3F;
    r.classes = ClassMap(5, 5, static_cast<std::uint8_t>(PixelClass::kUntouched));
    r.classes.at(2, 2) = static_cast<std::uint8_t>(PixelClass::kFilled);
    core::MapF raw(5, 5, 0.0F);
    const FilterMetrics m = EvaluateFilter(r, raw, truth, FullRegion(5, 5));
    EXPECT_EQ(m.filled_cells, 1);
    EXPECT_NEAR(m.filled_rmse_m, 0.1, 1e-6);
    EXPECT_NEAR(m.pi, 0.01 / 0.16, 1e-6);
    // Edge cells: the box cell and its 4 neighbours; only the box cell is off by 0.1.
    EXPECT_NEAR(m.edge_rmse_m, std::sqrt(0.01 / 5), 1e-6);
    EXPECT_EQ(m.edge_cells, 5);
    // Open cells: the other 20, all exact; an error there shows in open_rmse_m only.
    EXPECT_EQ(m.open_cells, 20);
    EXPECT_EQ(m.open_rmse_m, 0.0);
    r.elevation.at(0, 0) = 0.2F;
    const FilterMetrics m2 = EvaluateFilter(r, raw, truth, FullRegion(5, 5));
    EXPECT_NEAR(m2.open_rmse_m, std::sqrt(0.04 / 20), 1e-6);
    EXPECT_NEAR(m2.edge_rmse_m, m.edge_rmse_m, 1e-12);
    EXPECT_EQ(m.spikes, 0);
}

TEST(Metrics, EdgeAndOpenCellsLeaveOutUnknownCells) {
    core::MapF truth(5, 5, 0.0F);
    truth.at(2, 2) = 0.4F;
    core::MapF raw(5, 5, 0.0F);
    raw.at(2, 3) = std::nanf("");  // an edge cell the raw map never saw
    raw.at(0, 0) = std::nanf("");  // an open cell the raw map never saw
    FilterResult r;
    r.elevation = raw;
    const FilterMetrics m = EvaluateFilter(r, raw, truth, FullRegion(5, 5));
    EXPECT_EQ(m.edge_cells, 4);
    EXPECT_EQ(m.open_cells, 19);
    EXPECT_EQ(m.cells, 23);
}

}  // namespace
}  // namespace casmap::mapper
