// pipeline::RunDemo / WriteDemoMaps (what `casmap demo` runs): five filters scored on the
// synthetic map, independent of the thread count; the maps written as TIFF + PNG.
#include "casmap/pipeline/demo.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <string>

#include "casmap/core/input_error.hpp"
#include "casmap/io/image.hpp"
#include "tests/temp_dir.hpp"

namespace casmap::pipeline {
namespace {
namespace fs = std::filesystem;

TEST(Demo, ScoresFiveFiltersTheSameAtAnyThreadCount) {
    const DemoResult one = RunDemo({}, 1);
    const DemoResult two = RunDemo({}, 2);
    ASSERT_EQ(one.methods.size(), 5U);
    ASSERT_EQ(one.metrics.size(), 5U);
    EXPECT_EQ(one.methods[0], mapper::FilterMethod::kCas);
    for (std::size_t m = 0; m < one.metrics.size(); ++m) {
        EXPECT_EQ(one.metrics[m].pi, two.metrics[m].pi) << m;
        EXPECT_EQ(one.results[m].elevation.data, two.results[m].elevation.data) << m;
    }
    EXPECT_LT(one.metrics[0].pi, 1.0);  // CAS improves on the raw map (Eq. 11: raw = 1)
    EXPECT_GT(one.cas_classes.all.cells, 0);
    EXPECT_EQ(one.region.rows, 200);
}

TEST(Demo, TheSeedAndTheIncrementShapeTheMap) {
    DemoOptions other;
    other.seed = 2;
    EXPECT_NE(RunDemo({}, 1).map.elevation.data, RunDemo(other, 1).map.elevation.data);
    DemoOptions bad;
    bad.params.cas.k = 0;
    try {
        (void)RunDemo(bad, 1);
        ADD_FAILURE() << "no InputError for k = 0";
    } catch (const InputError& e) {
        EXPECT_EQ(e.field(), "k");
        EXPECT_EQ(e.where(), "filter parameters");
    }
}

TEST(Demo, WritesEveryMapBesideTheClasses) {
    const casmap::test::TempDir tmp("pipeline_demo");
    const fs::path dir = tmp / "maps";
    const DemoResult r = RunDemo({}, 0);
    WriteDemoMaps(r, dir);
    for (const char* stem : {"elevation", "certainty", "truth", "filtered_cas", "filtered_cwm"}) {
        EXPECT_TRUE(fs::exists(dir / (std::string(stem) + ".tiff"))) << stem;
        EXPECT_TRUE(fs::exists(dir / (std::string(stem) + ".png"))) << stem;
    }
    EXPECT_TRUE(fs::exists(dir / "cas_classes.png"));
    EXPECT_EQ(io::ReadMapTiff(dir / "filtered_cas.tiff").data, r.results[0].elevation.data);
}

}  // namespace
}  // namespace casmap::pipeline
