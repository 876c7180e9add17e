#pragma once

#include <cmath>
#include <cstddef>
#include <optional>
#include <vector>

namespace casmap::core {

struct Cell {
    int row = 0;  // along-track, world x
    int col = 0;  // across-track, world y
    bool operator==(const Cell&) const = default;
};

/// Map grid (DESIGN.md): cell (row, col) covers world x in [x0 + row*s, x0 + (row+1)*s) and
/// y in [y0 + col*s, y0 + (col+1)*s). Rows run along-track (the paper's N), cols across (M).
struct GridGeometry {
    double x0_m = 0.0;
    double y0_m = 0.0;
    double cell_m = 0.025;  // the paper's 25 mm cells
    int rows = 0;
    int cols = 0;

    [[nodiscard]] std::optional<Cell> CellOf(double x_m, double y_m) const {
        const double r = std::floor((x_m - x0_m) / cell_m);
        const double c = std::floor((y_m - y0_m) / cell_m);
        if (!(r >= 0.0 && c >= 0.0 && r < rows && c < cols)) {
            return std::nullopt;  // also rejects NaN
        }
        return Cell{static_cast<int>(r), static_cast<int>(c)};
    }
    [[nodiscard]] double CellCenterX(int row) const { return x0_m + (row + 0.5) * cell_m; }
    [[nodiscard]] double CellCenterY(int col) const { return y0_m + (col + 0.5) * cell_m; }
    [[nodiscard]] std::size_t size() const {
        return static_cast<std::size_t>(rows) * static_cast<std::size_t>(cols);
    }
    void Validate() const;  // throws InputError: rows, cols > 0, cell_m > 0, all finite
    bool operator==(const GridGeometry&) const = default;
};

/// A row-major raster of T over a grid; the map layers (elevation, certainty, truth).
template <typename T>
struct Raster {
    int rows = 0;
    int cols = 0;
    std::vector<T> data;

    Raster() = default;
    Raster(int rows_, int cols_, T fill = T{})
        : rows(rows_),
          cols(cols_),
          data(static_cast<std::size_t>(rows_) * static_cast<std::size_t>(cols_), fill) {}

    [[nodiscard]] T& at(int r, int c) {
        return data[static_cast<std::size_t>(r) * static_cast<std::size_t>(cols) +
                    static_cast<std::size_t>(c)];
    }
    [[nodiscard]] const T& at(int r, int c) const {
        return data[static_cast<std::size_t>(r) * static_cast<std::size_t>(cols) +
                    static_cast<std::size_t>(c)];
    }
    [[nodiscard]] bool SameShape(const Raster& o) const { return rows == o.rows && cols == o.cols; }
};

using MapF = Raster<float>;

}  // namespace casmap::core
