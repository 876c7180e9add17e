// CAS filter, Eq. 7-10 of Ye & Borenstein. Readings of the ambiguous parts (normalisation,
// never-observed cells, the weighted median's samples) are in docs/paper-notes.md.
//
// Speed: window statistics are separable sums and maxima over plain float rows (the compiler
// vectorises them); the weighted median of the Fig. 5 skeleton runs for 8 filled pixels at a
// time through a min/max network (see FastSkeletonMedian). Every pixel's result depends only
// on the unfiltered input, in a fixed order of operations: the output is deterministic.
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <utility>
#include <vector>

#if defined(__x86_64__) && defined(__GNUC__)
#include <immintrin.h>
#endif

#include "core/input_error.hpp"
#include "mapper/filters.hpp"

// The hot row loops are compiled twice, for AVX2 and the baseline, and picked at load time
// (GCC function multi-versioning). Both run the same element-wise operations in the same
// order (no FMA, no reassociation), so the output is identical on every x86-64 machine.
#if defined(__x86_64__) && defined(__GNUC__) && !defined(__clang__)
#define CASMAP_VECTOR_CLONES __attribute__((target_clones("avx2", "default")))
#else
#define CASMAP_VECTOR_CLONES
#endif

namespace casmap::mapper {
namespace {

using Comparator = std::pair<int, int>;

// Batcher's odd-even merge sort on wires [lo, hi] (inclusive), hi - lo + 1 a power of two.
void OddEvenMerge(int lo, int hi, int r, std::vector<Comparator>& out) {
    const int step = r * 2;
    if (step < hi - lo) {
        OddEvenMerge(lo, hi, step, out);
        OddEvenMerge(lo + r, hi, step, out);
        for (int i = lo + r; i < hi - r; i += step) {
            out.emplace_back(i, i + r);
        }
    } else {
        out.emplace_back(lo, lo + r);
    }
}

void OddEvenMergeSort(int lo, int hi, std::vector<Comparator>& out) {
    if (hi - lo >= 1) {
        const int mid = lo + (hi - lo) / 2;
        OddEvenMergeSort(lo, mid, out);
        OddEvenMergeSort(mid + 1, hi, out);
        OddEvenMerge(lo, hi, 1, out);
    }
}

// A min/max network that puts ranks [first, last] of n inputs in place: Batcher's network
// for the next power of two with the (+inf) padding wires dropped, then pruned to the
// comparators the wanted outputs depend on.
std::vector<Comparator> SelectionNetwork(int n, int first, int last) {
    int size = 1;
    while (size < n) {
        size *= 2;
    }
    std::vector<Comparator> all;
    OddEvenMergeSort(0, size - 1, all);
    std::vector<bool> needed(static_cast<std::size_t>(size), false);
    for (int w = first; w <= last; ++w) {
        needed[static_cast<std::size_t>(w)] = true;
    }
    std::vector<Comparator> kept;
    for (auto it = all.rbegin(); it != all.rend(); ++it) {
        const auto [a, b] = *it;
        if (b >= n) {
            continue;  // the padding wire holds +inf: a no-op
        }
        if (needed[static_cast<std::size_t>(a)] || needed[static_cast<std::size_t>(b)]) {
            needed[static_cast<std::size_t>(a)] = true;
            needed[static_cast<std::size_t>(b)] = true;
            kept.push_back(*it);
        }
    }
    std::reverse(kept.begin(), kept.end());
    return kept;
}

constexpr int kLanes = 8;
constexpr int kOuter = 20;  // weight-2 cells of Fig. 5
constexpr int kInner = 5;   // weight-1 cells: the centre and its four direct neighbours

// kLanes floats processed together (GCC/Clang vector extension).
typedef float Lanes __attribute__((vector_size(kLanes * sizeof(float))));

#if defined(__x86_64__) && defined(__GNUC__)
// minps/maxps, for AVX2 (8 lanes at once) or SSE (two halves); picked once at run time.
__attribute__((target("avx2"))) void ApplyNetworkAvx2(const std::vector<Comparator>& net,
                                                      Lanes* v) {
    auto* p = reinterpret_cast<float*>(v);
    for (const auto& [a, b] : net) {
        float* pa = p + a * kLanes;
        float* pb = p + b * kLanes;
        const __m256 x = _mm256_loadu_ps(pa);
        const __m256 y = _mm256_loadu_ps(pb);
        _mm256_storeu_ps(pa, _mm256_min_ps(x, y));
        _mm256_storeu_ps(pb, _mm256_max_ps(x, y));
    }
}

void ApplyNetworkSse(const std::vector<Comparator>& net, Lanes* v) {
    auto* p = reinterpret_cast<float*>(v);
    for (const auto& [a, b] : net) {
        for (int half = 0; half < kLanes; half += 4) {
            float* pa = p + a * kLanes + half;
            float* pb = p + b * kLanes + half;
            const __m128 x = _mm_loadu_ps(pa);
            const __m128 y = _mm_loadu_ps(pb);
            _mm_storeu_ps(pa, _mm_min_ps(x, y));
            _mm_storeu_ps(pb, _mm_max_ps(x, y));
        }
    }
}

bool UseAvx2() {
    static const bool avx2 = __builtin_cpu_supports("avx2") != 0;
    return avx2;
}

void ApplyNetwork(const std::vector<Comparator>& net, Lanes* v) {
    if (UseAvx2()) {
        ApplyNetworkAvx2(net, v);
    } else {
        ApplyNetworkSse(net, v);
    }
}
#else
void ApplyNetwork(const std::vector<Comparator>& net, Lanes* v) {
    for (const auto& [a, b] : net) {
        const Lanes x = v[a];
        const Lanes y = v[b];
        v[a] = y < x ? y : x;  // min and max as minps/maxps define them
        v[b] = y < x ? x : y;
    }
}
#endif

// The 23rd of the 45 Fig. 5 samples for k = 2, empty cells included. With O the 20 outer
// values sorted (each counted twice) and I the 5 inner ones sorted, the k-th of the union of
// two sorted lists is min_j max(D_(k-j), I_j); for k = 23 the non-dominated terms leave
// min(o12, max(o11, i1), max(o10, i3), max(o9, i5)) (1-based ranks).
void FastSkeletonMedian(const float* h,
                        int cols,
                        const std::vector<std::size_t>& fills,
                        float* out) {
    static const std::vector<Comparator> outer_net = SelectionNetwork(kOuter, 8, 11);
    static const std::vector<Comparator> inner_net = SelectionNetwork(kInner, 0, 4);
    std::array<std::ptrdiff_t, kOuter> outer_off{};
    std::array<std::ptrdiff_t, kInner> inner_off{};
    int no = 0;
    int ni = 0;
    for (int di = -2; di <= 2; ++di) {
        for (int dj = -2; dj <= 2; ++dj) {
            const std::ptrdiff_t off = static_cast<std::ptrdiff_t>(di) * cols + dj;
            if (std::abs(di) + std::abs(dj) <= 1) {
                inner_off[static_cast<std::size_t>(ni++)] = off;
            } else {
                outer_off[static_cast<std::size_t>(no++)] = off;
            }
        }
    }
    std::array<Lanes, kOuter> o{};
    std::array<Lanes, kInner> in{};
    for (std::size_t b = 0; b < fills.size(); b += kLanes) {
        for (int l = 0; l < kLanes; ++l) {
            const std::size_t idx =
                fills[std::min(b + static_cast<std::size_t>(l), fills.size() - 1)];
            const float* centre = h + idx;
            for (int s = 0; s < kOuter; ++s) {
                o[static_cast<std::size_t>(s)][l] = centre[outer_off[static_cast<std::size_t>(s)]];
            }
            for (int s = 0; s < kInner; ++s) {
                in[static_cast<std::size_t>(s)][l] = centre[inner_off[static_cast<std::size_t>(s)]];
            }
        }
        ApplyNetwork(outer_net, o.data());
        ApplyNetwork(inner_net, in.data());
        const Lanes t1 = o[10] < in[0] ? in[0] : o[10];
        const Lanes t2 = o[9] < in[2] ? in[2] : o[9];
        const Lanes t3 = o[8] < in[4] ? in[4] : o[8];
        Lanes m = t1 < o[11] ? t1 : o[11];
        m = t2 < m ? t2 : m;
        m = t3 < m ? t3 : m;
        for (int l = 0; l < kLanes && b + static_cast<std::size_t>(l) < fills.size(); ++l) {
            out[fills[b + static_cast<std::size_t>(l)]] = m[l];
        }
    }
}

// Any k, either wm_empty mode: collect the skeleton's samples and select the lower median.
void GenericSkeletonMedian(const float* h,
                           const float* c,
                           int cols,
                           int k,
                           WmEmpty wm_empty,
                           const std::vector<std::size_t>& fills,
                           float* out) {
    std::vector<std::ptrdiff_t> offsets;
    for (int di = -k; di <= k; ++di) {
        for (int dj = -k; dj <= k; ++dj) {
            const int weight = (std::abs(di) + std::abs(dj) <= 1) ? 1 : 2;  // Fig. 5
            offsets.insert(offsets.end(), static_cast<std::size_t>(weight),
                           static_cast<std::ptrdiff_t>(di) * cols + dj);
        }
    }
    std::vector<float> samples;
    samples.reserve(offsets.size());
    for (const std::size_t idx : fills) {
        samples.clear();
        for (const std::ptrdiff_t off : offsets) {
            const auto at = static_cast<std::size_t>(static_cast<std::ptrdiff_t>(idx) + off);
            if (wm_empty == WmEmpty::kInclude || c[at] != 0.0F) {
                samples.push_back(h[at]);
            }
        }
        if (samples.empty()) {
            continue;  // nothing observed around: the cell keeps its value (0)
        }
        const auto mid = samples.begin() + static_cast<std::ptrdiff_t>((samples.size() - 1) / 2);
        std::nth_element(samples.begin(), mid, samples.end());
        out[idx] = *mid;
    }
}

// Window statistics of one output row, per column j in [k, cols - k).
struct RowStats {
    std::vector<float> col_c, col_h, col_max;  // vertical (2k+1) sum / sum / max
    std::vector<float> win_c, win_h, win_max;  // the whole window
    explicit RowStats(std::size_t n)
        : col_c(n), col_h(n), col_max(n), win_c(n), win_h(n), win_max(n) {}
};

void ColumnSum(const float* src, std::size_t stride, int span, std::size_t n, float* dst) {
    float* __restrict d = dst;
    std::memcpy(d, src, n * sizeof(float));
    for (int r = 1; r < span; ++r) {
        const float* __restrict row = src + static_cast<std::size_t>(r) * stride;
        for (std::size_t j = 0; j < n; ++j) {
            d[j] += row[j];
        }
    }
}

void ColumnMax(const float* src, std::size_t stride, int span, std::size_t n, float* dst) {
    float* __restrict d = dst;
    std::memcpy(d, src, n * sizeof(float));
    for (int r = 1; r < span; ++r) {
        const float* __restrict row = src + static_cast<std::size_t>(r) * stride;
        for (std::size_t j = 0; j < n; ++j) {
            d[j] = row[j] > d[j] ? row[j] : d[j];
        }
    }
}

void WindowSum(const float* src, int k, std::size_t n, float* dst) {
    const std::size_t w = n - 2 * static_cast<std::size_t>(k);  // outputs k .. n-k-1
    float* __restrict d = dst + k;
    std::memcpy(d, src, w * sizeof(float));
    for (int s = 1; s <= 2 * k; ++s) {
        const float* __restrict in = src + s;
        for (std::size_t j = 0; j < w; ++j) {
            d[j] += in[j];
        }
    }
}

void WindowMax(const float* src, int k, std::size_t n, float* dst) {
    const std::size_t w = n - 2 * static_cast<std::size_t>(k);
    float* __restrict d = dst + k;
    std::memcpy(d, src, w * sizeof(float));
    for (int s = 1; s <= 2 * k; ++s) {
        const float* __restrict in = src + s;
        for (std::size_t j = 0; j < w; ++j) {
            d[j] = in[j] > d[j] ? in[j] : d[j];
        }
    }
}

// k = 2, fused: each column's five values are read once and the three statistics kept in
// registers. Same order of additions as the generic path, so the same bits.
CASMAP_VECTOR_CLONES void RowStatsK2(
    const float* abs_h, const float* c, std::size_t cols, int top, RowStats& s) {
    const std::size_t off = static_cast<std::size_t>(top) * cols;
    const float* __restrict h0 = abs_h + off;
    const float* __restrict h1 = h0 + cols;
    const float* __restrict h2 = h1 + cols;
    const float* __restrict h3 = h2 + cols;
    const float* __restrict h4 = h3 + cols;
    const float* __restrict c0 = c + off;
    const float* __restrict c1 = c0 + cols;
    const float* __restrict c2 = c1 + cols;
    const float* __restrict c3 = c2 + cols;
    const float* __restrict c4 = c3 + cols;
    float* __restrict sc = s.col_c.data();
    float* __restrict sh = s.col_h.data();
    float* __restrict sm = s.col_max.data();
    for (std::size_t j = 0; j < cols; ++j) {
        sc[j] = (((c0[j] + c1[j]) + c2[j]) + c3[j]) + c4[j];
    }
    for (std::size_t j = 0; j < cols; ++j) {
        sh[j] = (((h0[j] + h1[j]) + h2[j]) + h3[j]) + h4[j];
    }
    for (std::size_t j = 0; j < cols; ++j) {
        float m = h0[j];
        m = h1[j] > m ? h1[j] : m;
        m = h2[j] > m ? h2[j] : m;
        m = h3[j] > m ? h3[j] : m;
        m = h4[j] > m ? h4[j] : m;
        sm[j] = m;
    }
    float* __restrict wc = s.win_c.data() + 2;
    float* __restrict wh = s.win_h.data() + 2;
    float* __restrict wm = s.win_max.data() + 2;
    const std::size_t n = cols - 4;
    for (std::size_t j = 0; j < n; ++j) {
        wc[j] = (((sc[j] + sc[j + 1]) + sc[j + 2]) + sc[j + 3]) + sc[j + 4];
    }
    for (std::size_t j = 0; j < n; ++j) {
        wh[j] = (((sh[j] + sh[j + 1]) + sh[j + 2]) + sh[j + 3]) + sh[j + 4];
    }
    for (std::size_t j = 0; j < n; ++j) {
        float m = sm[j];
        m = sm[j + 1] > m ? sm[j + 1] : m;
        m = sm[j + 2] > m ? sm[j + 2] : m;
        m = sm[j + 3] > m ? sm[j + 3] : m;
        m = sm[j + 4] > m ? sm[j + 4] : m;
        wm[j] = m;
    }
}

void ComputeRowStats(
    const float* abs_h, const float* c, std::size_t cols, int top, int k, RowStats& s) {
    if (k == 2) {
        RowStatsK2(abs_h, c, cols, top, s);
        return;
    }
    const int span = 2 * k + 1;
    const std::size_t off = static_cast<std::size_t>(top) * cols;
    ColumnSum(c + off, cols, span, cols, s.col_c.data());
    ColumnSum(abs_h + off, cols, span, cols, s.col_h.data());
    ColumnMax(abs_h + off, cols, span, cols, s.col_max.data());
    WindowSum(s.col_c.data(), k, cols, s.win_c.data());
    WindowSum(s.col_h.data(), k, cols, s.win_h.data());
    WindowMax(s.col_max.data(), k, cols, s.win_max.data());
}

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

CASMAP_VECTOR_CLONES void AbsInto(const float* __restrict src,
                                  std::size_t n,
                                  float* __restrict dst) {
    for (std::size_t i = 0; i < n; ++i) {
        dst[i] = std::abs(src[i]);
    }
}

// Eq. 7 for one row in the default form (sum g_s, no E term), written so the compiler can
// vectorise it: the class of each pixel from its window statistics; removed pixels set to 0.
struct RowInputs {
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
        y[j] = removed != 0 ? 0.0F : y[j];
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
        y[j] = removed ? 0.0F : y[j];
        cls[j] = removed ? std::uint8_t{1} : (fill ? std::uint8_t{2} : std::uint8_t{0});
    }
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
    const int rows = elevation.rows;
    const int cols = elevation.cols;
    const int k = p.k;
    out.elevation.rows = rows;
    out.elevation.cols = cols;
    out.elevation.data.assign(elevation.data.begin(), elevation.data.end());
    out.classes.rows = rows;
    out.classes.cols = cols;
    out.classes.data.assign(elevation.data.size(), static_cast<std::uint8_t>(PixelClass::kBorder));
    if (rows < 2 * k + 1 || cols < 2 * k + 1) {
        return;
    }
    const auto ucols = static_cast<std::size_t>(cols);
    const auto uk = static_cast<std::size_t>(k);
    // Scratch reused between calls on the same thread (no page faults on every call).
    thread_local std::vector<float> abs_h;
    thread_local std::vector<std::size_t> fills;
    abs_h.resize(elevation.data.size());
    AbsInto(elevation.data.data(), abs_h.size(), abs_h.data());
    const bool global = p.normalise == Normalise::kGlobal;
    const float global_max_h = global ? *std::max_element(abs_h.begin(), abs_h.end()) : 0.0F;
    const float global_max_c =
        global ? *std::max_element(certainty.data.begin(), certainty.data.end()) : 0.0F;
    const Thresholds t{static_cast<float>(p.EffectiveA()),
                       static_cast<float>(p.EffectiveG()),
                       static_cast<float>(p.h_sum_min),
                       global_max_h,
                       global_max_c,
                       p.normalise == Normalise::kGlobal};
    const bool general = p.gs_mode == GsMode::kVariance || p.e_term;
    const float* h = elevation.data.data();
    const float* c = certainty.data.data();
    float* y = out.elevation.data.data();
    RowStats s(ucols);
    fills.resize(elevation.data.size());
    std::size_t n_fills = 0;
    for (int i = k; i < rows - k; ++i) {
        ComputeRowStats(abs_h.data(), c, ucols, i - k, k, s);
        const std::size_t row_off = static_cast<std::size_t>(i) * ucols;
        std::uint8_t* cls = out.classes.data.data() + row_off;
        const RowInputs in{c + row_off, s.win_c.data(), s.win_h.data(), s.win_max.data()};
        if (general) {
            ClassifyRowGeneral(abs_h.data(), c, ucols, row_off, in, p, t, uk, ucols - uk,
                               y + row_off, cls);
        } else {
            if (t.global) {
                ClassifyRowSum<true>(in, t, uk, ucols - uk, y + row_off, cls);
            } else {
                ClassifyRowSum<false>(in, t, uk, ucols - uk, y + row_off, cls);
            }
        }
        for (std::size_t j = uk; j < ucols - uk; ++j) {  // branch-free append
            fills[n_fills] = row_off + j;
            n_fills += cls[j] == static_cast<std::uint8_t>(PixelClass::kFilled) ? 1U : 0U;
        }
    }
    fills.resize(n_fills);
    // The weighted median reads the unfiltered map h, so filling after the loop changes nothing.
    if (k == 2 && p.wm_empty == WmEmpty::kInclude) {
        FastSkeletonMedian(h, cols, fills, y);
    } else {
        GenericSkeletonMedian(h, c, cols, k, p.wm_empty, fills, y);
    }
}

FilterResult CasFilter(const core::MapF& elevation,
                       const core::MapF& certainty,
                       const CasParams& p) {
    FilterResult out;
    CasFilterInto(elevation, certainty, p, out);
    return out;
}

}  // namespace casmap::mapper
