// CAS filter, Eq. 7-10 of Ye & Borenstein. Readings of the ambiguous parts (normalisation,
// never-observed cells, the weighted median's samples) are in docs/paper-notes.md.
//
// Speed: window statistics are separable sums and maxima over plain float rows (the compiler
// vectorises them; mapper/cas_window_stats.cpp); the weighted median of the Fig. 5 skeleton is
// mapper/skeleton_median.cpp. Every pixel's result depends only on the unfiltered input, in a fixed
// order of operations: the output is deterministic.
#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <span>
#include <utility>
#include <vector>

#include "casmap/core/input_error.hpp"
#include "casmap/mapper/cas_row_k2.hpp"
#include "casmap/mapper/cas_variants.hpp"
#include "casmap/mapper/cas_window_stats.hpp"
#include "casmap/mapper/filters.hpp"
#include "casmap/mapper/skeleton_median.hpp"

namespace casmap::mapper {
namespace {

using detail::RowStats;

// Population variance of x / norm over the window, by brute force (the optional forms).
float NormalisedVariance(const float* x, std::size_t cols, std::size_t idx, int k, float norm) {
    if (norm <= 0.0F) {
        return 0.0F;
    }
    float sum = 0.0F;
    float sum2 = 0.0F;
    for (int di = -k; di <= k; ++di) {
        for (int dj = -k; dj <= k; ++dj) {
            const float v =
                x[static_cast<std::size_t>(
                    static_cast<std::ptrdiff_t>(idx) +
                    static_cast<std::ptrdiff_t>(di) * static_cast<std::ptrdiff_t>(cols) + dj)] /
                norm;
            sum += v;
            sum2 += v * v;
        }
    }
    const auto n = static_cast<float>((2 * k + 1) * (2 * k + 1));
    const float mean = sum / n;
    return sum2 / n - mean * mean;
}

float WindowMaxOf(const float* x, std::size_t cols, std::size_t idx, int k) {
    float m = 0.0F;
    for (int di = -k; di <= k; ++di) {
        for (int dj = -k; dj <= k; ++dj) {
            m = std::max(
                m, x[static_cast<std::size_t>(
                       static_cast<std::ptrdiff_t>(idx) +
                       static_cast<std::ptrdiff_t>(di) * static_cast<std::ptrdiff_t>(cols) + dj)]);
        }
    }
    return m;
}

// Eq. 7 for one row in the default form (sum g_s, no E term), written so the compiler can
// vectorise it: the class of each pixel from its window statistics; removed pixels set to 0.
struct RowInputs {
    const float* h;        // elevation row (the unfiltered input)
    const float* c;        // certainty row
    const float* win_c;    // window sums of c
    const float* win_h;    // window sums of |h|
    const float* win_max;  // window maxima of |h| (unused with a global maximum)
};
struct Thresholds {
    float A, G, h_sum_min, global_max_h, global_max_c;
    bool global;
};

template <bool kGlobal>
CASMAP_VECTOR_CLONES void ClassifyRowSum(const RowInputs& in,
                                         const Thresholds& t,
                                         std::size_t first,
                                         std::size_t last,
                                         float* __restrict y,
                                         std::uint8_t* __restrict cls) {
    const float* __restrict hr = in.h;
    const float* __restrict c = in.c;
    const float* __restrict wc = in.win_c;
    const float* __restrict wh = in.win_h;
    const float* __restrict wm = in.win_max;
    // An all-zero window (max 0) has H-bar = 0 everywhere, a sum of 0.
    const int empty_gs0 = 0.0F < t.h_sum_min ? 1 : 0;
    const float A = t.A;
    const float G = t.G;
    const float h_sum_min = t.h_sum_min;
    const float global_max = t.global_max_h;
    for (std::size_t j = first; j < last; ++j) {
        const float max_h = kGlobal ? global_max : wm[j];
        const int gs0 = static_cast<int>(wh[j] < h_sum_min * max_h) |
                        (static_cast<int>(max_h <= 0.0F) & empty_gs0);
        const int gc0 = static_cast<int>(wc[j] < G);
        const int removed = static_cast<int>(c[j] <= A) & gs0 & gc0;
        const int fill = (gs0 ^ 1) & static_cast<int>(c[j] == 0.0F);  // excludes removed
        y[j] = removed != 0 ? 0.0F : hr[j];
        cls[j] = static_cast<std::uint8_t>(removed | (fill << 1));
    }
}

// k = 2, default form: the window sums and maximum come straight from the column sums in
// the classification loop (same order of operations as RowStatsK2's window loops).
template <bool kGlobal>
CASMAP_VECTOR_CLONES void ClassifyRowSumK2(const RowInputs& in,
                                           const RowStats& s,
                                           const Thresholds& t,
                                           std::size_t cols,
                                           float* __restrict y,
                                           std::uint8_t* __restrict cls) {
    const float* __restrict hr = in.h;
    const float* __restrict c = in.c;
    const float* __restrict sc = s.col_c.data();
    const float* __restrict sh = s.col_h.data();
    const float* __restrict sm = s.col_max.data();
    const int empty_gs0 = 0.0F < t.h_sum_min ? 1 : 0;
    const float A = t.A;
    const float G = t.G;
    const float h_sum_min = t.h_sum_min;
    const float global_max = t.global_max_h;
    for (std::size_t j = 2; j + 2 < cols; ++j) {
        const float wc = (((sc[j - 2] + sc[j - 1]) + sc[j]) + sc[j + 1]) + sc[j + 2];
        const float wh = (((sh[j - 2] + sh[j - 1]) + sh[j]) + sh[j + 1]) + sh[j + 2];
        float wm = sm[j - 2];
        wm = sm[j - 1] > wm ? sm[j - 1] : wm;
        wm = sm[j] > wm ? sm[j] : wm;
        wm = sm[j + 1] > wm ? sm[j + 1] : wm;
        wm = sm[j + 2] > wm ? sm[j + 2] : wm;
        const float max_h = kGlobal ? global_max : wm;
        const int gs0 = static_cast<int>(wh < h_sum_min * max_h) |
                        (static_cast<int>(max_h <= 0.0F) & empty_gs0);
        const int gc0 = static_cast<int>(wc < G);
        const int removed = static_cast<int>(c[j] <= A) & gs0 & gc0;
        const int fill = (gs0 ^ 1) & static_cast<int>(c[j] == 0.0F);
        y[j] = removed != 0 ? 0.0F : hr[j];
        cls[j] = static_cast<std::uint8_t>(removed | (fill << 1));
    }
}

// The optional forms (variance g_s, E term): per pixel, not vectorised.
void ClassifyRowGeneral(const float* abs_h,
                        const float* c_map,
                        std::size_t cols,
                        std::size_t row_off,
                        const RowInputs& in,
                        const CasParams& p,
                        const Thresholds& t,
                        std::size_t first,
                        std::size_t last,
                        float* y,
                        std::uint8_t* cls) {
    const int k = p.k;
    for (std::size_t j = first; j < last; ++j) {
        const std::size_t idx = row_off + j;
        const float max_h = t.global ? t.global_max_h : in.win_max[j];
        bool gs0 = max_h > 0.0F ? in.win_h[j] < t.h_sum_min * max_h : 0.0F < t.h_sum_min;
        if (p.gs_mode == GsMode::kVariance) {
            gs0 = NormalisedVariance(abs_h, cols, idx, k, max_h) > static_cast<float>(p.B);
        }
        bool gc0 = in.win_c[j] < t.G;
        if (p.e_term && !gc0) {
            const float max_c = t.global ? t.global_max_c : WindowMaxOf(c_map, cols, idx, k);
            gc0 = NormalisedVariance(c_map, cols, idx, k, max_c) > static_cast<float>(p.E);
        }
        const bool removed = (in.c[j] <= t.A) & gs0 & gc0;
        const bool fill = !gs0 & (in.c[j] == 0.0F);
        y[j] = removed ? 0.0F : in.h[j];
        cls[j] = removed ? std::uint8_t{1} : (fill ? std::uint8_t{2} : std::uint8_t{0});
    }
}

// Sizes the output and fills the unprocessed border (k cells wide): output = input, class
// kBorder. The interior is written by the row classification.
void ResetOutput(const core::MapF& elevation, int k, FilterResult& out) {
    const int rows = elevation.rows;
    const int cols = elevation.cols;
    out.elevation.rows = rows;
    out.elevation.cols = cols;
    out.elevation.data.resize(elevation.data.size());
    out.classes.rows = rows;
    out.classes.cols = cols;
    out.classes.data.resize(elevation.data.size());
    const auto border = static_cast<std::uint8_t>(PixelClass::kBorder);
    const auto copy = [&](int i, int j0, int j1) {
        const std::size_t a = static_cast<std::size_t>(i) * static_cast<std::size_t>(cols) +
                              static_cast<std::size_t>(j0);
        const auto n = static_cast<std::size_t>(j1 - j0);
        std::memcpy(out.elevation.data.data() + a, elevation.data.data() + a, n * sizeof(float));
        std::memset(out.classes.data.data() + a, border, n);
    };
    float* y = out.elevation.data.data();
    std::uint8_t* cls = out.classes.data.data();
    const float* h = elevation.data.data();
    for (int i = 0; i < rows; ++i) {
        if (i < k || i >= rows - k || cols <= 2 * k) {
            copy(i, 0, cols);
        } else {
            // k cells at each end: element copies, not two library calls per row.
            const std::size_t row = static_cast<std::size_t>(i) * static_cast<std::size_t>(cols);
            for (int j = 0; j < k; ++j) {
                const std::size_t a = row + static_cast<std::size_t>(j);
                const std::size_t b = row + static_cast<std::size_t>(cols - 1 - j);
                y[a] = h[a];
                y[b] = h[b];
                cls[a] = border;
                cls[b] = border;
            }
        }
    }
}

Thresholds MakeThresholds(const CasParams& p,
                          const std::vector<float>& abs_h,
                          const core::MapF& certainty) {
    const bool global = p.normalise == Normalise::kGlobal;
    Thresholds t{};
    t.A = static_cast<float>(p.EffectiveA());
    t.G = static_cast<float>(p.EffectiveG());
    t.h_sum_min = static_cast<float>(p.h_sum_min);
    t.global_max_h = global ? *std::max_element(abs_h.begin(), abs_h.end()) : 0.0F;
    t.global_max_c =
        global ? *std::max_element(certainty.data.begin(), certainty.data.end()) : 0.0F;
    t.global = global;
    return t;
}

// Appends the row's filled pixels to fills[n..]; returns the new count. Eight class bytes at a
// time: a word test finds the (few) bytes equal to kFilled, so the cost follows the fills.
std::size_t AppendFills(const std::uint8_t* cls,
                        std::size_t row_off,
                        std::size_t first,
                        std::size_t last,
                        std::vector<std::size_t>& fills,
                        std::size_t n) {
    constexpr auto kFill = static_cast<std::uint8_t>(PixelClass::kFilled);
    std::size_t j = first;
    if constexpr (std::endian::native == std::endian::little) {
        constexpr std::uint64_t kLow7 = 0x7F7F7F7F7F7F7F7FULL;
        constexpr std::uint64_t kFillBytes = 0x0101010101010101ULL * kFill;
        for (; j + 8 <= last; j += 8) {
            std::uint64_t word = 0;
            std::memcpy(&word, cls + j, sizeof(word));
            const std::uint64_t x = word ^ kFillBytes;  // zero bytes where the class is kFilled
            std::uint64_t hits = ~(((x & kLow7) + kLow7) | x | kLow7);  // 0x80 per zero byte
            while (hits != 0) {
                fills[n++] = row_off + j + static_cast<std::size_t>(std::countr_zero(hits)) / 8;
                hits &= hits - 1;
            }
        }
    }
    for (; j < last; ++j) {
        if (cls[j] == kFill) {
            fills[n++] = row_off + j;
        }
    }
    return n;
}

}  // namespace

void CasFilterInto(const core::MapF& elevation,
                   const core::MapF& certainty,
                   const CasParams& p,
                   FilterResult& out) {
    if (!elevation.SameShape(certainty)) {
        throw MakeInputError("cas filter", "certainty",
                             std::to_string(certainty.rows) + "x" + std::to_string(certainty.cols),
                             "must have the elevation map's size " +
                                 std::to_string(elevation.rows) + "x" +
                                 std::to_string(elevation.cols));
    }
    if (p.unknown != Unknown::kZero || p.ground != Ground::kZero || p.support != Support::kOff) {
        detail::CasVariantInto(elevation, certainty, p, out);  // the wave-2 forms
        return;
    }
    const int k = p.k;
    ResetOutput(elevation, k, out);
    if (elevation.rows < 2 * k + 1 || elevation.cols < 2 * k + 1) {
        return;
    }
    const auto cols = static_cast<std::size_t>(elevation.cols);
    const auto first = static_cast<std::size_t>(k);
    const std::size_t last = cols - first;
    // Scratch reused between calls on the same thread (no page faults on every call).
    thread_local std::vector<float> abs_h;
    thread_local std::vector<std::size_t> fills;
    const bool general = p.gs_mode == GsMode::kVariance || p.e_term;
    const bool fused = k == 2 && !general;
    // The fused path takes |h| on the fly; the others (and a map-wide maximum) need the map.
    const bool need_abs = !fused || p.normalise == Normalise::kGlobal;
    if (need_abs) {
        abs_h.resize(elevation.data.size());
        detail::AbsInto(elevation.data.data(), abs_h.size(), abs_h.data());
    }
    if (fills.size() < elevation.data.size()) {
        fills.resize(elevation.data.size());  // grown once, never shrunk: no zeroing per call
    }
    std::size_t n_fills = 0;
    const Thresholds t = MakeThresholds(p, abs_h, certainty);
    const float* c = certainty.data.data();
    float* y = out.elevation.data.data();
    if (fused && detail::CasRowK2Available()) {
        // The default form on AVX2: one pass per row (mapper/cas_row_k2.hpp), same bits.
        thread_local std::vector<float> scratch;
        scratch.resize(3 * cols + 24);
        const detail::CasK2Thresholds t2{t.A, t.G, t.h_sum_min, t.global_max_h, t.global};
        for (int i = k; i < elevation.rows - k; ++i) {
            n_fills =
                detail::CasRowK2(elevation.data.data(), c, cols, static_cast<std::size_t>(i), t2,
                                 scratch.data(), y, out.classes.data.data(), fills.data(), n_fills);
        }
        SkeletonMedian(elevation.data.data(), c, elevation.cols, k, p.wm_empty,
                       std::span<const std::size_t>(fills.data(), n_fills), y);
        return;
    }
    RowStats s(cols);
    for (int i = k; i < elevation.rows - k; ++i) {
        if (fused) {
            detail::ColumnStatsK2Signed(elevation.data.data(), c, cols, i - k, s);
        } else {
            detail::ComputeRowStats(abs_h.data(), c, cols, i - k, k, s);
        }
        const std::size_t row_off = static_cast<std::size_t>(i) * cols;
        std::uint8_t* cls = out.classes.data.data() + row_off;
        const RowInputs in{elevation.data.data() + row_off, c + row_off, s.win_c.data(),
                           s.win_h.data(), s.win_max.data()};
        if (fused) {
            if (t.global) {
                ClassifyRowSumK2<true>(in, s, t, cols, y + row_off, cls);
            } else {
                ClassifyRowSumK2<false>(in, s, t, cols, y + row_off, cls);
            }
        } else if (general) {
            ClassifyRowGeneral(abs_h.data(), c, cols, row_off, in, p, t, first, last, y + row_off,
                               cls);
        } else if (t.global) {
            ClassifyRowSum<true>(in, t, first, last, y + row_off, cls);
        } else {
            ClassifyRowSum<false>(in, t, first, last, y + row_off, cls);
        }
        n_fills = AppendFills(cls, row_off, first, last, fills, n_fills);
    }
    // The weighted median reads the unfiltered map, so filling after the loop changes nothing.
    SkeletonMedian(elevation.data.data(), c, elevation.cols, k, p.wm_empty,
                   std::span<const std::size_t>(fills.data(), n_fills), y);
}

FilterResult CasFilter(const core::MapF& elevation,
                       const core::MapF& certainty,
                       const CasParams& p) {
    FilterResult out;
    CasFilterInto(elevation, certainty, p, out);
    return out;
}

}  // namespace casmap::mapper
