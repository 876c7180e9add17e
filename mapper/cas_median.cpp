// cas_median (docs/paper-notes.md "cas_median"): CAS decides which cells are objects, a median
// smooths everything else, except where the median would round a surface's edge. The median has
// the lowest PI of the paper's filters on open floor and box tops (it removes noise, mixed pixels
// and trails alike) but deletes every object narrower than half its window (the poles) and cuts
// the edges and corners of wider ones (a box corner has 9 top cells in a 5 x 5 window of 25).
// cas_trail keeps the poles (their cores have certainty above A and support at their height) and
// removes the trails beside them, but leaves the floor's noise as it was measured, and it also
// keeps the pole's halo: the neighbours of a pole's cell that hold the pole's top (beam
// footprint and pose error smear the top over them; they are well observed and share the top's
// height, so neither Eq. 10 nor the support test removes them). So:
//   candidate  a cell cas_trail left untouched, known (c > 0), that stands out from the median
//              by more than support_tol_m (an object the median would delete);
//   object     a candidate with the highest certainty among the candidates of its (2k+1)^2
//              window (ties: the first in row-major order): one cell per object, the one the
//              scanner saw most often, which is where the object stands;
//   surface    a known non-object cell that stands out from the median by more than
//              support_tol_m and has at least surface_min known cells of its (2k+1)^2 window
//              (itself included) within surface_tol_m of its own height: the edge or corner of
//              a surface wider than a pole (a trail or a halo has a few such cells at most);
//   out = h            on objects,
//         the lower median of those same-height known cells   on surfaces,
//         the median of the raw map   everywhere else (floor, box tops, halos, removed trails,
//                                      filled holes).
// Every value comes from the unfiltered map; no floating-point reduction, so the output is the
// same bit for bit at any thread count.
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <vector>

#include "casmap/mapper/cas_surface.hpp"
#include "casmap/mapper/filters.hpp"
#include "casmap/mapper/ground.hpp"

namespace casmap::mapper {

std::optional<float> detail::SurfaceMedian(const core::MapF& elevation,
                                           const core::MapF& certainty,
                                           int i,
                                           int j,
                                           int k,
                                           float tol,
                                           int min_cells,
                                           std::vector<float>& samples) {
    const float h = elevation.at(i, j);
    samples.clear();
    for (int r = std::max(0, i - k); r <= std::min(elevation.rows - 1, i + k); ++r) {
        for (int s = std::max(0, j - k); s <= std::min(elevation.cols - 1, j + k); ++s) {
            const float v = elevation.at(r, s);
            if (certainty.at(r, s) > 0.0F && std::abs(v - h) <= tol) {  // false for NaN
                samples.push_back(v);
            }
        }
    }
    if (static_cast<int>(samples.size()) < min_cells) {
        return std::nullopt;
    }
    const auto mid = samples.begin() + static_cast<std::ptrdiff_t>((samples.size() - 1) / 2);
    std::nth_element(samples.begin(), mid, samples.end());
    return *mid;
}

FilterResult CasMedianFilter(const core::MapF& elevation,
                             const core::MapF& certainty,
                             const FilterParams& params) {
    params.Validate();
    CasParams cas = params.cas;
    cas.support = Support::kHeight;
    FilterResult out = CasFilter(elevation, certainty, cas);  // the cas_trail classes
    const core::MapF median = MedianFilter(elevation, params.baseline);
    const auto tol = static_cast<float>(cas.support_tol_m);
    const std::size_t cells = out.elevation.data.size();
    const auto surface_tol = static_cast<float>(cas.surface_tol_m);
    std::vector<std::uint8_t> candidate(cells, 0);
    std::vector<std::uint8_t> stands_out(cells, 0);
    for (std::size_t n = 0; n < cells; ++n) {
        const float h = elevation.data[n];
        stands_out[n] =
            certainty.data[n] > 0.0F && !std::isnan(h) && !(std::abs(h - median.data[n]) <= tol)
                ? 1
                : 0;
        candidate[n] = stands_out[n] != 0 && out.classes.data[n] ==
                                                 static_cast<std::uint8_t>(PixelClass::kUntouched)
                           ? 1
                           : 0;
    }
    std::vector<float> samples;
    const int rows = elevation.rows;
    const int cols = elevation.cols;
    const int k = cas.k;
    const auto index = [cols](int i, int j) {
        return static_cast<std::size_t>(i) * static_cast<std::size_t>(cols) +
               static_cast<std::size_t>(j);
    };
    for (int i = 0; i < rows; ++i) {
        for (int j = 0; j < cols; ++j) {
            const std::size_t n = index(i, j);
            bool object = candidate[n] != 0;
            for (int r = std::max(0, i - k); object && r <= std::min(rows - 1, i + k); ++r) {
                for (int s = std::max(0, j - k); s <= std::min(cols - 1, j + k); ++s) {
                    const std::size_t o = index(r, s);
                    if (o != n && candidate[o] != 0 &&
                        (certainty.data[o] > certainty.data[n] ||
                         (certainty.data[o] == certainty.data[n] && o < n))) {
                        object = false;
                        break;
                    }
                }
            }
            if (object) {
                out.elevation.data[n] = elevation.data[n];
            } else if (stands_out[n] != 0) {
                out.elevation.data[n] = detail::SurfaceMedian(elevation, certainty, i, j, k,
                                                              surface_tol, cas.surface_min, samples)
                                            .value_or(median.data[n]);
            } else {
                out.elevation.data[n] = median.data[n];
            }
        }
    }
    RestoreTrustedCells(elevation, certainty, cas, out.elevation);            // mapper/ground.hpp
    BoundByMeasurement(elevation, certainty, cas, out.elevation);             // unknown = nan only
    SmoothSurfaceCells(elevation, certainty, median, params, out.elevation);  // unknown = nan only
    return out;
}

}  // namespace casmap::mapper
