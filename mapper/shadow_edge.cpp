// cas_hybrid's edge_fill (docs/paper-notes.md "cas_hybrid", "Occluded box edges"): a
// never-observed cell in the shadow right beside a measured surface takes part of the step.
//
// The truth of a cell is the highest surface point anywhere in it (docs/paper-notes.md
// "Metrics"), so the cell a box's edge falls in holds the box's height, however little of it the
// box covers. On the far side of a box (seen from the scanner) that cell lies in the box's
// shadow: when the box covers only a sliver of it no beam hits it and it stays unknown, and
// every filter gives it the floor's height (the shadow's fill). On the training maps the
// unobserved cells beside a box top whose shadow continues beyond them hold the box's height
// 13-63 % of the time (the rest are the first floor cells of the shadow); the least-squares
// value for such a cell lies between the floor and the top, in proportion to that probability.
// Only beside surface cells seen at most A times (Eq. 7's "seen rarely"; see below).
//
// Spills (edge_spill_c > 0): the reverse case. Beams that hit a box top near its far edge
// return ranges a few cm too long (the footprint straddles the edge), so their points land one
// cell past the edge, on the floor, at nearly the top's height; seen once (c = a), such a cell
// is the outermost surface cell before the shadow and every filter keeps it at the top's
// height. On the training maps (seeds 1-2) a one-hit outermost surface cell whose measured
// height is within 1 cm of the surface it continues is the box's edge cell 89-97 % of the time,
// but one 1-3 cm below it is the floor 76-100 % of the time (the long range also drops the
// point along the beam). Such a cell takes edge_spill of the step down to the shadow's value
// (the least-squares value), and the shadow beyond it gets no edge_fill from it.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <optional>
#include <utility>
#include <vector>

#include "casmap/mapper/cas_surface.hpp"

namespace casmap::mapper::detail {

void FillShadowEdges(const core::MapF& elevation,
                     const core::MapF& certainty,
                     const ShadowEdgeParams& params,
                     core::MapF& out) {
    const bool spills = params.spill_max_certainty > 0.0F;
    if (params.fill <= 0.0F && !spills) {
        return;
    }
    const int rows = elevation.rows;
    const int cols = elevation.cols;
    const int k = params.k;
    const auto index = [cols](int i, int j) {
        return static_cast<std::size_t>(i) * static_cast<std::size_t>(cols) +
               static_cast<std::size_t>(j);
    };
    const auto inside = [rows, cols](int i, int j) {
        return i >= 0 && i < rows && j >= 0 && j < cols;
    };
    const auto known = [&](std::size_t n) {
        return certainty.data[n] > 0.0F && !std::isnan(elevation.data[n]);
    };
    // surface[n]: -1 not yet decided, 0 no, 1 a known cell seen at most max_certainty times
    // that the filter kept within edge_tol of its measured height, with >= edge_min known
    // window cells (itself included) within edge_tol of it (cas_edge's surface test). A surface
    // cell seen more often lies where the scanner looked often: had the box reached into the
    // unknown cell beside it, a beam would have hit that sliver (training maps: 0-12 % of such
    // unknown cells hold the box's height, against 29-76 % beside cells seen at most A times).
    std::vector<std::int8_t> surface(elevation.data.size(), -1);
    const auto is_surface = [&](int i, int j) {
        const std::size_t n = index(i, j);
        if (surface[n] < 0) {
            const float h = elevation.data[n];
            bool yes = known(n) && certainty.data[n] <= params.max_certainty &&
                       std::abs(out.data[n] - h) <= params.edge_tol;
            if (yes) {
                int same = 0;
                for (int r = std::max(0, i - k); r <= std::min(rows - 1, i + k); ++r) {
                    for (int s = std::max(0, j - k); s <= std::min(cols - 1, j + k); ++s) {
                        const std::size_t o = index(r, s);
                        same += known(o) && std::abs(elevation.data[o] - h) <= params.edge_tol;
                    }
                }
                yes = same >= params.edge_min;
            }
            surface[n] = yes ? 1 : 0;
        }
        return surface[n] == 1;
    };
    constexpr int kSteps[4][2] = {{1, 0}, {-1, 0}, {0, 1}, {0, -1}};
    // Spills, decided and valued on the input out; written after the fill.
    std::vector<std::pair<std::size_t, float>> spilled;
    std::vector<std::uint8_t> is_spill(spills ? elevation.data.size() : 0, 0);
    std::vector<float> samples;
    for (int i = 0; spills && i < rows; ++i) {
        for (int j = 0; j < cols; ++j) {
            const std::size_t n = index(i, j);
            if (!known(n) || certainty.data[n] > params.spill_max_certainty || !is_surface(i, j)) {
                continue;
            }
            for (const auto& step : kSteps) {
                const int pi = i - step[0];
                const int pj = j - step[1];
                const int fi = i + step[0];
                const int fj = j + step[1];
                const int gi = fi + step[0];
                const int gj = fj + step[1];
                if (!inside(pi, pj) || !inside(fi, fj) || known(index(fi, fj)) ||
                    (inside(gi, gj) && known(index(gi, gj))) || !known(index(pi, pj)) ||
                    !(std::abs(out.data[index(pi, pj)] - out.data[n]) <= params.edge_tol)) {
                    continue;
                }
                const float top = out.data[n];
                const float floor = out.data[index(fi, fj)];
                if (std::isnan(floor) || !(top - floor > params.step_min)) {
                    continue;
                }
                const std::optional<float> m =
                    SurfaceMedian(elevation, certainty, pi, pj, k, params.edge_tol, 1, samples);
                if (!m || !(elevation.data[n] <= *m - params.spill_drop)) {
                    continue;
                }
                spilled.emplace_back(n, floor + params.spill * (top - floor));
                is_spill[n] = 1;
                break;
            }
        }
    }
    for (int i = 0; params.fill > 0.0F && i < rows; ++i) {
        for (int j = 0; j < cols; ++j) {
            const std::size_t u = index(i, j);
            const float base = out.data[u];
            if (known(u) || std::isnan(base)) {
                continue;
            }
            // The highest surface 4-neighbour whose shadow continues past (i, j): the cell on
            // the other side is unknown too, or outside the map.
            bool found = false;
            float top = 0.0F;
            for (const auto& step : kSteps) {
                const int ni = i - step[0];
                const int nj = j - step[1];
                const int bi = i + step[0];
                const int bj = j + step[1];
                if (!inside(ni, nj) || (inside(bi, bj) && known(index(bi, bj))) ||
                    !known(index(ni, nj)) || !is_surface(ni, nj) ||
                    (spills && is_spill[index(ni, nj)] != 0)) {
                    continue;
                }
                const float h = out.data[index(ni, nj)];
                // The edge continues along the box: the neighbour's own neighbours across the
                // step (on the edge's line) that are surfaces at its height.
                int along = 0;
                for (const int side : {1, -1}) {
                    const int li = ni + side * step[1];
                    const int lj = nj + side * step[0];
                    along += inside(li, lj) && known(index(li, lj)) && is_surface(li, lj) &&
                                     std::abs(out.data[index(li, lj)] - h) <= params.edge_tol
                                 ? 1
                                 : 0;
                }
                if (along < params.along_min) {
                    continue;
                }
                if (!found || h > top) {
                    top = h;
                    found = true;
                }
            }
            if (found && top - base > params.step_min) {
                out.data[u] = base + params.fill * (top - base);
            }
        }
    }
    for (const auto& [n, value] : spilled) {
        out.data[n] = value;
    }
}

}  // namespace casmap::mapper::detail
