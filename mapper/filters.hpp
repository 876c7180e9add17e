#pragma once

#include <cstdint>

#include "casmap/core/grid.hpp"
#include "casmap/mapper/filter_params.hpp"

namespace casmap::mapper {

/// What the CAS filter did to one pixel (Eq. 7 branches; Table II classes).
enum class PixelClass : std::uint8_t {
    kUntouched = 0,  // output = input (third branch)
    kRemoved = 1,    // set to 0: mixed pixel / artifact (first branch)
    kFilled = 2,     // weighted median of the Fig. 5 skeleton: missing data (second branch)
    kBorder = 3,     // within k cells of the edge: the window does not fit, left as it was
};
using ClassMap = core::Raster<std::uint8_t>;

struct FilterResult {
    core::MapF elevation;  // filtered H, metres
    ClassMap classes;      // per-pixel PixelClass for CAS; empty (0 x 0) for the baselines
};

/// Runs one filter on the raw elevation map H (metres) and certainty map C (counts).
/// The certainty map is needed by CAS only (it may be empty otherwise). Throws InputError if
/// the parameters are invalid or H and C differ in size. Never filters in place: every output
/// pixel is computed from the unfiltered input.
[[nodiscard]] FilterResult RunFilter(FilterMethod method,
                                     const core::MapF& elevation,
                                     const core::MapF& certainty,
                                     const FilterParams& params);

/// CAS filter, Eq. 7-10 (mapper/cas_filter.cpp). Pixels within k of the border are kBorder.
[[nodiscard]] FilterResult CasFilter(const core::MapF& elevation,
                                     const core::MapF& certainty,
                                     const CasParams& params);

/// The same, reusing `out`'s buffers (for repeated calls, e.g. a benchmark or a live map).
void CasFilterInto(const core::MapF& elevation,
                   const core::MapF& certainty,
                   const CasParams& params,
                   FilterResult& out);

/// cas_median (mapper/cas_median.cpp): candidates = known cells cas_trail (CAS with
/// support = height) left untouched that differ from the median (params.baseline.window) by more
/// than support_tol_m; objects = candidates with the highest certainty among the candidates of
/// their (2k+1)^2 window (ties: first in row-major order). Output: the raw height on objects,
/// the median everywhere else; then RestoreTrustedCells (mapper/ground.hpp). Classes = the
/// cas_trail classes. Throws InputError as RunFilter.
[[nodiscard]] FilterResult CasMedianFilter(const core::MapF& elevation,
                                           const core::MapF& certainty,
                                           const FilterParams& params);

/// cas_edge (mapper/cas_edge.cpp): T = cas_trail's output, M = its median
/// (params.baseline); candidates = known cells cas_trail left untouched with |h - M| >
/// support_tol_m; objects = candidates with >= edge_min known window cells within edge_tol_m of
/// their height (surfaces: box edges, corners) or the highest certainty among the candidates of
/// their window (ties: first in row-major order). Output: h on objects, M elsewhere. Classes =
/// cas_trail's. With unknown = nan, M is the median of GroundRelativeVotes (mapper/ground.hpp):
/// removed known cells vote for the local ground, filled cells keep their fill value. Ends with
/// RestoreTrustedCells (mapper/ground.hpp). Throws InputError as RunFilter.
[[nodiscard]] FilterResult CasEdgeFilter(const core::MapF& elevation,
                                         const core::MapF& certainty,
                                         const FilterParams& params);

/// cas_hybrid (mapper/cas_edge.cpp): cas_edge, plus cas_median's surface rule on the known cells
/// that differ from M by more than support_tol_m but are not candidates: one with >=
/// surface_min known window cells within surface_tol_m of its height takes the lower median of
/// those cells instead of M. Classes = cas_trail's. Throws InputError as RunFilter.
[[nodiscard]] FilterResult CasHybridFilter(const core::MapF& elevation,
                                           const core::MapF& certainty,
                                           const FilterParams& params);

/// Baselines (mapper/baseline_filters.cpp). Every one replicates the edge pixels beyond the
/// border (OpenCV BORDER_REPLICATE, the mode cv::medianBlur uses internally).
[[nodiscard]] core::MapF WienerFilter(const core::MapF& elevation, const BaselineParams& params);
[[nodiscard]] core::MapF AverageFilter(const core::MapF& elevation, const BaselineParams& params);
[[nodiscard]] core::MapF MedianFilter(const core::MapF& elevation, const BaselineParams& params);
[[nodiscard]] core::MapF CwmFilter(const core::MapF& elevation, const BaselineParams& params);

/// The Wiener noise power actually used: params.noise or the mean local variance (m^2).
[[nodiscard]] double WienerNoise(const core::MapF& elevation, const BaselineParams& params);

}  // namespace casmap::mapper
