#include "casmap/mapper/obstacle_map.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "casmap/core/input_error.hpp"

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
        throw MakeInputError("obstacle map", "cell_m", std::to_string(cell_m),
                             "must be finite and > 0");
    }
    if (!(std::isfinite(x0_m) && std::isfinite(y0_m))) {
        throw MakeInputError("obstacle map", "origin", std::to_string(x0_m), "must be finite");
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
    ++registered_;
}

ObstacleRaster ObstacleMap::ToRaster() const {
    if (tiles_.empty()) {
        ObstacleRaster r;
        r.grid.cell_m = cell_m_;
        r.grid.x0_m = x0_m_;
        r.grid.y0_m = y0_m_;
        return r;
    }
    std::int64_t i0 = std::numeric_limits<std::int64_t>::max();
    std::int64_t j0 = i0;
    std::int64_t i1 = std::numeric_limits<std::int64_t>::min();
    std::int64_t j1 = i1;
    for (const auto& [key, tile] : tiles_) {
        const std::int64_t ti = key >> 32;
        const auto tj = static_cast<std::int64_t>(static_cast<std::int32_t>(key & 0xFFFFFFFFLL));
        for (int a = 0; a < kTile; ++a) {
            for (int b = 0; b < kTile; ++b) {
                if (tile->n[a * kTile + b] != 0) {
                    i0 = std::min(i0, ti * kTile + a);
                    i1 = std::max(i1, ti * kTile + a);
                    j0 = std::min(j0, tj * kTile + b);
                    j1 = std::max(j1, tj * kTile + b);
                }
            }
        }
    }
    core::GridGeometry g;
    g.cell_m = cell_m_;
    g.x0_m = x0_m_ + static_cast<double>(i0) * cell_m_;
    g.y0_m = y0_m_ + static_cast<double>(j0) * cell_m_;
    g.rows = static_cast<int>(i1 - i0 + 1);
    g.cols = static_cast<int>(j1 - j0 + 1);
    return ToRaster(g);
}

ObstacleRaster ObstacleMap::ToRaster(const core::GridGeometry& grid) const {
    ObstacleRaster r;
    r.grid = grid;
    r.elevation = core::MapF(grid.rows, grid.cols, 0.0F);
    r.certainty = core::MapF(grid.rows, grid.cols, 0.0F);
    r.count = core::Raster<std::uint16_t>(grid.rows, grid.cols, 0);
    const auto i0 = static_cast<std::int64_t>(std::llround((grid.x0_m - x0_m_) / cell_m_));
    const auto j0 = static_cast<std::int64_t>(std::llround((grid.y0_m - y0_m_) / cell_m_));
    for (int a = 0; a < grid.rows; ++a) {
        for (int b = 0; b < grid.cols; ++b) {
            const std::int64_t i = i0 + a;
            const std::int64_t j = j0 + b;
            const std::int64_t ti = FloorDiv(i, kTile);
            const std::int64_t tj = FloorDiv(j, kTile);
            const Tile* t = FindTile(ti, tj);
            if (t == nullptr) {
                continue;
            }
            const auto idx = static_cast<std::size_t>((i - ti * kTile) * kTile + (j - tj * kTile));
            r.elevation.at(a, b) = t->h[idx];
            r.certainty.at(a, b) = t->c[idx];
            r.count.at(a, b) = t->n[idx];
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
