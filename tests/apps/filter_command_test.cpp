// `casmap filter`: runs the built binary on float TIFFs made here, checks the outputs and the
// bad-input contract (exit 2, one line naming the file or parameter and the rule, no output).
#include <gtest/gtest.h>
#include <sys/wait.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <string>

#include "casmap/io/image.hpp"
#include "tests/apps/cli_runner.hpp"
#include "tests/temp_dir.hpp"

namespace casmap {
namespace {
namespace fs = std::filesystem;

using test::Casmap;
using test::Result;

int Lines(const std::string& s) {
    int n = 0;
    for (const char ch : s) {
        n += ch == '\n' ? 1 : 0;
    }
    return n;
}

class FilterCommand : public ::testing::Test {
protected:
    void SetUp() override {
        // A 20 x 24 map: floor at 2 mm seen 5 times (c = 15), a box top at 0.4 m, a sparsely
        // seen corner (c = 3) holding a spike, and a hole in the box top.
        h_ = core::MapF(20, 24, 0.002F);
        c_ = core::MapF(20, 24, 15.0F);
        for (int i = 4; i < 12; ++i) {
            for (int j = 4; j < 12; ++j) {
                h_.at(i, j) = 0.4F;
            }
        }
        h_.at(7, 7) = 0.0F;
        c_.at(7, 7) = 0.0F;
        for (int i = 12; i < 20; ++i) {
            for (int j = 14; j < 24; ++j) {
                c_.at(i, j) = 3.0F;
            }
        }
        h_.at(16, 19) = 0.7F;  // spike in the sparse corner
        io::WriteMapTiff(dir_ / "h.tiff", h_);
        io::WriteMapTiff(dir_ / "c.tiff", c_);
    }
    std::string P(const std::string& name) const { return (dir_ / name).string(); }
    void ExpectBadInput(const std::string& args, const std::string& needle) {
        const Result r = Casmap("filter " + args + " --out " + P("out.tiff"));
        EXPECT_EQ(r.code, 2) << r.output;
        EXPECT_EQ(Lines(r.output), 1) << r.output;
        EXPECT_NE(r.output.find(needle), std::string::npos) << r.output;
        EXPECT_FALSE(fs::exists(dir_ / "out.tiff"));
        EXPECT_FALSE(fs::exists(dir_ / "out.png"));
    }
    const casmap::test::TempDir tmp_{"filter_cmd"};
    const fs::path dir_ = tmp_.Path();
    core::MapF h_;
    core::MapF c_;
};

TEST_F(FilterCommand, CasRemovesSpikeFillsHoleKeepsTheRest) {
    const Result r = Casmap("filter --method cas --elevation " + P("h.tiff") + " --certainty " +
                            P("c.tiff") + " --out " + P("out.tiff") + " --threads 1");
    ASSERT_EQ(r.code, 0) << r.output;
    const core::MapF out = io::ReadMapTiff(dir_ / "out.tiff");
    EXPECT_EQ(out.at(16, 19), 0.0F);  // removed
    EXPECT_EQ(out.at(7, 7), 0.4F);    // filled with the box height
    for (int i = 0; i < out.rows; ++i) {
        for (int j = 0; j < out.cols; ++j) {
            if (c_.at(i, j) > 12.0F) {  // above A = 12: bit-identical
                ASSERT_EQ(out.at(i, j), h_.at(i, j)) << i << "," << j;
            }
        }
    }
    const core::MapF classes = io::ReadMapTiff(dir_ / "out_classes.tiff");
    EXPECT_EQ(classes.at(16, 19), 1.0F);
    EXPECT_EQ(classes.at(7, 7), 2.0F);
    EXPECT_EQ(classes.at(0, 0), 3.0F);
    EXPECT_EQ(classes.at(5, 5), 0.0F);
    EXPECT_TRUE(fs::exists(dir_ / "out.png"));
    EXPECT_TRUE(fs::exists(dir_ / "out_classes.png"));
}

TEST_F(FilterCommand, MedianEqualsOpenCvAndThreadsChangeNothing) {
    ASSERT_EQ(Casmap("filter --method median --elevation " + P("h.tiff") + " --out " +
                     P("m1.tiff") + " --threads 1")
                  .code,
              0);
    ASSERT_EQ(Casmap("filter --method median --elevation " + P("h.tiff") + " --out " +
                     P("m2.tiff") + " --threads 2")
                  .code,
              0);
    const core::MapF a = io::ReadMapTiff(dir_ / "m1.tiff");
    const core::MapF b = io::ReadMapTiff(dir_ / "m2.tiff");
    EXPECT_EQ(a.data, b.data);
    cv::Mat ref;
    cv::medianBlur(cv::Mat(h_.rows, h_.cols, CV_32F, h_.data.data()), ref, 5);
    for (int i = 0; i < a.rows; ++i) {
        for (int j = 0; j < a.cols; ++j) {
            ASSERT_EQ(a.at(i, j), ref.at<float>(i, j));
        }
    }
}

TEST_F(FilterCommand, SetChangesParameters) {
    // With the window sum threshold G = 0, g_c is never 0: the spike survives.
    const Result r = Casmap("filter --method cas --elevation " + P("h.tiff") + " --certainty " +
                            P("c.tiff") + " --set G=0 --set A=12 --out " + P("out.tiff"));
    ASSERT_EQ(r.code, 0) << r.output;
    EXPECT_EQ(io::ReadMapTiff(dir_ / "out.tiff").at(16, 19), 0.7F);
}

TEST_F(FilterCommand, PresetAppliesThePipelinesSectionOfTheMethod) {
    // config/presets/cas_hybrid.yaml gives cas_hybrid its values in `pipelines:`; the filter
    // command applies that section for --method cas_hybrid, so the output equals the one with
    // the same values given by --set (and differs from the defaults' on this map).
    const std::string maps = "--elevation " + P("h.tiff") + " --certainty " + P("c.tiff");
    ASSERT_EQ(Casmap("filter --method cas_hybrid " + maps + " --preset cas_hybrid --out " +
                     P("preset.tiff"))
                  .code,
              0);
    ASSERT_EQ(Casmap("filter --method cas_hybrid " + maps +
                     " --set A=25 --set h_sum_min=9 --set support_min=5 --set support_tol_m=0.13"
                     " --set edge_min=9 --set edge_tol_m=0.1 --set surface_tol_m=0.015"
                     " --set surface_min=7 --set surface_prior=0.75 --set median_mix=0.125"
                     " --set edge_fill=0.5 --set edge_fill_run=1 --set edge_spill_c=9"
                     " --set edge_spill_drop_m=0.01 --set edge_spill=0.5 --out " +
                     P("set.tiff"))
                  .code,
              0);
    const Result plain =
        Casmap("filter --method cas_hybrid " + maps + " --out " + P("default.tiff"));
    ASSERT_EQ(plain.code, 0);
    // The stats line names the method (it said "cas:" for every CAS method).
    EXPECT_EQ(plain.output.rfind("cas_hybrid (cas_trail's classes): A = 12, G = 120; of ", 0), 0U)
        << plain.output;
    const core::MapF preset = io::ReadMapTiff(dir_ / "preset.tiff");
    EXPECT_EQ(preset.data, io::ReadMapTiff(dir_ / "set.tiff").data);
    EXPECT_NE(preset.data, io::ReadMapTiff(dir_ / "default.tiff").data);
}

TEST_F(FilterCommand, RejectsMissingFile) {
    ExpectBadInput("--method median --elevation " + P("missing.tiff"), "missing.tiff");
}

TEST_F(FilterCommand, RejectsEightBitTiff) {
    cv::imwrite(P("u8.tiff"), cv::Mat(20, 24, CV_8U, cv::Scalar(3)));
    ExpectBadInput("--method median --elevation " + P("u8.tiff"), "8-bit");
}

TEST_F(FilterCommand, RejectsMultiChannelTiff) {
    cv::imwrite(P("rgb.tiff"), cv::Mat(20, 24, CV_32FC3, cv::Scalar(1, 2, 3)));
    ExpectBadInput("--method median --elevation " + P("rgb.tiff"), "channels = 3");
}

TEST_F(FilterCommand, RejectsSizeMismatch) {
    io::WriteMapTiff(dir_ / "small.tiff", core::MapF(10, 24, 3.0F));
    ExpectBadInput("--method cas --elevation " + P("h.tiff") + " --certainty " + P("small.tiff"),
                   "small.tiff: shape = 10x24");
}

TEST_F(FilterCommand, RejectsUnknownSetName) {
    ExpectBadInput("--method cas --elevation " + P("h.tiff") + " --certainty " + P("c.tiff") +
                       " --set bogus=3",
                   "bogus");
}

TEST_F(FilterCommand, RejectsOutOfRangeValue) {
    ExpectBadInput("--method cwm --elevation " + P("h.tiff") + " --set center_weight=4",
                   "center_weight = 4");
    ExpectBadInput(
        "--method cas --elevation " + P("h.tiff") + " --certainty " + P("c.tiff") + " --set k=9",
        "k = 9");
}

TEST_F(FilterCommand, RejectsUnknownMethodAndMissingCertainty) {
    ExpectBadInput("--method gauss --elevation " + P("h.tiff"), "--method = gauss");
    ExpectBadInput("--method cas --elevation " + P("h.tiff"), "--certainty");
}

TEST_F(FilterCommand, BadInputLeavesExistingOutputAlone) {
    {
        std::ofstream old(dir_ / "keep.tiff");
        old << "previous";
    }
    const Result r = Casmap("filter --method median --elevation " + P("h.tiff") +
                            " --set window=4 --out " + P("keep.tiff"));
    EXPECT_EQ(r.code, 2);
    std::ifstream in(dir_ / "keep.tiff");
    std::string content;
    in >> content;
    EXPECT_EQ(content, "previous");
    const Result missing_dir = Casmap("filter --method median --elevation " + P("h.tiff") +
                                      " --out " + P("nodir/out.tiff"));
    EXPECT_EQ(missing_dir.code, 2) << missing_dir.output;
    EXPECT_NE(missing_dir.output.find("does not exist"), std::string::npos);
}

TEST(DemoCommand, PrintsThePiTableForAllFiveFilters) {
    const Result r = Casmap("demo --seed 3");
    ASSERT_EQ(r.code, 0) << r.output;
    for (const char* name : {"cas", "wiener", "average", "median", "cwm", "(raw)"}) {
        EXPECT_NE(r.output.find(std::string("\n") + name + " "), std::string::npos) << name;
    }
    EXPECT_EQ(Casmap("demo --seed 3 --threads 1").output, r.output);  // thread-independent
}

}  // namespace
}  // namespace casmap
