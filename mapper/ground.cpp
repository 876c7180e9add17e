// Ground-relative votes (mapper/ground.hpp, docs/paper-notes.md "Ground-relative votes on
// terrain").
#include "casmap/mapper/ground.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <string>
#include <vector>

#include "casmap/core/input_error.hpp"
#include "casmap/mapper/cas_variants.hpp"

namespace casmap::mapper {

namespace {

std::string Size(int rows, int cols) { return std::to_string(rows) + "x" + std::to_string(cols); }

// Every map these functions take has the elevation map's size (as CasFilter checks).
template <class Map>
void CheckSize(const core::MapF& elevation, const Map& map, const std::string& field) {
    if (map.rows != elevation.rows || map.cols != elevation.cols) {
        throw MakeInputError(
            "ground", field, Size(map.rows, map.cols),
            "must have the elevation map's size " + Size(elevation.rows, elevation.cols));
    }
}

std::size_t Index(int cols, int i, int j) {
    return static_cast<std::size_t>(i) * static_cast<std::size_t>(cols) +
           static_cast<std::size_t>(j);
}

// A halo: a 3 x 3 neighbour of (i, j) that `filtered` kept at its measured height, seen more
// often than (i, j), lies within edge_tol of its measured height (a pole's top smeared onto it).
bool IsHalo(const core::MapF& elevation,
            const core::MapF& certainty,
            const core::MapF& filtered,
            int i,
            int j,
            float edge_tol) {
    const int rows = elevation.rows;
    const int cols = elevation.cols;
    const std::size_t n = Index(cols, i, j);
    const float h = elevation.data[n];
    const float c = certainty.data[n];
    for (int r = std::max(0, i - 1); r <= std::min(rows - 1, i + 1); ++r) {
        for (int s = std::max(0, j - 1); s <= std::min(cols - 1, j + 1); ++s) {
            const std::size_t o = Index(cols, r, s);
            const float ho = elevation.data[o];
            if (o != n && certainty.data[o] > c && !std::isnan(ho) && filtered.data[o] == ho &&
                std::abs(ho - h) <= edge_tol) {
                return true;
            }
        }
    }
    return false;
}

}  // namespace

core::MapF LocalGroundEstimate(const core::MapF& elevation,
                               const core::MapF& certainty,
                               int k,
                               double quantile) {
    CheckSize(elevation, certainty, "certainty");
    if (k < 0) {
        throw MakeInputError("ground", "k", std::to_string(k), "allowed: >= 0");
    }
    if (!(quantile >= 0.0 && quantile <= 1.0)) {
        throw MakeInputError("ground", "quantile", std::to_string(quantile), "allowed: 0..1");
    }
    return detail::LocalGround(elevation, certainty, k, quantile);
}

core::MapF GroundRelativeVotes(const core::MapF& elevation,
                               const core::MapF& certainty,
                               const CasParams& params,
                               const FilterResult& cleaned) {
    CheckSize(elevation, certainty, "certainty");
    CheckSize(elevation, cleaned.elevation, "cleaned.elevation");
    core::MapF votes = cleaned.elevation;
    if (params.unknown != Unknown::kNaN || params.ground != Ground::kZero) {
        return votes;
    }
    CheckSize(elevation, cleaned.classes, "cleaned.classes");
    const auto removed = static_cast<std::uint8_t>(PixelClass::kRemoved);
    const auto filled = static_cast<std::uint8_t>(PixelClass::kFilled);
    const std::size_t cells = votes.data.size();
    core::MapF ground;
    for (std::size_t n = 0; n < cells; ++n) {
        const bool known = certainty.data[n] > 0.0F && !std::isnan(elevation.data[n]);
        if (cleaned.classes.data[n] == removed && known) {
            if (ground.data.empty()) {
                ground =
                    detail::LocalGround(elevation, certainty, params.k, params.ground_quantile);
            }
            votes.data[n] = ground.data[n];
        } else if (cleaned.classes.data[n] == filled && !known) {
            votes.data[n] = std::numeric_limits<float>::quiet_NaN();
        }
    }
    return votes;
}

void RestoreTrustedCells(const core::MapF& elevation,
                         const core::MapF& certainty,
                         const CasParams& params,
                         core::MapF& filtered) {
    CheckSize(elevation, certainty, "certainty");
    CheckSize(elevation, filtered, "filtered");
    const auto trusted = static_cast<float>(params.EffectiveG());
    const auto tol = static_cast<float>(params.support_tol_m);
    const auto edge_tol = static_cast<float>(params.edge_tol_m);
    const int rows = elevation.rows;
    const int cols = elevation.cols;
    const auto index = [cols](int i, int j) { return Index(cols, i, j); };
    // Decided on the filter's output as it came (no cell sees another's restoration).
    std::vector<std::size_t> restore;
    for (int i = 0; i < rows; ++i) {
        for (int j = 0; j < cols; ++j) {
            const std::size_t n = index(i, j);
            const float h = elevation.data[n];
            const float c = certainty.data[n];
            const float y = filtered.data[n];
            if (!(c > trusted) || std::isnan(h) || std::isnan(y) || !(std::abs(y - h) > tol)) {
                continue;
            }
            if (!IsHalo(elevation, certainty, filtered, i, j, edge_tol)) {
                restore.push_back(n);
            }
        }
    }
    for (const std::size_t n : restore) {
        filtered.data[n] = elevation.data[n];
    }
}

void BoundByMeasurement(const core::MapF& elevation,
                        const core::MapF& certainty,
                        const CasParams& params,
                        core::MapF& filtered) {
    CheckSize(elevation, certainty, "certainty");
    CheckSize(elevation, filtered, "filtered");
    if (params.unknown != Unknown::kNaN) {
        return;
    }
    const auto tol = static_cast<float>(params.support_tol_m);
    const auto edge_tol = static_cast<float>(params.edge_tol_m);
    const auto seen = static_cast<float>(params.EffectiveA());
    const int rows = elevation.rows;
    const int cols = elevation.cols;
    // Decided on the filter's output as it came (the halo test sees no other cell's change).
    std::vector<std::size_t> restore;
    std::vector<std::size_t> clamp;
    for (int i = 0; i < rows; ++i) {
        for (int j = 0; j < cols; ++j) {
            const std::size_t n = Index(cols, i, j);
            const float h = elevation.data[n];
            const float c = certainty.data[n];
            const float y = filtered.data[n];
            if (!(c > 0.0F) || std::isnan(h) || std::isnan(y)) {
                continue;
            }
            if (y > h + tol) {
                clamp.push_back(n);
            } else if (y < h - tol && c > seen &&
                       !IsHalo(elevation, certainty, filtered, i, j, edge_tol)) {
                restore.push_back(n);
            }
        }
    }
    for (const std::size_t n : clamp) {
        filtered.data[n] = elevation.data[n] + tol;
    }
    for (const std::size_t n : restore) {
        filtered.data[n] = elevation.data[n];
    }
}

void SmoothSurfaceCells(const core::MapF& elevation,
                        const core::MapF& certainty,
                        const core::MapF& median,
                        const FilterParams& params,
                        core::MapF& filtered) {
    CheckSize(elevation, certainty, "certainty");
    CheckSize(elevation, median, "median");
    CheckSize(elevation, filtered, "filtered");
    if (params.cas.unknown != Unknown::kNaN) {
        return;
    }
    const auto near = static_cast<float>(params.cas.surface_tol_m);
    core::MapF smooth;
    for (std::size_t n = 0; n < filtered.data.size(); ++n) {
        const float h = elevation.data[n];
        if (!(certainty.data[n] > 0.0F) || std::isnan(h) ||
            !(std::abs(filtered.data[n] - h) <= near) || !(std::abs(median.data[n] - h) <= near)) {
            continue;
        }
        if (smooth.data.empty()) {
            smooth = WienerFilter(elevation, params.baseline);
        }
        if (std::abs(smooth.data[n] - h) <= near) {
            filtered.data[n] = smooth.data[n];
        }
    }
}

}  // namespace casmap::mapper
