#include "casmap/rig/profile.hpp"

#include <gtest/gtest.h>

#include <numbers>

#include "casmap/core/input_error.hpp"

namespace casmap::rig {
namespace {

constexpr double kDeg = std::numbers::pi / 180.0;

TEST(Profile, SinusoidStartsAtCentreWithPeakRate) {
    const AngleProfile p{ProfileShape::kSinusoid, 10.0, 5.0, 2.0, 0.0};
    EXPECT_NEAR(EvaluateProfile(p, 0.0).value_rad, 10.0 * kDeg, 1e-12);
    EXPECT_NEAR(EvaluateProfile(p, 0.0).rate_rad_s, 5.0 * kDeg * std::numbers::pi, 1e-12);
    EXPECT_NEAR(EvaluateProfile(p, 0.5).value_rad, 15.0 * kDeg, 1e-12);
    EXPECT_NEAR(PeakRateDegS(p), 5.0 * std::numbers::pi, 1e-12);
}

TEST(Profile, TriangleHasConstantRateBetweenExtremes) {
    const AngleProfile p{ProfileShape::kTriangle, 0.0, 10.0, 4.0, 0.0};
    EXPECT_NEAR(EvaluateProfile(p, 1.0).value_rad, 10.0 * kDeg, 1e-12);
    EXPECT_NEAR(EvaluateProfile(p, 2.0).value_rad, 0.0, 1e-12);
    EXPECT_NEAR(EvaluateProfile(p, 3.0).value_rad, -10.0 * kDeg, 1e-12);
    EXPECT_NEAR(EvaluateProfile(p, 0.5).rate_rad_s, 10.0 * kDeg, 1e-12);
    EXPECT_NEAR(EvaluateProfile(p, 1.5).rate_rad_s, -10.0 * kDeg, 1e-12);
    EXPECT_NEAR(PeakRateDegS(p), 10.0, 1e-12);
    EXPECT_THROW((void)ParseProfileShape("square", "x.shape"), InputError);
}

TEST(Profile, SpeedScheduleRampsCruisesAndStops) {
    const SpeedSchedule s{1.0, 0.8, 0.5, 2.0};
    EXPECT_DOUBLE_EQ(s.Duration(), 3.0);
    EXPECT_NEAR(s.Evaluate(0.5).value_rad, 1.0 + 0.2, 1e-12);
    EXPECT_NEAR(s.Evaluate(1.5).rate_rad_s, 0.8, 1e-12);
    EXPECT_NEAR(s.Evaluate(3.0).value_rad, 1.0 + 0.4 + 1.6, 1e-12);
    EXPECT_NEAR(s.Evaluate(3.0).rate_rad_s, 0.0, 1e-12);
}

}  // namespace
}  // namespace casmap::rig
