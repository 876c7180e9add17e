#pragma once

// World-fixed obstacle-negotiation map (paper Sec. IV.B): the elevation map the live window
// registers its CAS-filtered rows into, in cells that may be coarser than the 25 mm mapping
// cells (default 100 mm). It grows as the vehicle travels (tiles allocated on first use).
//
// Aggregation of fine cells into one coarse cell: the highest filtered height registered
// into it, with the certainty of the fine cell that gave that height (on equal heights, the
// larger certainty). The highest height because a vehicle must clear the tallest thing in
// the cell; its own certainty so a tall reading resting on a single beam stays visibly weak.

#include <cstdint>
#include <memory>
#include <unordered_map>

#include "casmap/core/grid.hpp"
#include "casmap/mapper/filters.hpp"

namespace casmap::mapper {

/// A raster copy of an obstacle map: its grid (origin on the map's lattice), the height
/// (m, 0 where nothing was registered), certainty (counts) and registered fine-cell counts.
struct ObstacleRaster {
    core::GridGeometry grid;
    core::MapF elevation;
    core::MapF certainty;
    core::Raster<std::uint16_t> count;  // fine cells registered per coarse cell (0: unknown)
};

class ObstacleMap {
public:
    /// Cells of `cell_m` on the world lattice x0 + i cell_m, y0 + j cell_m. Throws InputError
    /// unless cell_m is finite and > 0 and the origin finite.
    explicit ObstacleMap(double cell_m, double x0_m = 0.0, double y0_m = 0.0);

    /// Registers one filtered fine cell centred at world (x, y) with height h (m) and the
    /// certainty c (counts) of the mapping cell. Never allocates for an already used tile.
    void Register(double x_m, double y_m, float h_m, float c);

    /// The smallest raster holding every registered cell (0 x 0 if none).
    [[nodiscard]] ObstacleRaster ToRaster() const;
    /// The grid of ToRaster() without copying cells (kept up to date by Register).
    [[nodiscard]] core::GridGeometry Bounds() const;
    /// A raster over exactly `grid` (its cell size must be this map's; origin on the lattice).
    [[nodiscard]] ObstacleRaster ToRaster(const core::GridGeometry& grid) const;

    [[nodiscard]] double cell_m() const { return cell_m_; }
    [[nodiscard]] std::uint64_t registered() const { return registered_; }

private:
    static constexpr int kTile = 64;  // cells per tile side
    struct Tile {
        float h[kTile * kTile];
        float c[kTile * kTile];
        std::uint16_t n[kTile * kTile];
    };
    [[nodiscard]] static std::int64_t Key(std::int64_t ti, std::int64_t tj);
    Tile& TileAt(std::int64_t ti, std::int64_t tj);
    [[nodiscard]] const Tile* FindTile(std::int64_t ti, std::int64_t tj) const;

    double cell_m_;
    double x0_m_;
    double y0_m_;
    std::unordered_map<std::int64_t, std::unique_ptr<Tile>> tiles_;
    std::int64_t last_key_ = 0;
    Tile* last_tile_ = nullptr;  // the tile of the previous Register (rows stay in a few tiles)
    std::uint64_t registered_ = 0;
    std::int64_t i0_ = 0, i1_ = -1, j0_ = 0, j1_ = -1;  // registered cell index bounds
};

/// The offline counterpart of the live registration: every non-border cell of a CAS-filtered
/// map on `grid` that was observed (certainty > 0) or filled by CAS, registered at its centre.
void RegisterFilteredMap(const FilterResult& filtered,
                         const core::MapF& certainty,
                         const core::GridGeometry& grid,
                         ObstacleMap& map);

}  // namespace casmap::mapper
