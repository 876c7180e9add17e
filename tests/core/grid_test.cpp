#include "casmap/core/grid.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "casmap/core/input_error.hpp"

namespace casmap::core {
namespace {

TEST(GridGeometry, CellsAreHalfOpen) {
    const GridGeometry g{1.0, -1.0, 0.025, 200, 80};
    EXPECT_EQ(g.CellOf(1.0, -1.0), (Cell{0, 0}));
    EXPECT_EQ(g.CellOf(1.0251, -0.9749), (Cell{1, 1}));
    EXPECT_EQ(g.CellOf(1.0249, -0.9751), (Cell{0, 0}));
    EXPECT_FALSE(g.CellOf(0.9999, 0.0).has_value());
    EXPECT_FALSE(g.CellOf(1.0 + 200 * 0.025, 0.0).has_value());
    EXPECT_FALSE(g.CellOf(std::nan(""), 0.0).has_value());
    EXPECT_NEAR(g.CellCenterX(0), 1.0125, 1e-12);
}

TEST(GridGeometry, ValidateRejectsEmptyGrid) {
    EXPECT_THROW((GridGeometry{0, 0, 0.025, 0, 10}.Validate()), InputError);
    EXPECT_THROW((GridGeometry{0, 0, -1.0, 10, 10}.Validate()), InputError);
    EXPECT_NO_THROW((GridGeometry{0, 0, 0.025, 10, 10}.Validate()));
}

TEST(Raster, RowMajorLayout) {
    Raster<float> r(2, 3, 0.0F);
    r.at(1, 2) = 5.0F;
    EXPECT_EQ(r.data[5], 5.0F);
}

}  // namespace
}  // namespace casmap::core
