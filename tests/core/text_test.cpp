#include "casmap/core/text.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <string>

namespace casmap::core {
namespace {

TEST(SplitList, KeepsInnerEmptyItemsAndDropsATrailingSeparator) {
    EXPECT_EQ(SplitList("a,b,c"), (std::vector<std::string>{"a", "b", "c"}));
    EXPECT_EQ(SplitList("a,,b"), (std::vector<std::string>{"a", "", "b"}));
    EXPECT_EQ(SplitList("a,b,"), (std::vector<std::string>{"a", "b"}));
    EXPECT_EQ(SplitList(",a"), (std::vector<std::string>{"", "a"}));
    EXPECT_TRUE(SplitList("").empty());
    EXPECT_EQ(SplitList("1-3;7", ';'), (std::vector<std::string>{"1-3", "7"}));
}

TEST(ParseFiniteDouble, WholeStringFiniteOnly) {
    EXPECT_EQ(ParseFiniteDouble("0.025"), 0.025);
    EXPECT_EQ(ParseFiniteDouble("-1e-3"), -1e-3);
    EXPECT_FALSE(ParseFiniteDouble("").has_value());
    EXPECT_FALSE(ParseFiniteDouble("1.5x").has_value());
    EXPECT_FALSE(ParseFiniteDouble(" 1").has_value());
    EXPECT_FALSE(ParseFiniteDouble("nan").has_value());
    EXPECT_FALSE(ParseFiniteDouble("inf").has_value());
}

TEST(ParseWholeInt, RejectsFractionsAndEmpty) {
    EXPECT_EQ(ParseWholeInt("16"), 16);
    EXPECT_FALSE(ParseWholeInt("1.0").has_value());
    EXPECT_FALSE(ParseWholeInt("").has_value());
}

TEST(ParseNumberList, ExactCountNoTrailingComma) {
    EXPECT_EQ(ParseNumberList("1,2.5,-3", 3), (std::vector<double>{1.0, 2.5, -3.0}));
    EXPECT_FALSE(ParseNumberList("1,2", 3).has_value());
    EXPECT_FALSE(ParseNumberList("1,2,3,", 3).has_value());
    EXPECT_FALSE(ParseNumberList("1,,3", 3).has_value());
    EXPECT_FALSE(ParseNumberList("1,x,3", 3).has_value());
}

TEST(FormatNumber, ShortestRoundTripAndYamlSpecials) {
    EXPECT_EQ(FormatNumber(0.1), "0.1");
    EXPECT_EQ(FormatNumber(1.0), "1");
    EXPECT_EQ(FormatNumber(-2.5), "-2.5");
    EXPECT_EQ(FormatNumber(1000.0), "1000");
    EXPECT_EQ(FormatNumber(1e-5), "1e-05");
    EXPECT_EQ(FormatNumber(0.1 + 0.2), "0.30000000000000004");
    EXPECT_EQ(FormatNumber(-0.0), "0");
    EXPECT_EQ(FormatNumber(std::nan("")), ".nan");
    EXPECT_EQ(FormatNumber(std::numeric_limits<double>::infinity()), ".inf");
    EXPECT_EQ(FormatNumber(-std::numeric_limits<double>::infinity()), "-.inf");
    for (const double v :
         {0.025, 1.0 / 3.0, 6.02214076e23, -2.2250738585072014e-308, 1e300, 40.0}) {
        EXPECT_EQ(std::stod(FormatNumber(v)), v) << FormatNumber(v);
    }
}

}  // namespace
}  // namespace casmap::core

namespace casmap::core {
namespace {

TEST(FormatNumber, SignificantDigitsForLabels) {
    EXPECT_EQ(FormatNumber(1234.5, 3), "1230");  // %.3g said "1.23e+03"
    EXPECT_EQ(FormatNumber(0.012345, 3), "0.0123");
    EXPECT_EQ(FormatNumber(-0.5, 3), "-0.5");
    EXPECT_EQ(FormatNumber(0.30000000000000004, 3), "0.3");
    EXPECT_EQ(FormatNumber(2.0, 1), "2");
    EXPECT_EQ(FormatNumber(0.0, 3), "0");
    EXPECT_EQ(FormatNumber(std::nan(""), 3), ".nan");
}

}  // namespace
}  // namespace casmap::core
