// pipeline::RunMixedPixels (the Fig. 3 experiment behind `casmap mixed-pixels`) called directly.
#include "casmap/pipeline/mixed_pixels.hpp"

#include <gtest/gtest.h>

#include <string>

#include "casmap/core/input_error.hpp"

namespace casmap::pipeline {
namespace {

TEST(MixedPixels, ValidationNamesTheOptionsFieldNotAFlag) {
    MixedPixelsOptions o;
    o.step_m = 0.0;
    try {
        o.Validate();
        FAIL() << "no error";
    } catch (const InputError& e) {
        EXPECT_EQ(e.field(), "step_m");
        EXPECT_TRUE(e.where().empty());
        EXPECT_EQ(std::string(e.what()).find("--"), std::string::npos) << e.what();
    }
    o = MixedPixelsOptions{};
    o.to_m = 0.1;
    EXPECT_THROW(o.Validate(), InputError);
    o = MixedPixelsOptions{};
    o.readings = 0;
    EXPECT_THROW((void)RunMixedPixels(o, 1), InputError);
}

TEST(MixedPixels, SmallGapMixesWideGapSeparatesAtAnyThreadCount) {
    MixedPixelsOptions o;
    o.from_m = 0.5;
    o.to_m = 3.0;
    o.step_m = 2.5;
    o.readings = 300;
    o.seed = 3;
    std::size_t last_done = 0;
    std::size_t last_total = 0;
    const MixedPixelsResult one = RunMixedPixels(o, 1, [&](std::size_t done, std::size_t total) {
        last_done = done;
        last_total = total;
    });
    ASSERT_EQ(one.gaps.size(), 2U);
    EXPECT_EQ(last_done, 2U);
    EXPECT_EQ(last_total, 2U);
    EXPECT_DOUBLE_EQ(one.gaps[0].delta_d_m, 0.5);
    EXPECT_DOUBLE_EQ(one.gaps[1].delta_d_m, 3.0);
    EXPECT_GT(one.gaps[0].mixed, 50);  // 0.5 m: the echoes merge
    EXPECT_EQ(one.gaps[1].mixed, 0);   // 3 m: they separate
    EXPECT_LE(one.gaps[0].mixed, one.gaps[0].valid);
    const MixedPixelsResult two = RunMixedPixels(o, 2);
    EXPECT_EQ(MixedPixelsJson(o, one), MixedPixelsJson(o, two));
    EXPECT_NE(MixedPixelsJson(o, one).find("\"mixed\": ["), std::string::npos);
    EXPECT_GT(MixedPixelsPng(o, one).size(), 1000U);
}

}  // namespace
}  // namespace casmap::pipeline
