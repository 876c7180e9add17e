// Scan pre-filters: a pole in front of a wall with one veiling point between them.
#include "casmap/mapper/scan_filters.hpp"

#include <gtest/gtest.h>

#include <numbers>

#include "casmap/core/input_error.hpp"

namespace casmap::mapper {
namespace {

constexpr double kDeg = std::numbers::pi / 180.0;

// A wall 3 m away on every beam, a pole at 1.5 m on beams 88-90, a mixed pixel at 2.2 m on
// beam 91 (between the pole and the wall), one beam without return.
core::Scan PoleScan() {
    core::Scan s;
    s.start_angle_rad = -90 * kDeg;
    s.angle_step_rad = kDeg;
    s.beam_period_s = (1.0 / 75.0) / 360.0;
    s.beams.assign(181, core::Beam{3.0F, core::BeamStatus::kOk, 0});
    for (std::size_t i = 88; i <= 90; ++i) {
        s.beams[i].range_m = 1.5F;
    }
    s.beams[91].range_m = 2.2F;
    s.beams[20].status = core::BeamStatus::kNoReturn;
    return s;
}

TEST(ScanFilters, ShadowFilterRejectsTheVeilingPointAndKeepsThePole) {
    const std::vector<std::uint8_t> keep = ShadowFilterLabels(PoleScan(), {});
    EXPECT_EQ(keep[91], 0);  // veiling point
    for (std::size_t i = 88; i <= 90; ++i) {
        EXPECT_EQ(keep[i], 1) << i;  // the pole
    }
    EXPECT_EQ(keep[50], 1);  // plain wall
    EXPECT_EQ(keep[20], 1);  // no return: left to the mapper
}

TEST(ScanFilters, RangeJumpRejectsOnlyTheReturnBetweenTwoDepths) {
    const std::vector<std::uint8_t> keep = RangeJumpLabels(PoleScan(), {});
    EXPECT_EQ(keep[91], 0);
    int rejected = 0;
    for (const std::uint8_t k : keep) {
        rejected += k == 0 ? 1 : 0;
    }
    EXPECT_EQ(rejected, 1);
    RangeJumpConfig strict;
    strict.jump_min_m = 2.0;  // the pole-to-wall gap is 1.5 m: no edge this large
    strict.margin_m = 0.03;
    EXPECT_EQ(RangeJumpLabels(PoleScan(), strict)[91], 1);
}

TEST(ScanFilters, RemovalScoreCountsAgainstTruthLabels) {
    const core::Scan scan = PoleScan();
    std::vector<core::BeamLabel> labels(scan.beams.size(), core::BeamLabel::kValid);
    labels[91] = core::BeamLabel::kMixed;
    labels[100] = core::BeamLabel::kMixed;  // missed by both filters
    RemovalScore score;
    score.Add(scan, RangeJumpLabels(scan, {}), labels);
    EXPECT_EQ(score.true_pos, 1);
    EXPECT_EQ(score.false_pos, 0);
    EXPECT_EQ(score.false_neg, 1);
    EXPECT_DOUBLE_EQ(score.Precision(), 1.0);
    EXPECT_DOUBLE_EQ(score.Recall(), 0.5);
    EXPECT_THROW(score.Add(scan, std::vector<std::uint8_t>(3, 1), labels), InputError);
}

TEST(ScanFilters, InvalidSettingsNameTheField) {
    ShadowFilterConfig s;
    s.min_angle_deg = 95.0;
    try {
        (void)ShadowFilterLabels(PoleScan(), s);
        FAIL() << "accepted min_angle_deg = 95";
    } catch (const InputError& e) {
        EXPECT_NE(std::string(e.what()).find("shadow.min_angle_deg"), std::string::npos);
    }
    RangeJumpConfig r;
    r.margin_m = 0.1;  // >= jump_min_m / 2
    EXPECT_THROW((void)RangeJumpLabels(PoleScan(), r), InputError);
}

}  // namespace
}  // namespace casmap::mapper
