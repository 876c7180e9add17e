#include "casmap/io/image.hpp"

#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>
#include <string>

#include "casmap/core/input_error.hpp"

namespace casmap::io {
namespace {
namespace fs = std::filesystem;

class ImageTest : public ::testing::Test {
protected:
    void SetUp() override {
        dir_ = fs::temp_directory_path() /
               ("casmap_image_test_" + std::to_string(getpid()) + "_" +
                ::testing::UnitTest::GetInstance()->current_test_info()->name());
        fs::create_directories(dir_);
    }
    void TearDown() override { fs::remove_all(dir_); }
    std::string ErrorOf(const fs::path& p) {
        try {
            (void)ReadMapTiff(p);
        } catch (const InputError& e) {
            return e.what();
        }
        return "";
    }
    fs::path dir_;
};

core::MapF Sample() {
    core::MapF m(3, 4);
    for (std::size_t i = 0; i < m.data.size(); ++i) {
        m.data[i] = static_cast<float>(i) * 0.125F - 0.3F;
    }
    return m;
}

TEST_F(ImageTest, FloatTiffRoundTripIsExact) {
    core::MapF m = Sample();
    m.at(1, 2) = std::numeric_limits<float>::quiet_NaN();
    m.at(2, 3) = 1e-7F;
    const fs::path p = dir_ / "map.tiff";
    WriteMapTiff(p, m);
    const core::MapF back = ReadMapTiff(p);
    ASSERT_EQ(back.rows, 3);
    ASSERT_EQ(back.cols, 4);
    for (std::size_t i = 0; i < m.data.size(); ++i) {
        if (std::isnan(m.data[i])) {
            EXPECT_TRUE(std::isnan(back.data[i]));
        } else {
            EXPECT_EQ(back.data[i], m.data[i]) << i;
        }
    }
    // Only the final file is left: the temporary was renamed.
    int files = 0;
    for ([[maybe_unused]] const auto& e : fs::directory_iterator(dir_)) {
        ++files;
    }
    EXPECT_EQ(files, 1);
}

TEST_F(ImageTest, RejectsMissingFile) {
    const std::string e = ErrorOf(dir_ / "nope.tiff");
    EXPECT_NE(e.find("nope.tiff"), std::string::npos) << e;
    EXPECT_NE(e.find("does not exist"), std::string::npos) << e;
}

TEST_F(ImageTest, RejectsEightBitTiff) {
    const fs::path p = dir_ / "u8.tiff";
    ASSERT_TRUE(cv::imwrite(p.string(), cv::Mat(4, 5, CV_8U, cv::Scalar(7))));
    const std::string e = ErrorOf(p);
    EXPECT_NE(e.find("u8.tiff"), std::string::npos) << e;
    EXPECT_NE(e.find("8-bit"), std::string::npos) << e;
    EXPECT_NE(e.find("single-channel 32-bit float TIFF"), std::string::npos) << e;
}

TEST_F(ImageTest, RejectsMultiChannelTiff) {
    const fs::path p = dir_ / "rgb.tiff";
    ASSERT_TRUE(cv::imwrite(p.string(), cv::Mat(4, 5, CV_32FC3, cv::Scalar(1, 2, 3))));
    const std::string e = ErrorOf(p);
    EXPECT_NE(e.find("rgb.tiff"), std::string::npos) << e;
    EXPECT_NE(e.find("channels = 3"), std::string::npos) << e;
}

TEST_F(ImageTest, RejectsNonTiff) {
    const fs::path p = dir_ / "fake.tiff";
    ASSERT_TRUE(cv::imwrite((dir_ / "x.png").string(), cv::Mat(4, 5, CV_8U, cv::Scalar(7))));
    fs::rename(dir_ / "x.png", p);
    const std::string e = ErrorOf(p);
    EXPECT_NE(e.find("not a TIFF"), std::string::npos) << e;
    std::ofstream(dir_ / "empty.tiff").close();
    EXPECT_NE(ErrorOf(dir_ / "empty.tiff").find("not a TIFF"), std::string::npos);
}

TEST_F(ImageTest, WriteIntoMissingDirectoryFailsWithoutOutput) {
    EXPECT_THROW(WriteMapTiff(dir_ / "no" / "map.tiff", Sample()), InputError);
    EXPECT_FALSE(fs::exists(dir_ / "no"));
}

TEST_F(ImageTest, PngDrawsNanAndUnknownDistinctly) {
    core::MapF m(10, 10, 0.5F);
    m.at(0, 0) = std::numeric_limits<float>::quiet_NaN();
    core::Raster<std::uint8_t> unknown(10, 10, 0);
    unknown.at(9, 9) = 1;
    PngStyle style;
    style.unknown = &unknown;
    style.pixels_per_cell = 4;
    style.title = "test";
    const fs::path p = dir_ / "map.png";
    WriteMapPng(p, m, style);
    const cv::Mat img = cv::imread(p.string(), cv::IMREAD_COLOR);
    ASSERT_FALSE(img.empty());
    // The map sits at (10, 30) in the canvas, 4 px per cell.
    EXPECT_EQ(img.at<cv::Vec3b>(30 + 1, 10 + 1), cv::Vec3b(255, 0, 255));  // NaN
    EXPECT_EQ(img.at<cv::Vec3b>(30 + 9 * 4 + 1, 10 + 9 * 4 + 1), cv::Vec3b(60, 60, 60));
    const cv::Vec3b normal = img.at<cv::Vec3b>(30 + 5 * 4, 10 + 5 * 4);
    EXPECT_NE(normal, cv::Vec3b(255, 0, 255));
    EXPECT_NE(normal, cv::Vec3b(60, 60, 60));
}

TEST_F(ImageTest, ClassesPngUsesLegendColours) {
    core::Raster<std::uint8_t> classes(6, 6, 0);
    classes.at(2, 2) = 1;
    const fs::path p = dir_ / "classes.png";
    WriteClassesPng(p, classes, {{"untouched", 200, 200, 200}, {"removed", 0, 0, 255}}, "c");
    const cv::Mat img = cv::imread(p.string(), cv::IMREAD_COLOR);
    ASSERT_FALSE(img.empty());
    const int ppc = 600 / 6;
    EXPECT_EQ(img.at<cv::Vec3b>(30 + 2 * ppc + 1, 10 + 2 * ppc + 1), cv::Vec3b(0, 0, 255));
    EXPECT_EQ(img.at<cv::Vec3b>(30 + 1, 10 + 1), cv::Vec3b(200, 200, 200));
}

}  // namespace
}  // namespace casmap::io
