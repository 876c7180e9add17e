#include "casmap/pipeline/sweep_search.hpp"

#include <cmath>
#include <optional>
#include <utility>

#include "casmap/pipeline/sweep_detail.hpp"

namespace casmap::pipeline::detail {

/// The chosen point: lowest finite mean PI among points keeping every pole in every run; if
/// none does, the most poles kept, then the lowest mean PI. First in grid order on ties.
void ChooseBest(SweepResult& result) {
    std::optional<std::size_t> best;
    bool any_keep = false;
    for (const SweepPoint& p : result.points) {
        any_keep = any_keep || (p.KeepsEveryPole() && std::isfinite(p.pi.mean));
    }
    for (std::size_t i = 0; i < result.points.size(); ++i) {
        const SweepPoint& p = result.points[i];
        if (!std::isfinite(p.pi.mean) || (any_keep && !p.KeepsEveryPole())) {
            continue;
        }
        if (!best) {
            best = i;
            continue;
        }
        const SweepPoint& b = result.points[*best];
        const bool better = any_keep ? p.pi.mean < b.pi.mean
                                     : (p.poles_kept > b.poles_kept ||
                                        (p.poles_kept == b.poles_kept && p.pi.mean < b.pi.mean));
        best = better ? i : *best;
    }
    result.best = best.value_or(0);
    result.best_keeps_every_pole = any_keep;
    result.best_rule = any_keep ? "lowest mean PI among the points that kept every pole in every "
                                  "training run"
                                : "no point kept every pole in every training run: most poles "
                                  "kept, then lowest mean PI";
}

/// Points not dominated in (mean PI lower, poles kept higher, spikes lower).
std::vector<std::size_t> ParetoFront(const std::vector<SweepPoint>& points) {
    std::vector<std::size_t> front;
    for (std::size_t i = 0; i < points.size(); ++i) {
        const SweepPoint& p = points[i];
        if (!std::isfinite(p.pi.mean)) {
            continue;
        }
        bool dominated = false;
        for (std::size_t j = 0; j < points.size() && !dominated; ++j) {
            const SweepPoint& q = points[j];
            if (j == i || !std::isfinite(q.pi.mean)) {
                continue;
            }
            const bool no_worse = q.pi.mean <= p.pi.mean && q.poles_kept >= p.poles_kept &&
                                  q.spikes_total <= p.spikes_total;
            const bool better = q.pi.mean < p.pi.mean || q.poles_kept > p.poles_kept ||
                                q.spikes_total < p.spikes_total;
            dominated = no_worse && better;
        }
        if (!dominated) {
            front.push_back(i);
        }
    }
    return front;
}

/// Extends every axis (or only `only_axis` when >= 0) whose edge holds the best point, when
/// the value beyond is allowed and the grid stays <= 10000 points; returns the growth records
/// (empty: nothing grew, `opt` unchanged).
std::vector<SweepGrowth> Grow(SweepOptions& opt, const SweepPoint& best, int round, int only_axis) {
    SweepOptions next = opt;
    std::vector<SweepGrowth> grown;
    for (std::size_t i = 0; i < next.axes.size(); ++i) {
        SweepAxis& axis = next.axes[i];
        const std::size_t n = axis.values.size();
        if (n < 2 || (only_axis >= 0 && static_cast<std::size_t>(only_axis) != i)) {
            continue;  // a single value has no step to grow by
        }
        const double v = best.values[i];
        std::optional<double> added;
        if (v == axis.values.front()) {
            const double value = detail::Snap(axis.values[0] - (axis.values[1] - axis.values[0]));
            if (detail::AxisValueAllowed(next, axis.name, value)) {
                axis.values.insert(axis.values.begin(), value);
                added = value;
            }
        } else if (v == axis.values.back()) {
            const double value =
                detail::Snap(axis.values[n - 1] + (axis.values[n - 1] - axis.values[n - 2]));
            if (detail::AxisValueAllowed(next, axis.name, value)) {
                axis.values.push_back(value);
                added = value;
            }
        }
        if (added) {
            grown.push_back({round, axis.name, {*added}, best.values});
        }
    }
    std::size_t total = 1;
    for (const SweepAxis& a : next.axes) {
        total *= a.values.size();
    }
    if (total > 10000 || grown.empty()) {
        return {};
    }
    opt = std::move(next);
    return grown;
}

}  // namespace casmap::pipeline::detail
