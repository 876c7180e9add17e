#include "casmap/core/check.hpp"

#include <gtest/gtest.h>

#include <limits>
#include <string>

#include "tests/input_error_of.hpp"

namespace casmap::core {
namespace {

using test::ErrorOf;

TEST(Check, PassingRulesThrowNothing) {
    const Check check("sensor.yaml", "lms200.");
    EXPECT_NO_THROW(check.That(true, "x", 1.0, "rule"));
    EXPECT_NO_THROW(check.Positive("x", 1e-9));
    EXPECT_NO_THROW(check.NonNegative("x", 0.0));
    EXPECT_NO_THROW(check.Finite("x", -3.0));
    EXPECT_NO_THROW(check.InRange("x", 1.0, 0.0, 1.0));
    EXPECT_NO_THROW(check.Probability("x", 0.0));
}

TEST(Check, MessageNamesWhereFieldValueAndRule) {
    const Check check("sensor.yaml", "lms200.");
    EXPECT_EQ(ErrorOf([&] { check.Positive("r10_m", -0.5); }),
              "sensor.yaml: lms200.r10_m = -0.5 (must be > 0)");
    EXPECT_EQ(ErrorOf([&] { check.InRange("p_sun", 1.25, 0.0, 1.0); }),
              "sensor.yaml: lms200.p_sun = 1.25 (allowed: 0..1)");
    EXPECT_EQ(ErrorOf([&] { check.That(false, "mode", "fast", "allowed: mm, cm"); }),
              "sensor.yaml: lms200.mode = fast (allowed: mm, cm)");
}

TEST(Check, NumbersAreWrittenByFormatNumber) {
    const Check check;  // an options struct: no where, no prefix
    EXPECT_EQ(ErrorOf([&] { check.That(false, "m", 500.0, ">= 1"); }), "m = 500 (>= 1)");
    EXPECT_EQ(ErrorOf([&] { check.NonNegative("gap_s", 0.1 - 0.3); }),
              "gap_s = -0.19999999999999998 (must be >= 0)");
}

TEST(Check, IntegersKeepAllTheirDigits) {
    const Check check("LMS 200 driver");
    EXPECT_EQ(ErrorOf([&] { check.That(false, "baud", 500000, "allowed: 9600..500000"); }),
              "LMS 200 driver: baud = 500000 (allowed: 9600..500000)");
    EXPECT_EQ(ErrorOf([&] { check.That(false, "tries", std::size_t{0}, ">= 1"); }),
              "LMS 200 driver: tries = 0 (>= 1)");
}

TEST(Check, NonFiniteValuesFailEveryNumericRule) {
    const Check check("live");
    const double nan = std::numeric_limits<double>::quiet_NaN();
    const double inf = std::numeric_limits<double>::infinity();
    EXPECT_EQ(ErrorOf([&] { check.Positive("speed_m_s", nan); }),
              "live: speed_m_s = .nan (must be > 0)");
    EXPECT_EQ(ErrorOf([&] { check.NonNegative("gap_s", inf); }),
              "live: gap_s = .inf (must be >= 0)");
    EXPECT_EQ(ErrorOf([&] { check.Finite("x0_m", -inf); }), "live: x0_m = -.inf (must be finite)");
    EXPECT_EQ(ErrorOf([&] { check.Probability("p", nan); }), "live: p = .nan (allowed: 0..1)");
}

TEST(Check, ErrorKeepsItsPartsForCallersThatRename) {
    const InputError e = Check("", "kalman.").Error("a", "0", "allowed: integer >= 1");
    EXPECT_EQ(e.field(), "kalman.a");
    EXPECT_EQ(e.value(), "0");
    EXPECT_EQ(e.rule(), "allowed: integer >= 1");
    EXPECT_EQ(std::string(e.what()), "kalman.a = 0 (allowed: integer >= 1)");
}

TEST(Check, CustomRuleReplacesTheDefaultText) {
    EXPECT_EQ(ErrorOf([] { Check("mapper").Positive("scan_period_s", 0.0, "finite and > 0"); }),
              "mapper: scan_period_s = 0 (finite and > 0)");
}

}  // namespace
}  // namespace casmap::core
