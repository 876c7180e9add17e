#include "casmap/core/lms200.hpp"

#include <gtest/gtest.h>

namespace casmap::core {
namespace {

TEST(Lms200Format, SpecialCodesMatchTheTelegramListing) {
    const Lms200Format f8{RangeMode::k8m, RangeUnits::kMillimetre};
    EXPECT_EQ(f8.CodeFor(BeamStatus::kNoReturn), 8191);
    EXPECT_EQ(f8.CodeFor(BeamStatus::kDazzle), 8190);
    EXPECT_EQ(f8.CodeFor(BeamStatus::kOverflow), 8189);
    EXPECT_EQ(f8.CodeFor(BeamStatus::kLowSignal), 8187);
    EXPECT_EQ(f8.CodeFor(BeamStatus::kReadError), 8186);
    EXPECT_EQ(f8.CodeFor(BeamStatus::kOutOfRange), 8183);
    const Lms200Format f16{RangeMode::k16m, RangeUnits::kMillimetre};
    EXPECT_EQ(f16.CodeFor(BeamStatus::kNoReturn), 16383);
    EXPECT_EQ(f16.CodeFor(BeamStatus::kOutOfRange), 16375);
    const Lms200Format f32{RangeMode::k32m, RangeUnits::kMillimetre};
    EXPECT_EQ(f32.CodeFor(BeamStatus::kOutOfRange), 32759);
}

TEST(Lms200Format, EncodeDecodeRoundTripsToTheUnit) {
    const Lms200Format mm{RangeMode::k8m, RangeUnits::kMillimetre};
    EXPECT_EQ(mm.EncodeRange(1.2344), 1234);
    EXPECT_FLOAT_EQ(mm.Decode(1234).range_m, 1.234F);
    EXPECT_EQ(mm.Decode(1234).status, BeamStatus::kOk);
    const Lms200Format cm{RangeMode::k8m, RangeUnits::kCentimetre};
    EXPECT_EQ(cm.EncodeRange(12.345), 1235);
    EXPECT_NEAR(cm.MaxRangeM(), 81.82, 1e-9);
}

TEST(Lms200Format, BeyondMaximumGetsTheOutOfRangeCode) {
    const Lms200Format mm{RangeMode::k8m, RangeUnits::kMillimetre};
    EXPECT_EQ(mm.EncodeRange(9.0), 8183);
    EXPECT_EQ(mm.Decode(8183).status, BeamStatus::kOutOfRange);
    EXPECT_EQ(mm.Decode(8191).status, BeamStatus::kNoReturn);
    EXPECT_EQ(mm.Decode(8187).status, BeamStatus::kLowSignal);
}

TEST(Lms200Format, FlagBitsAboveTheValueAreIgnored) {
    const Lms200Format mm{RangeMode::k8m, RangeUnits::kMillimetre};
    const Beam beam = mm.Decode(static_cast<std::uint16_t>(0x2000 | 1500));
    EXPECT_EQ(beam.status, BeamStatus::kOk);
    EXPECT_FLOAT_EQ(beam.range_m, 1.5F);
}

}  // namespace
}  // namespace casmap::core
