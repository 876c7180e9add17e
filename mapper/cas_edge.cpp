// cas_edge (docs/paper-notes.md "cas_edge"): the median votes over the map cas_trail cleaned,
// and CAS keeps objects and box edges at their measured height.
//
// Three observations on the simulated courses (training seeds) drive it:
//   1. the 5 x 5 median of the RAW map lets a dense mixed-pixel trail vote: where the trail
//      covers half the window the median returns a trail height. cas_trail has already removed
//      those cells (to 0 / the local ground / NaN), so the median here runs over cas_trail's
//      output: removed cells vote for the floor, cells CAS filled vote with their fill value;
//   2. the median rounds the top side of every box edge and corner (a corner cell has 9 box
//      cells of 25 in its window), the largest error the median-based pipelines leave on box
//      courses; yet the raw map measures those cells well (many hits, neighbours at the same
//      height). A cell that stands out from the median and has at least edge_min known cells
//      of its window within edge_tol_m of its own height is a surface, not a mixed pixel: kept;
//   3. a pole's halo (its top smeared onto 2-8 neighbouring cells) has fewer same-height
//      neighbours than a surface; among such unsupported candidates only the certainty peak of
//      each window (cas_median's rule) marks an object, and the object's cell is the one that
//      holds the certainty-weighted centroid of the peak's same-height 3 x 3 block.
// So, with T = cas_trail's output and M = the median of T's votes (mapper/ground.hpp: with
// unknown = nan a removed known cell votes with the local ground estimate instead of leaving a
// hole, and a filled cell does not vote; otherwise T itself):
//   candidate  a known (c > 0) cell cas_trail left untouched with |h - M| > support_tol_m;
//   surface    a candidate with >= edge_min known window cells (itself included) within
//              edge_tol_m of h: out = h;
//   peak       any other candidate of highest certainty among the candidates of its (2k+1)^2
//              window (ties: first in row-major order): out = h at the cell of the
//              certainty-weighted centroid of the known cells of its 3 x 3 within edge_tol_m
//              of its height (that cell's own h; the peak's h if that cell is not in the set);
//   out = M    everywhere else (a cell that did not vote keeps T's value: CAS's fill, or NaN).
// cas_hybrid (docs/paper-notes.md "cas_hybrid") is cas_edge with three changes:
//   - cas_median's surface rule for the known cells that stand out from M but are not
//     candidates (cas_trail removed them, or they lie within k of the map's border): one with
//     >= surface_min known window cells within surface_tol_m of its height takes the lower
//     median of those cells (detail::SurfaceMedian). On the training maps those are one-hit
//     cells at a box's far edges and corners, in sparsely seen windows, that Eq. 10 removed
//     inside cas_trail; M rounds them to the floor;
//   - the value of every non-object cell is B = M + median_mix (R - M), R the median of the
//     raw map (where both are known; M elsewhere): M lets CAS's fills vote (right on box tops
//     next to a shadow, wrong on the floor beyond a box edge), R lets never-observed cells
//     vote the floor (the reverse); each is wrong where the other is right; with unknown = nan
//     nan_median_mix replaces median_mix when set (docs/paper-notes.md "Median mix on terrain");
//   - a surface cell takes B + w (h - B), w = c / (c + surface_prior): its measured height
//     in proportion to its evidence. A surface cell seen once (c = a = 3) is as often a box
//     edge (h right) as a box top smeared one cell onto the floor (B right) on the training
//     maps; the least-squares answer for such a cell lies between; cells seen many times keep
//     nearly h;
//   - with edge_fill > 0, a never-observed cell in the shadow beside a surface takes edge_fill
//     of the step up to it (mapper/shadow_edge.cpp): the cell a box's edge falls in holds the
//     box's height in the truth however little of it the box covers, and on the box's far
//     side no beam may reach it.
// Candidates, surfaces and peaks are decided against M exactly as in cas_edge; the pole's
// centroid cell keeps its raw height.
// Every value comes from the unfiltered map, cas_trail's output or the median; the centroid is
// summed in a fixed order, so the output is the same bit for bit at any thread count.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

#include "casmap/mapper/cas_surface.hpp"
#include "casmap/mapper/filters.hpp"
#include "casmap/mapper/ground.hpp"

namespace casmap::mapper {
namespace {

// cas_edge; with hybrid, cas_hybrid (see the top of the file).
FilterResult EdgeFilter(const core::MapF& elevation,
                        const core::MapF& certainty,
                        const FilterParams& params,
                        bool hybrid) {
    params.Validate();
    CasParams cas = params.cas;
    cas.support = Support::kHeight;
    FilterResult out = CasFilter(elevation, certainty, cas);  // cas_trail, classes kept
    // With unknown = nan: removed known cells vote for the local ground, filled cells not at all.
    const core::MapF votes = GroundRelativeVotes(elevation, certainty, cas, out);
    const core::MapF median = MedianFilter(votes, params.baseline);
    const auto tol = static_cast<float>(cas.support_tol_m);
    const auto edge_tol = static_cast<float>(cas.edge_tol_m);
    const auto surface_tol = static_cast<float>(cas.surface_tol_m);
    const auto prior = static_cast<float>(cas.surface_prior);
    std::vector<float> samples;
    // B: the value of non-object cells (M for cas_edge).
    core::MapF base = median;
    if (hybrid && cas.EffectiveMedianMix() > 0.0) {  // nan_median_mix with unknown = nan
        const core::MapF raw_median = MedianFilter(elevation, params.baseline);
        const auto mix = static_cast<float>(cas.EffectiveMedianMix());
        for (std::size_t n = 0; n < base.data.size(); ++n) {
            const float r = raw_median.data[n];
            if (!std::isnan(base.data[n]) && !std::isnan(r)) {
                base.data[n] += mix * (r - base.data[n]);
            }
        }
    }
    const int rows = elevation.rows;
    const int cols = elevation.cols;
    const int k = cas.k;
    const std::size_t cells = elevation.data.size();
    const auto index = [cols](int i, int j) {
        return static_cast<std::size_t>(i) * static_cast<std::size_t>(cols) +
               static_cast<std::size_t>(j);
    };
    const auto known = [&](std::size_t n) {
        return certainty.data[n] > 0.0F && !std::isnan(elevation.data[n]);
    };
    std::vector<std::uint8_t> candidate(cells, 0);
    for (std::size_t n = 0; n < cells; ++n) {
        candidate[n] = out.classes.data[n] == static_cast<std::uint8_t>(PixelClass::kUntouched) &&
                               known(n) && !(std::abs(elevation.data[n] - median.data[n]) <= tol)
                           ? 1
                           : 0;
    }
    // Pass 1: surfaces keep their height, everything else takes M; peaks are collected.
    std::vector<std::size_t> peaks;
    for (int i = 0; i < rows; ++i) {
        for (int j = 0; j < cols; ++j) {
            const std::size_t n = index(i, j);
            bool surface = false;
            bool peak = false;
            if (candidate[n] != 0) {
                const float h = elevation.data[n];
                peak = true;
                int same = 0;
                for (int r = std::max(0, i - k); r <= std::min(rows - 1, i + k); ++r) {
                    for (int s = std::max(0, j - k); s <= std::min(cols - 1, j + k); ++s) {
                        const std::size_t o = index(r, s);
                        if (known(o) && std::abs(elevation.data[o] - h) <= edge_tol) {
                            ++same;
                        }
                        if (o != n && candidate[o] != 0 &&
                            (certainty.data[o] > certainty.data[n] ||
                             (certainty.data[o] == certainty.data[n] && o < n))) {
                            peak = false;
                        }
                    }
                }
                surface = same >= cas.edge_min;
            }
            const float b = base.data[n];
            if (surface) {
                const float h = elevation.data[n];
                const float c = certainty.data[n];
                out.elevation.data[n] =
                    hybrid && prior > 0.0F && !std::isnan(b) ? b + c / (c + prior) * (h - b) : h;
            } else if (std::isnan(votes.data[n])) {
                // A filled cell that did not vote (unknown = nan) keeps CAS's fill value.
            } else if (hybrid && candidate[n] == 0 && known(n) &&
                       !(std::abs(elevation.data[n] - median.data[n]) <= tol)) {
                out.elevation.data[n] = detail::SurfaceMedian(elevation, certainty, i, j, k,
                                                              surface_tol, cas.surface_min, samples)
                                            .value_or(b);
            } else {
                out.elevation.data[n] = b;
            }
            if (peak && !surface) {
                peaks.push_back(n);
            }
        }
    }
    // Pass 2: a peak stands for a small object (a pole) whose top the beam footprint and the
    // pose error smear over a block of cells; the object's cell is the one holding the
    // certainty-weighted centroid of the known cells of the peak's 3 x 3 within edge_tol_m of
    // the peak's height (the peak itself is the truth cell in 641 of 728 training poles, the
    // centroid's cell in 678). That cell keeps its own measured height.
    for (const std::size_t n : peaks) {
        const int i = static_cast<int>(n / static_cast<std::size_t>(cols));
        const int j = static_cast<int>(n % static_cast<std::size_t>(cols));
        const float h = elevation.data[n];
        double w = 0.0;
        double wi = 0.0;
        double wj = 0.0;
        for (int r = std::max(0, i - 1); r <= std::min(rows - 1, i + 1); ++r) {
            for (int s = std::max(0, j - 1); s <= std::min(cols - 1, j + 1); ++s) {
                const std::size_t o = index(r, s);
                if (known(o) && std::abs(elevation.data[o] - h) <= edge_tol) {
                    const double c = certainty.data[o];
                    w += c;
                    wi += c * r;
                    wj += c * s;
                }
            }
        }
        // w >= c(peak) > 0: the peak is in its own set.
        const int ci = static_cast<int>(std::floor(wi / w + 0.5));
        const int cj = static_cast<int>(std::floor(wj / w + 0.5));
        const std::size_t o = index(ci, cj);
        out.elevation.data[o] =
            known(o) && std::abs(elevation.data[o] - h) <= edge_tol ? elevation.data[o] : h;
    }
    RestoreTrustedCells(elevation, certainty, cas, out.elevation);  // mapper/ground.hpp
    BoundByMeasurement(elevation, certainty, cas, out.elevation);   // unknown = nan only
    if (hybrid) {
        const detail::ShadowEdgeParams fill{k,
                                            edge_tol,
                                            cas.edge_min,
                                            tol,
                                            static_cast<float>(cas.EffectiveA()),
                                            static_cast<float>(cas.edge_fill),
                                            cas.edge_fill_run,
                                            static_cast<float>(cas.edge_spill_c),
                                            static_cast<float>(cas.edge_spill_drop_m),
                                            static_cast<float>(cas.edge_spill)};
        detail::FillShadowEdges(elevation, certainty, fill, out.elevation);  // cas_surface.hpp
    }
    // Known cells only (the fill above writes never-observed ones); unknown = nan only.
    SmoothSurfaceCells(elevation, certainty, median, params, out.elevation);
    return out;
}

}  // namespace

FilterResult CasEdgeFilter(const core::MapF& elevation,
                           const core::MapF& certainty,
                           const FilterParams& params) {
    return EdgeFilter(elevation, certainty, params, false);
}

FilterResult CasHybridFilter(const core::MapF& elevation,
                             const core::MapF& certainty,
                             const FilterParams& params) {
    return EdgeFilter(elevation, certainty, params, true);
}

}  // namespace casmap::mapper
