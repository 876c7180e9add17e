// CheckFilterInputs: the one set of checks `casmap filter` and `casmap.filter` make on maps.
#include "casmap/mapper/filter_inputs.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <string>

#include "casmap/core/input_error.hpp"

namespace casmap::mapper {
namespace {

std::string ErrorOf(FilterMethod method,
                    const core::MapF& h,
                    const core::MapF& c,
                    const FilterParams& params = {}) {
    try {
        CheckFilterInputs(method, h, c, params, {"h.tiff", "c.tiff"});
    } catch (const InputError& e) {
        return e.what();
    }
    return "";
}

TEST(CheckFilterInputs, AcceptsAGoodPairAndBaselinesWithoutCertainty) {
    const core::MapF h(4, 5, 0.25F);
    const core::MapF c(4, 5, 3.0F);
    EXPECT_EQ(ErrorOf(FilterMethod::kCas, h, c), "");
    EXPECT_EQ(ErrorOf(FilterMethod::kMedian, h, core::MapF()), "");
}

TEST(CheckFilterInputs, EveryCasMethodNeedsCertainty) {
    const core::MapF h(4, 5, 0.0F);
    for (const FilterMethod m :
         {FilterMethod::kCas, FilterMethod::kCasTerrain, FilterMethod::kCasTrail}) {
        EXPECT_EQ(ErrorOf(m, h, core::MapF()),
                  "certainty (required for method " + std::string(ToString(m)) + ")");
    }
}

TEST(CheckFilterInputs, ShapeMustMatch) {
    EXPECT_EQ(ErrorOf(FilterMethod::kCas, core::MapF(20, 24, 0.0F), core::MapF(10, 24, 1.0F)),
              "c.tiff: shape = 10x24 (must equal the elevation map's 20x24 (h.tiff))");
}

TEST(CheckFilterInputs, NamesTheFirstBadPixel) {
    core::MapF h(4, 5, 0.0F);
    core::MapF c(4, 5, 1.0F);
    c.at(3, 4) = -3.0F;
    EXPECT_EQ(ErrorOf(FilterMethod::kCas, h, c),
              "c.tiff: pixel (row 3, col 4) = -3 (must be finite and >= 0)");
    c.at(3, 4) = std::numeric_limits<float>::quiet_NaN();
    EXPECT_NE(ErrorOf(FilterMethod::kCas, h, c).find("c.tiff: pixel (row 3, col 4) = .nan"),
              std::string::npos);
    c.at(3, 4) = 1.0F;
    h.at(0, 3) = std::numeric_limits<float>::quiet_NaN();
    EXPECT_EQ(ErrorOf(FilterMethod::kWiener, h, core::MapF()),
              "h.tiff: pixel (row 0, col 3) = .nan (must be finite (NaN, an unknown cell, needs "
              "the filter parameter unknown=nan))");
}

TEST(CheckFilterInputs, NanElevationOnlyWithUnknownNan) {
    core::MapF h(4, 5, 0.0F);
    const core::MapF c(4, 5, 1.0F);
    h.at(1, 1) = std::numeric_limits<float>::quiet_NaN();
    FilterParams nan_unknown;
    nan_unknown.SetAssignment("unknown=nan");
    EXPECT_EQ(ErrorOf(FilterMethod::kCas, h, c, nan_unknown), "");
    h.at(2, 2) = std::numeric_limits<float>::infinity();
    EXPECT_EQ(ErrorOf(FilterMethod::kCas, h, c, nan_unknown),
              "h.tiff: pixel (row 2, col 2) = .inf (must be finite or NaN)");
}

}  // namespace
}  // namespace casmap::mapper
