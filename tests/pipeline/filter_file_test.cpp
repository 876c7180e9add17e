// pipeline::FilterMapFiles (what `casmap filter` runs): the files written equal RunFilter's
// result; the CAS family adds the class files; errors name fields, not flags.
#include "casmap/pipeline/filter_file.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <string>

#include "casmap/core/input_error.hpp"
#include "casmap/io/image.hpp"
#include "casmap/mapper/synthetic_map.hpp"
#include "tests/input_error_of.hpp"
#include "tests/temp_dir.hpp"

namespace casmap::pipeline {
namespace {
namespace fs = std::filesystem;

class FilterFile : public ::testing::Test {
protected:
    void SetUp() override {
        mapper::SyntheticMapConfig config;
        config.rows = 60;
        config.cols = 50;
        map_ = mapper::BuildSyntheticMap(config);
        io::WriteMapTiff(dir_ / "h.tiff", map_.elevation);
        io::WriteMapTiff(dir_ / "c.tiff", map_.certainty);
    }
    FilterFileOptions Options(const std::string& method) const {
        FilterFileOptions o;
        o.method = method;
        o.elevation = (dir_ / "h.tiff").string();
        o.certainty = (dir_ / "c.tiff").string();
        o.out = (dir_ / "out.tiff").string();
        return o;
    }
    // One folder per test and per run (ctest may run tests and whole suites side by side).
    const casmap::test::TempDir tmp_{"pipeline_filter_file"};
    const fs::path dir_ = tmp_.Path();
    mapper::SyntheticMap map_;
};

std::string FieldOf(const FilterFileOptions& o) {
    return test::FieldOfError([&] { o.Validate(); });
}

TEST_F(FilterFile, CasWritesTheFilteredMapAndItsClassesAsRunFilterComputesThem) {
    const FilterFileResult r = FilterMapFiles(Options("cas"));
    const mapper::FilterResult direct = mapper::RunFilter(
        mapper::FilterMethod::kCas, map_.elevation, map_.certainty, mapper::FilterParams{});
    EXPECT_EQ(io::ReadMapTiff(dir_ / "out.tiff").data, direct.elevation.data);
    EXPECT_EQ(r.result.elevation.data, direct.elevation.data);
    const core::MapF codes = io::ReadMapTiff(dir_ / "out_classes.tiff");
    ASSERT_EQ(codes.data.size(), direct.classes.data.size());
    for (std::size_t i = 0; i < codes.data.size(); ++i) {
        ASSERT_EQ(codes.data[i], static_cast<float>(direct.classes.data[i])) << i;
    }
    ASSERT_EQ(r.written.size(), 4U);
    for (const fs::path& p : r.written) {
        EXPECT_GT(fs::file_size(p), 0U) << p;
    }
    EXPECT_EQ(r.written[3], dir_ / "out_classes.png");
    ASSERT_TRUE(r.classes.has_value());
    EXPECT_GT(r.classes->all.cells, 0);
    EXPECT_NEAR(
        r.classes->all.removed_pct + r.classes->all.filled_pct + r.classes->all.untouched_pct,
        100.0, 1e-6);
}

TEST_F(FilterFile, BaselinesWriteNoClassesAndNeedNoCertainty) {
    FilterFileOptions o = Options("median");
    o.certainty.clear();
    const FilterFileResult r = FilterMapFiles(o);
    EXPECT_FALSE(r.classes.has_value());
    EXPECT_EQ(r.written.size(), 2U);
    EXPECT_FALSE(fs::exists(dir_ / "out_classes.tiff"));
}

TEST_F(FilterFile, ErrorsNameTheFieldAndWriteNothing) {
    FilterFileOptions o = Options("kas");
    EXPECT_EQ(FieldOf(o), "method");
    o = Options("cas");
    o.out = (dir_ / "out.png").string();
    EXPECT_EQ(FieldOf(o), "out");
    o.out = (dir_ / "missing" / "out.tiff").string();
    EXPECT_EQ(FieldOf(o), "out");
    o = Options("cas");
    o.certainty.clear();
    EXPECT_EQ(FieldOf(o), "certainty");
    o = Options("cas");
    o.params.cas.k = 9;
    EXPECT_EQ(FieldOf(o), "k");
    EXPECT_FALSE(fs::exists(dir_ / "out.tiff"));
    EXPECT_EQ(BesideOutput("a/b/m.tiff", "_classes", ".png"), fs::path("a/b/m_classes.png"));
}

}  // namespace
}  // namespace casmap::pipeline
