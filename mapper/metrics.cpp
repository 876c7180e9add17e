#include "casmap/mapper/metrics.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "casmap/core/input_error.hpp"

namespace casmap::mapper {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

void CheckShapes(const core::MapF& a, const core::MapF& b, const Region& region) {
    if (!a.SameShape(b)) {
        throw MakeInputError("metrics", "map size",
                             std::to_string(b.rows) + "x" + std::to_string(b.cols),
                             "must equal " + std::to_string(a.rows) + "x" + std::to_string(a.cols));
    }
    if (region.row0 < 0 || region.col0 < 0 || region.rows < 0 || region.cols < 0 ||
        region.row0 + region.rows > a.rows || region.col0 + region.cols > a.cols) {
        throw MakeInputError("metrics", "region",
                             std::to_string(region.row0) + "," + std::to_string(region.col0) + "+" +
                                 std::to_string(region.rows) + "x" + std::to_string(region.cols),
                             "must lie inside the map");
    }
}

// Sum of (a - b)^2 over the region's cells where a, b (and `also`, when given) are all
// finite, and the number of those cells. With the paper's 0-for-unknown maps every cell
// counts and the sum is the same, in the same order, as before NaN maps existed.
struct Sum {
    double sq = 0.0;
    std::int64_t cells = 0;
};
Sum SquaredError(const core::MapF& a,
                 const core::MapF& b,
                 const Region& r,
                 const core::MapF* also = nullptr) {
    Sum s;
    for (int i = r.row0; i < r.row0 + r.rows; ++i) {
        for (int j = r.col0; j < r.col0 + r.cols; ++j) {
            const double d = static_cast<double>(a.at(i, j)) - static_cast<double>(b.at(i, j));
            if (std::isnan(d) || (also != nullptr && std::isnan(also->at(i, j)))) {
                continue;
            }
            s.sq += d * d;
            ++s.cells;
        }
    }
    return s;
}

void AddClass(ClassShares& s, PixelClass cls) {
    ++s.cells;
    if (cls == PixelClass::kRemoved) {
        s.removed_pct += 1.0;
    } else if (cls == PixelClass::kFilled) {
        s.filled_pct += 1.0;
    } else {
        s.untouched_pct += 1.0;
    }
}

void ToPercent(ClassShares& s) {
    const double scale = s.cells > 0 ? 100.0 / static_cast<double>(s.cells) : 0.0;
    s.removed_pct *= scale;
    s.filled_pct *= scale;
    s.untouched_pct *= scale;
}

bool IsTruthEdge(const core::MapF& truth, int i, int j, double step_m) {
    const double t = truth.at(i, j);
    const int di[4] = {-1, 1, 0, 0};
    const int dj[4] = {0, 0, -1, 1};
    for (int n = 0; n < 4; ++n) {
        const int r = i + di[n];
        const int c = j + dj[n];
        if (r >= 0 && c >= 0 && r < truth.rows && c < truth.cols &&
            std::abs(static_cast<double>(truth.at(r, c)) - t) > step_m) {
            return true;
        }
    }
    return false;
}

}  // namespace

Region PaperRegion(int map_rows, int map_cols) {
    Region r;
    r.rows = std::min(200, map_rows);
    r.cols = std::min(80, map_cols);
    r.row0 = (map_rows - r.rows) / 2;
    r.col0 = (map_cols - r.cols) / 2;
    return r;
}

Region FullRegion(int map_rows, int map_cols) { return Region{0, 0, map_rows, map_cols}; }

double PerformanceIndex(const core::MapF& filtered,
                        const core::MapF& raw,
                        const core::MapF& truth,
                        const Region& region) {
    CheckShapes(truth, filtered, region);
    CheckShapes(truth, raw, region);
    const double den = SquaredError(raw, truth, region, &filtered).sq;
    return den > 0.0 ? SquaredError(filtered, truth, region, &raw).sq / den : kNaN;
}

double Rmse(const core::MapF& a, const core::MapF& b, const Region& region) {
    CheckShapes(a, b, region);
    const Sum s = SquaredError(a, b, region);
    return s.cells > 0 ? std::sqrt(s.sq / static_cast<double>(s.cells)) : kNaN;
}

ClassReport ClassPercentages(const ClassMap& classes, const core::MapF& certainty) {
    ClassReport report;
    const bool have_c = certainty.rows == classes.rows && certainty.cols == classes.cols;
    for (std::size_t i = 0; i < classes.data.size(); ++i) {
        const auto cls = static_cast<PixelClass>(classes.data[i]);
        if (cls == PixelClass::kBorder) {
            continue;
        }
        AddClass(report.all, cls);
        const bool never_observed = have_c && certainty.data[i] == 0.0F;
        if (!never_observed || cls == PixelClass::kFilled) {
            AddClass(report.observed, cls);
        }
    }
    ToPercent(report.all);
    ToPercent(report.observed);
    return report;
}

std::int64_t CountSpikes(const core::MapF& map,
                         const core::MapF& truth,
                         const Region& region,
                         const SpikeRule& rule) {
    CheckShapes(truth, map, region);
    std::int64_t count = 0;
    const int rad = rule.radius_cells;
    for (int i = region.row0; i < region.row0 + region.rows; ++i) {
        for (int j = region.col0; j < region.col0 + region.cols; ++j) {
            float highest = -std::numeric_limits<float>::infinity();
            for (int r = std::max(0, i - rad); r <= std::min(truth.rows - 1, i + rad); ++r) {
                for (int c = std::max(0, j - rad); c <= std::min(truth.cols - 1, j + rad); ++c) {
                    if (!std::isnan(truth.at(r, c))) {
                        highest = std::max(highest, truth.at(r, c));
                    }
                }
            }
            // An unknown (NaN) map cell is no spike: the comparison below is false.
            if (static_cast<double>(map.at(i, j)) - static_cast<double>(highest) >
                rule.threshold_m) {
                ++count;
            }
        }
    }
    return count;
}

FilterMetrics EvaluateFilter(const FilterResult& result,
                             const core::MapF& raw,
                             const core::MapF& truth,
                             const Region& region) {
    FilterMetrics m;
    m.pi = PerformanceIndex(result.elevation, raw, truth, region);
    const Sum filtered = SquaredError(result.elevation, truth, region, &raw);
    const Sum raw_sum = SquaredError(raw, truth, region, &result.elevation);
    m.cells = filtered.cells;
    m.rmse_m =
        filtered.cells > 0 ? std::sqrt(filtered.sq / static_cast<double>(filtered.cells)) : kNaN;
    m.raw_rmse_m =
        raw_sum.cells > 0 ? std::sqrt(raw_sum.sq / static_cast<double>(raw_sum.cells)) : kNaN;
    const std::int64_t raw_known = SquaredError(raw, truth, region).cells;
    m.coverage =
        raw_known > 0 ? static_cast<double>(m.cells) / static_cast<double>(raw_known) : kNaN;
    m.spikes = CountSpikes(result.elevation, truth, region);
    m.raw_spikes = CountSpikes(raw, truth, region);
    const bool have_classes =
        result.classes.rows == truth.rows && result.classes.cols == truth.cols;
    double filled_sq = 0.0;
    double edge_sq = 0.0;
    double open_sq = 0.0;
    std::int64_t edges = 0;
    std::int64_t open = 0;
    const double step_m = SpikeRule{}.threshold_m;
    for (int i = region.row0; i < region.row0 + region.rows; ++i) {
        for (int j = region.col0; j < region.col0 + region.cols; ++j) {
            const double d = static_cast<double>(result.elevation.at(i, j)) -
                             static_cast<double>(truth.at(i, j));
            if (std::isnan(d)) {
                continue;  // unknown in the filtered map or the truth (NaN maps)
            }
            if (have_classes &&
                result.classes.at(i, j) == static_cast<std::uint8_t>(PixelClass::kFilled)) {
                ++m.filled_cells;
                filled_sq += d * d;
            }
            if (std::isnan(raw.at(i, j))) {
                continue;  // not a scored cell
            }
            if (IsTruthEdge(truth, i, j, step_m)) {
                ++edges;
                edge_sq += d * d;
            } else {
                ++open;
                open_sq += d * d;
            }
        }
    }
    m.filled_rmse_m =
        m.filled_cells > 0 ? std::sqrt(filled_sq / static_cast<double>(m.filled_cells)) : kNaN;
    m.edge_rmse_m = edges > 0 ? std::sqrt(edge_sq / static_cast<double>(edges)) : kNaN;
    m.open_rmse_m = open > 0 ? std::sqrt(open_sq / static_cast<double>(open)) : kNaN;
    m.edge_cells = edges;
    m.open_cells = open;
    return m;
}

}  // namespace casmap::mapper
