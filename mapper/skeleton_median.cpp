// Weighted median of the CAS filter's Fig. 5 skeleton. For k = 2 with empty cells included
// (the paper's form) 8 pixels go through a min/max selection network at once (AVX2 or SSE,
// chosen at run time; both give the same result); otherwise the samples are collected and
// std::nth_element selects.
#include "casmap/mapper/skeleton_median.hpp"

#include <algorithm>
#include <array>
#include <cstdint>
#include <cstdlib>
#include <span>
#include <utility>
#include <vector>

#if defined(__x86_64__) && defined(__GNUC__)
#include <immintrin.h>
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

#if defined(__x86_64__) && defined(__GNUC__)
// The same networks as compile-time tables, so the AVX2 kernel below is straight-line code
// whose 25 vectors the compiler keeps in registers.
struct FixedNetwork {
    std::array<Comparator, 256> c{};
    std::size_t size = 0;
};

constexpr void AddComparator(FixedNetwork& n, int a, int b) { n.c[n.size++] = Comparator{a, b}; }

constexpr void FixedMerge(int lo, int hi, int r, FixedNetwork& out) {
    const int step = r * 2;
    if (step < hi - lo) {
        FixedMerge(lo, hi, step, out);
        FixedMerge(lo + r, hi, step, out);
        for (int i = lo + r; i < hi - r; i += step) {
            AddComparator(out, i, i + r);
        }
    } else {
        AddComparator(out, lo, lo + r);
    }
}

constexpr void FixedSort(int lo, int hi, FixedNetwork& out) {
    if (hi - lo >= 1) {
        const int mid = lo + (hi - lo) / 2;
        FixedSort(lo, mid, out);
        FixedSort(mid + 1, hi, out);
        FixedMerge(lo, hi, 1, out);
    }
}

// As SelectionNetwork, at compile time.
constexpr FixedNetwork FixedSelection(int n, int first, int last) {
    int size = 1;
    while (size < n) {
        size *= 2;
    }
    FixedNetwork all;
    FixedSort(0, size - 1, all);
    std::array<bool, 64> needed{};
    for (int w = first; w <= last; ++w) {
        needed[static_cast<std::size_t>(w)] = true;
    }
    FixedNetwork kept;
    for (std::size_t i = all.size; i-- > 0;) {
        const int a = all.c[i].first;
        const int b = all.c[i].second;
        if (b < n && (needed[static_cast<std::size_t>(a)] || needed[static_cast<std::size_t>(b)])) {
            needed[static_cast<std::size_t>(a)] = true;
            needed[static_cast<std::size_t>(b)] = true;
            AddComparator(kept, a, b);
        }
    }
    FixedNetwork out;
    for (std::size_t i = kept.size; i-- > 0;) {
        AddComparator(out, kept.c[i].first, kept.c[i].second);
    }
    return out;
}

inline constexpr FixedNetwork kOuterNet = FixedSelection(20, 8, 11);
inline constexpr FixedNetwork kInnerNet = FixedSelection(5, 0, 4);

__attribute__((target("avx2"), always_inline)) inline void MinMax(__m256& a, __m256& b) {
    const __m256 lo = _mm256_min_ps(a, b);
    b = _mm256_max_ps(a, b);
    a = lo;
}

template <const FixedNetwork& kNet, std::size_t... I>
__attribute__((target("avx2"), always_inline)) inline void ApplyFixed(__m256* v,
                                                                      std::index_sequence<I...>) {
    (MinMax(v[kNet.c[I].first], v[kNet.c[I].second]), ...);
}

// The selection and the closed form below on the 25 sample vectors of eight pixels.
__attribute__((target("avx2"), always_inline)) inline void SelectAvx2(__m256* o,
                                                                      __m256* in,
                                                                      float* result) {
    ApplyFixed<kOuterNet>(o, std::make_index_sequence<kOuterNet.size>{});
    ApplyFixed<kInnerNet>(in, std::make_index_sequence<kInnerNet.size>{});
    const __m256 t1 = _mm256_max_ps(o[10], in[0]);
    const __m256 t2 = _mm256_max_ps(o[9], in[2]);
    const __m256 t3 = _mm256_max_ps(o[8], in[4]);
    const __m256 m = _mm256_min_ps(_mm256_min_ps(o[11], t1), _mm256_min_ps(t2, t3));
    _mm256_storeu_ps(result, m);
}

// Eight filled pixels: gather their 25 samples one float at a time, then select.
__attribute__((target("avx2"))) void SkeletonBatchAvx2(const float* h,
                                                       const std::size_t* idx,
                                                       const std::ptrdiff_t* outer_off,
                                                       const std::ptrdiff_t* inner_off,
                                                       float* result) {
    __m256 o[kOuter];
    __m256 in[kInner];
    const float* p0 = h + idx[0];
    const float* p1 = h + idx[1];
    const float* p2 = h + idx[2];
    const float* p3 = h + idx[3];
    const float* p4 = h + idx[4];
    const float* p5 = h + idx[5];
    const float* p6 = h + idx[6];
    const float* p7 = h + idx[7];
    for (int s = 0; s < kOuter; ++s) {
        const std::ptrdiff_t d = outer_off[s];
        o[s] = _mm256_setr_ps(p0[d], p1[d], p2[d], p3[d], p4[d], p5[d], p6[d], p7[d]);
    }
    for (int s = 0; s < kInner; ++s) {
        const std::ptrdiff_t d = inner_off[s];
        in[s] = _mm256_setr_ps(p0[d], p1[d], p2[d], p3[d], p4[d], p5[d], p6[d], p7[d]);
    }
    SelectAvx2(o, in, result);
}

// The same samples in the same order, read as five 8-float rows per pixel (columns -2..+5 of
// each window row) and transposed: 40 vector loads and 105 shuffles instead of 200 scalar
// loads and 175 inserts. Every pixel needs columns up to +5 inside its row (col <= cols - 6).
__attribute__((target("avx2"), always_inline)) inline void SkeletonBatchRowsBody(
    const float* h, const std::size_t* idx, std::ptrdiff_t cols, float* result) {
    __m256 o[kOuter];
    __m256 in[kInner];
    int no = 0;
    int ni = 0;
    for (int di = -2; di <= 2; ++di) {
        const std::ptrdiff_t row = di * cols - 2;
        __m256 v[kLanes];
        for (int l = 0; l < kLanes; ++l) {
            v[l] = _mm256_loadu_ps(h + static_cast<std::ptrdiff_t>(idx[l]) + row);
        }
        // 8 x 8 transpose; t[q] lane l = pixel l's column q - 2 of this window row.
        const __m256 a0 = _mm256_unpacklo_ps(v[0], v[1]);
        const __m256 a1 = _mm256_unpackhi_ps(v[0], v[1]);
        const __m256 a2 = _mm256_unpacklo_ps(v[2], v[3]);
        const __m256 a3 = _mm256_unpackhi_ps(v[2], v[3]);
        const __m256 a4 = _mm256_unpacklo_ps(v[4], v[5]);
        const __m256 a5 = _mm256_unpackhi_ps(v[4], v[5]);
        const __m256 a6 = _mm256_unpacklo_ps(v[6], v[7]);
        const __m256 a7 = _mm256_unpackhi_ps(v[6], v[7]);
        const __m256 b0 = _mm256_shuffle_ps(a0, a2, 0x44);
        const __m256 b1 = _mm256_shuffle_ps(a0, a2, 0xEE);
        const __m256 b2 = _mm256_shuffle_ps(a1, a3, 0x44);
        const __m256 b3 = _mm256_shuffle_ps(a1, a3, 0xEE);
        const __m256 b4 = _mm256_shuffle_ps(a4, a6, 0x44);
        const __m256 b5 = _mm256_shuffle_ps(a4, a6, 0xEE);
        const __m256 b6 = _mm256_shuffle_ps(a5, a7, 0x44);
        const __m256 b7 = _mm256_shuffle_ps(a5, a7, 0xEE);
        const __m256 t[5] = {
            _mm256_permute2f128_ps(b0, b4, 0x20), _mm256_permute2f128_ps(b1, b5, 0x20),
            _mm256_permute2f128_ps(b2, b6, 0x20), _mm256_permute2f128_ps(b3, b7, 0x20),
            _mm256_permute2f128_ps(b0, b4, 0x31)};
        for (int dj = -2; dj <= 2; ++dj) {
            if (std::abs(di) + std::abs(dj) <= 1) {
                in[ni++] = t[dj + 2];
            } else {
                o[no++] = t[dj + 2];
            }
        }
    }
    SelectAvx2(o, in, result);
}

__attribute__((target("avx2"))) void SkeletonBatchRowsAvx2(const float* h,
                                                           const std::size_t* idx,
                                                           std::ptrdiff_t cols,
                                                           float* result) {
    SkeletonBatchRowsBody(h, idx, cols, result);
}

#endif

// The 23rd of the 45 Fig. 5 samples for k = 2, empty cells included. With O the 20 outer
// values sorted (each counted twice) and I the 5 inner ones sorted, the k-th of the union of
// two sorted lists is min_j max(D_(k-j), I_j); for k = 23 the non-dominated terms leave
// min(o12, max(o11, i1), max(o10, i3), max(o9, i5)) (1-based ranks).
void FastSkeletonMedian(const float* h, int cols, std::span<const std::size_t> fills, float* out) {
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
#if defined(__x86_64__) && defined(__GNUC__)
    if (UseAvx2()) {
        std::array<std::size_t, kLanes> idx{};
        std::array<float, kLanes> result{};
        const auto ucols = static_cast<std::size_t>(cols);
        std::size_t row_start = 0;  // of the row holding the batch's current pixel
        for (std::size_t b = 0; b < fills.size(); b += kLanes) {
            // fills ascend: the row starts advance monotonically.
            bool rows_fit = cols >= 6;
            for (std::size_t l = 0; l < kLanes; ++l) {
                idx[l] = fills[std::min(b + l, fills.size() - 1)];
                while (idx[l] >= row_start + ucols) {
                    row_start += ucols;
                }
                rows_fit = rows_fit && idx[l] - row_start + 6 <= ucols;
            }
            if (rows_fit) {
                SkeletonBatchRowsAvx2(h, idx.data(), cols, result.data());
            } else {
                SkeletonBatchAvx2(h, idx.data(), outer_off.data(), inner_off.data(), result.data());
            }
            for (std::size_t l = 0; l < kLanes && b + l < fills.size(); ++l) {
                out[fills[b + l]] = result[l];
            }
        }
        return;
    }
#endif
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
                           std::span<const std::size_t> fills,
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

}  // namespace

void SkeletonMedian(const float* h,
                    const float* c,
                    int cols,
                    int k,
                    WmEmpty wm_empty,
                    std::span<const std::size_t> fills,
                    float* out) {
    if (k == 2 && wm_empty == WmEmpty::kInclude) {
        FastSkeletonMedian(h, cols, fills, out);
    } else {
        GenericSkeletonMedian(h, c, cols, k, wm_empty, fills, out);
    }
}

}  // namespace casmap::mapper
