#include "casmap/mapper/obstacle_map.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "casmap/core/input_error.hpp"
#include "casmap/core/text.hpp"

namespace casmap::mapper {
namespace {

std::int64_t FloorDiv(std::int64_t a, std::int64_t b) {
    const std::int64_t q = a / b;
    return (a % b != 0 && (a < 0) != (b < 0)) ? q - 1 : q;
}

}  // namespace

ObstacleMap::ObstacleMap(double cell_m, double x0_m, double y0_m)
    : cell_m_(cell_m), x0_m_(x0_m), y0_m_(y0_m) {
    if (!(std::isfinite(cell_m) && cell_m > 0.0)) {
        throw MakeInputError("obstacle map", "cell_m", core::FormatNumber(cell_m),
                             "must be finite and > 0");
    }
    if (!(std::isfinite(x0_m) && std::isfinite(y0_m))) {
        throw MakeInputError("obstacle map", "origin", core::FormatNumber(x0_m), "must be finite");
    }
}

std::int64_t ObstacleMap::Key(std::int64_t ti, std::int64_t tj) {
    return (ti << 32) ^ (tj & 0xFFFFFFFFLL);
}

ObstacleMap::Tile& ObstacleMap::TileAt(std::int64_t ti, std::int64_t tj) {
    const std::int64_t key = Key(ti, tj);
    if (last_tile_ != nullptr && key == last_key_) {
        return *last_tile_;
    }
    std::unique_ptr<Tile>& slot = tiles_[key];
    if (!slot) {
        slot = std::make_unique<Tile>();
        std::fill(std::begin(slot->h), std::end(slot->h), 0.0F);
        std::fill(std::begin(slot->c), std::end(slot->c), 0.0F);
        std::fill(std::begin(slot->n), std::end(slot->n), std::uint16_t{0});
    }
    last_key_ = key;
    last_tile_ = slot.get();
    return *slot;
}

const ObstacleMap::Tile* ObstacleMap::FindTile(std::int64_t ti, std::int64_t tj) const {
    const auto it = tiles_.find(Key(ti, tj));
    return it == tiles_.end() ? nullptr : it->second.get();
}

void ObstacleMap::Register(double x_m, double y_m, float h_m, float c) {
    const double fi = std::floor((x_m - x0_m_) / cell_m_);
    const double fj = std::floor((y_m - y0_m_) / cell_m_);
    if (!(std::abs(fi) < 1e9 && std::abs(fj) < 1e9)) {
        return;  // NaN or absurdly far: not a place on this map
    }
    const auto i = static_cast<std::int64_t>(fi);
    const auto j = static_cast<std::int64_t>(fj);
    const std::int64_t ti = FloorDiv(i, kTile);
    const std::int64_t tj = FloorDiv(j, kTile);
    Tile& tile = TileAt(ti, tj);
    const auto idx = static_cast<std::size_t>((i - ti * kTile) * kTile + (j - tj * kTile));
    float& h = tile.h[idx];
    float& cc = tile.c[idx];
    std::uint16_t& n = tile.n[idx];
    if (n == 0 || h_m > h || (h_m == h && c > cc)) {
        h = h_m;
        cc = c;
    }
    if (n < std::numeric_limits<std::uint16_t>::max()) {
        ++n;
    }
    if (registered_ == 0) {
        i0_ = i1_ = i;
        j0_ = j1_ = j;
    } else {
        i0_ = std::min(i0_, i);
        i1_ = std::max(i1_, i);
        j0_ = std::min(j0_, j);
        j1_ = std::max(j1_, j);
    }
    ++registered_;
}

core::GridGeometry ObstacleMap::Bounds() const {
    core::GridGeometry g;
    g.cell_m = cell_m_;
    g.x0_m = x0_m_ + static_cast<double>(i0_) * cell_m_;
    g.y0_m = y0_m_ + static_cast<double>(j0_) * cell_m_;
    g.rows = registered_ == 0 ? 0 : static_cast<int>(i1_ - i0_ + 1);
    g.cols = registered_ == 0 ? 0 : static_cast<int>(j1_ - j0_ + 1);
    return g;
}

ObstacleRaster ObstacleMap::ToRaster() const {
    if (registered_ == 0) {
        ObstacleRaster r;
        r.grid = Bounds();
        return r;
    }
    return ToRaster(Bounds());
}

ObstacleRaster ObstacleMap::ToRaster(const core::GridGeometry& grid) const {
    ObstacleRaster r;
    r.grid = grid;
    r.elevation = core::MapF(grid.rows, grid.cols, 0.0F);
    r.certainty = core::MapF(grid.rows, grid.cols, 0.0F);
    r.count = core::Raster<std::uint16_t>(grid.rows, grid.cols, 0);
    const auto i0 = static_cast<std::int64_t>(std::llround((grid.x0_m - x0_m_) / cell_m_));
    const auto j0 = static_cast<std::int64_t>(std::llround((grid.y0_m - y0_m_) / cell_m_));
    // Tile by tile: one hash lookup per tile the grid overlaps.
    for (std::int64_t ti = FloorDiv(i0, kTile); ti <= FloorDiv(i0 + grid.rows - 1, kTile); ++ti) {
        for (std::int64_t tj = FloorDiv(j0, kTile); tj <= FloorDiv(j0 + grid.cols - 1, kTile);
             ++tj) {
            const Tile* t = FindTile(ti, tj);
            if (t == nullptr) {
                continue;
            }
            const std::int64_t a_lo = std::max<std::int64_t>(ti * kTile, i0);
            const std::int64_t a_hi = std::min<std::int64_t>(ti * kTile + kTile, i0 + grid.rows);
            const std::int64_t b_lo = std::max<std::int64_t>(tj * kTile, j0);
            const std::int64_t b_hi = std::min<std::int64_t>(tj * kTile + kTile, j0 + grid.cols);
            for (std::int64_t i = a_lo; i < a_hi; ++i) {
                for (std::int64_t j = b_lo; j < b_hi; ++j) {
                    const auto idx =
                        static_cast<std::size_t>((i - ti * kTile) * kTile + (j - tj * kTile));
                    const auto row = static_cast<int>(i - i0);
                    const auto col = static_cast<int>(j - j0);
                    r.elevation.at(row, col) = t->h[idx];
                    r.certainty.at(row, col) = t->c[idx];
                    r.count.at(row, col) = t->n[idx];
                }
            }
        }
    }
    return r;
}

void RegisterFilteredMap(const FilterResult& filtered,
                         const core::MapF& certainty,
                         const core::GridGeometry& grid,
                         ObstacleMap& map) {
    const auto border = static_cast<std::uint8_t>(PixelClass::kBorder);
    const auto filled = static_cast<std::uint8_t>(PixelClass::kFilled);
    for (int i = 0; i < grid.rows; ++i) {
        for (int j = 0; j < grid.cols; ++j) {
            const std::uint8_t cls = filtered.classes.at(i, j);
            const float c = certainty.at(i, j);
            if (cls == border || (c <= 0.0F && cls != filled)) {
                continue;
            }
            map.Register(grid.CellCenterX(i), grid.CellCenterY(j), filtered.elevation.at(i, j), c);
        }
    }
}

}  // namespace casmap::mapper
