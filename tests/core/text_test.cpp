#include "casmap/core/text.hpp"

#include <gtest/gtest.h>

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

}  // namespace
}  // namespace casmap::core
