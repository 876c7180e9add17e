// CAS filter, Eq. 7-10 of Ye & Borenstein. Readings of the ambiguous parts (normalisation,
// never-observed cells, the weighted median's samples) are in docs/paper-notes.md.
#include <algorithm>
#include <cmath>
#include <vector>

#include "core/input_error.hpp"
#include "mapper/filters.hpp"

namespace casmap::mapper {
namespace {

// Per-row scratch of window statistics, one entry per column. Window sums are recomputed
// from the rows (never a running sum), so no rounding drifts along the map.
struct RowScratch {
    std::vector<float> sum_c, sum_h, max_h;      // vertical (2k+1) sums/max per column
    std::vector<float> sum_c2, sum_h2, max_c;    // only for the variance and E forms
    std::vector<float> win_c, win_h, win_max_h;  // full (2k+1)^2 window per column
    std::vector<float> win_c2, win_h2, win_max_c;
    explicit RowScratch(std::size_t cols)
        : sum_c(cols),
          sum_h(cols),
          max_h(cols),
          sum_c2(cols),
          sum_h2(cols),
          max_c(cols),
          win_c(cols),
          win_h(cols),
          win_max_h(cols),
          win_c2(cols),
          win_h2(cols),
          win_max_c(cols) {}
};

// Fig. 5: weight 1 on the centre and its four direct neighbours, 2 elsewhere (45 samples for
// k = 2; the median is the 23rd).
std::vector<int> SkeletonOffsets(int k, int cols) {
    std::vector<int> offsets;
    for (int di = -k; di <= k; ++di) {
        for (int dj = -k; dj <= k; ++dj) {
            const int weight = (std::abs(di) + std::abs(dj) <= 1) ? 1 : 2;
            for (int w = 0; w < weight; ++w) {
                offsets.push_back(di * cols + dj);
            }
        }
    }
    return offsets;
}

float WeightedMedian(const float* h,
                     const float* c,
                     const std::vector<int>& offsets,
                     WmEmpty wm_empty,
                     std::vector<float>& samples) {
    samples.clear();
    for (const int off : offsets) {
        if (wm_empty == WmEmpty::kSkip && c[off] == 0.0F) {
            continue;
        }
        samples.push_back(h[off]);
    }
    if (samples.empty()) {
        return h[0];  // nothing observed around: the cell stays as it was (0)
    }
    // Lower median; for the 45 samples of Fig. 5 the 23rd.
    const auto mid = samples.begin() + static_cast<std::ptrdiff_t>((samples.size() - 1) / 2);
    std::nth_element(samples.begin(), mid, samples.end());
    return *mid;
}

void VerticalPass(const std::vector<float>& abs_h,
                  const float* c,
                  int top,
                  int span,
                  int cols,
                  bool need_var,
                  RowScratch& s) {
    const auto n = static_cast<std::size_t>(cols);
    std::fill(s.sum_c.begin(), s.sum_c.end(), 0.0F);
    std::fill(s.sum_h.begin(), s.sum_h.end(), 0.0F);
    std::fill(s.max_h.begin(), s.max_h.end(), 0.0F);
    if (need_var) {
        std::fill(s.sum_c2.begin(), s.sum_c2.end(), 0.0F);
        std::fill(s.sum_h2.begin(), s.sum_h2.end(), 0.0F);
        std::fill(s.max_c.begin(), s.max_c.end(), 0.0F);
    }
    for (int r = top; r < top + span; ++r) {
        const float* hr = abs_h.data() + static_cast<std::size_t>(r) * n;
        const float* cr = c + static_cast<std::size_t>(r) * n;
        for (std::size_t j = 0; j < n; ++j) {
            s.sum_c[j] += cr[j];
            s.sum_h[j] += hr[j];
            s.max_h[j] = std::max(s.max_h[j], hr[j]);
        }
        if (need_var) {
            for (std::size_t j = 0; j < n; ++j) {
                s.sum_c2[j] += cr[j] * cr[j];
                s.sum_h2[j] += hr[j] * hr[j];
                s.max_c[j] = std::max(s.max_c[j], cr[j]);
            }
        }
    }
}

void HorizontalPass(int k, int cols, bool need_var, RowScratch& s) {
    const auto first = static_cast<std::size_t>(k);
    const auto last = static_cast<std::size_t>(cols - k);  // exclusive
    for (std::size_t j = first; j < last; ++j) {
        s.win_c[j] = 0.0F;
        s.win_h[j] = 0.0F;
        s.win_max_h[j] = 0.0F;
    }
    for (int d = -k; d <= k; ++d) {
        for (std::size_t j = first; j < last; ++j) {
            const std::size_t src = static_cast<std::size_t>(static_cast<std::ptrdiff_t>(j) + d);
            s.win_c[j] += s.sum_c[src];
            s.win_h[j] += s.sum_h[src];
            s.win_max_h[j] = std::max(s.win_max_h[j], s.max_h[src]);
        }
    }
    if (!need_var) {
        return;
    }
    for (std::size_t j = first; j < last; ++j) {
        s.win_c2[j] = 0.0F;
        s.win_h2[j] = 0.0F;
        s.win_max_c[j] = 0.0F;
    }
    for (int d = -k; d <= k; ++d) {
        for (std::size_t j = first; j < last; ++j) {
            const std::size_t src = static_cast<std::size_t>(static_cast<std::ptrdiff_t>(j) + d);
            s.win_c2[j] += s.sum_c2[src];
            s.win_h2[j] += s.sum_h2[src];
            s.win_max_c[j] = std::max(s.win_max_c[j], s.max_c[src]);
        }
    }
}

// Variance of x / norm over n samples from the sums of x and x^2 (population variance).
float NormalisedVariance(float sum, float sum2, float norm, float n) {
    if (norm <= 0.0F) {
        return 0.0F;
    }
    const float mean = sum / (norm * n);
    return sum2 / (norm * norm * n) - mean * mean;
}

}  // namespace

FilterResult CasFilter(const core::MapF& elevation,
                       const core::MapF& certainty,
                       const CasParams& p) {
    if (!elevation.SameShape(certainty)) {
        throw MakeInputError("cas filter", "certainty",
                             std::to_string(certainty.rows) + "x" + std::to_string(certainty.cols),
                             "must have the elevation map's size " +
                                 std::to_string(elevation.rows) + "x" +
                                 std::to_string(elevation.cols));
    }
    const int rows = elevation.rows;
    const int cols = elevation.cols;
    const int k = p.k;
    const int span = 2 * k + 1;
    FilterResult out;
    out.elevation = elevation;
    out.classes = ClassMap(rows, cols, static_cast<std::uint8_t>(PixelClass::kBorder));
    if (rows < span || cols < span) {
        return out;
    }
    const auto A = static_cast<float>(p.EffectiveA());
    const auto G = static_cast<float>(p.EffectiveG());
    const auto h_sum_min = static_cast<float>(p.h_sum_min);
    const auto B = static_cast<float>(p.B);
    const auto E = static_cast<float>(p.E);
    const auto n_window = static_cast<float>(span * span);
    const bool variance_gs = p.gs_mode == GsMode::kVariance;
    const bool need_var = variance_gs || p.e_term;
    const bool global = p.normalise == Normalise::kGlobal;

    std::vector<float> abs_h(elevation.data.size());
    float global_max_h = 0.0F;
    float global_max_c = 0.0F;
    for (std::size_t i = 0; i < abs_h.size(); ++i) {
        abs_h[i] = std::abs(elevation.data[i]);
        global_max_h = std::max(global_max_h, abs_h[i]);
        global_max_c = std::max(global_max_c, certainty.data[i]);
    }
    const std::vector<int> skeleton = SkeletonOffsets(k, cols);
    std::vector<float> samples;
    samples.reserve(skeleton.size());
    RowScratch s(static_cast<std::size_t>(cols));
    const float* h = elevation.data.data();
    const float* c = certainty.data.data();

    for (int i = k; i < rows - k; ++i) {
        VerticalPass(abs_h, c, i - k, span, cols, need_var, s);
        HorizontalPass(k, cols, need_var, s);
        const std::size_t row_off = static_cast<std::size_t>(i) * static_cast<std::size_t>(cols);
        for (int j = k; j < cols - k; ++j) {
            const auto ju = static_cast<std::size_t>(j);
            const std::size_t idx = row_off + ju;
            const float cij = c[idx];
            const float max_h = global ? global_max_h : s.win_max_h[ju];
            // g_s (Eq. 9): 0 = spatially discontinuous. Sum form: sum of H-bar < h_sum_min.
            bool gs0 = false;
            if (variance_gs) {
                gs0 = NormalisedVariance(s.win_h[ju], s.win_h2[ju], max_h, n_window) > B;
            } else {
                gs0 = max_h > 0.0F ? s.win_h[ju] < h_sum_min * max_h : 0.0F < h_sum_min;
            }
            // g_c (Eq. 10): 0 = too little certainty in the window (or too varied, E term).
            bool gc0 = s.win_c[ju] < G;
            if (p.e_term && !gc0) {
                const float max_c = global ? global_max_c : s.win_max_c[ju];
                gc0 = NormalisedVariance(s.win_c[ju], s.win_c2[ju], max_c, n_window) > E;
            }
            PixelClass cls = PixelClass::kUntouched;
            if (cij <= A && gs0 && gc0) {
                out.elevation.data[idx] = 0.0F;  // Eq. 7 first branch
                cls = PixelClass::kRemoved;
            } else if (!gs0 && cij == 0.0F) {
                out.elevation.data[idx] =
                    WeightedMedian(h + idx, c + idx, skeleton, p.wm_empty, samples);
                cls = PixelClass::kFilled;
            }
            out.classes.data[idx] = static_cast<std::uint8_t>(cls);
        }
    }
    return out;
}

}  // namespace casmap::mapper
