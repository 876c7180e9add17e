// pipeline::WriteTruthFiles (what `casmap truth` runs): the map equals sim's ground truth, the
// TIFF and PNG appear together; bad options name their field and write nothing.
#include "casmap/pipeline/truth_file.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "casmap/core/input_error.hpp"
#include "casmap/io/image.hpp"
#include "casmap/io/scene_file.hpp"
#include "tests/temp_dir.hpp"

namespace casmap::pipeline {
namespace {
namespace fs = std::filesystem;

class TruthFile : public ::testing::Test {
protected:
    void SetUp() override {
        std::ofstream(dir_ / "scene.yaml") << "objects:\n"
                                              "  - name: block\n"
                                              "    box: {size_m: [0.4, 0.4, 0.3]}\n"
                                              "    pose: {xyz_m: [0.5, 0.5, 0.15]}\n";
        options_.scene = (dir_ / "scene.yaml").string();
        options_.grid = core::GridGeometry{0.0, 0.0, 0.1, 10, 10};
        options_.out = (dir_ / "t.tiff").string();
        options_.png = (dir_ / "t.png").string();
    }
    // One folder per test and per run (ctest may run tests and whole suites side by side).
    const casmap::test::TempDir tmp_{"pipeline_truth_file"};
    const fs::path dir_ = tmp_.Path();
    TruthFileOptions options_;
};

TEST_F(TruthFile, WritesTheGroundTruthAsTiffAndPng) {
    const TruthFileResult r = WriteTruthFiles(options_, 1);
    const core::MapF expected =
        sim::GroundTruthElevation(io::LoadScene(options_.scene), options_.grid, options_.truth, 1);
    EXPECT_EQ(r.map.data, expected.data);
    EXPECT_EQ(io::ReadMapTiff(options_.out).data, expected.data);
    EXPECT_TRUE(fs::exists(options_.png));
    EXPECT_FLOAT_EQ(r.min_m, 0.0F);
    EXPECT_NEAR(r.max_m, 0.3F, 1e-6F);
}

TEST_F(TruthFile, BadOptionsNameTheirFieldAndWriteNothing) {
    const auto field_of = [](const TruthFileOptions& o) {
        try {
            (void)WriteTruthFiles(o, 1);
        } catch (const InputError& e) {
            return e.field();
        }
        return std::string("(no error)");
    };
    TruthFileOptions o = options_;
    o.out = (dir_ / "t.png").string();
    EXPECT_EQ(field_of(o), "out");
    o = options_;
    o.png = (dir_ / "t.jpg").string();
    EXPECT_EQ(field_of(o), "png");
    o = options_;
    o.png = (dir_ / "missing" / "t.png").string();
    EXPECT_EQ(field_of(o), "png");
    o = options_;
    o.grid.cell_m = 0.0;
    EXPECT_EQ(field_of(o), "cell_m");
    EXPECT_FALSE(fs::exists(dir_ / "missing"));
    EXPECT_FALSE(fs::exists(options_.out));
}

}  // namespace
}  // namespace casmap::pipeline
