#include "casmap/mapper/cas_row_k2.hpp"

#include <array>
#include <bit>
#include <cmath>
#include <cstring>

#if defined(__x86_64__) && defined(__GNUC__)
#include <immintrin.h>
#define CASMAP_CAS_ROW_AVX2 1
#endif

namespace casmap::mapper::detail {
namespace {

// Byte i of kSpread[m] is 1 when bit i of m is set: eight class bytes from a lane mask.
constexpr std::array<std::uint64_t, 256> MakeSpread() {
    std::array<std::uint64_t, 256> t{};
    for (std::size_t m = 0; m < 256; ++m) {
        for (std::size_t i = 0; i < 8; ++i) {
            if ((m >> i) & 1U) {
                t[m] |= std::uint64_t{1} << (8 * i);
            }
        }
    }
    return t;
}
constexpr std::array<std::uint64_t, 256> kSpread = MakeSpread();

// The portable path's expressions for one column (ColumnStatsK2Signed in cas_filter.cpp).
inline void ColumnScalar(const float* h,
                         const float* c,
                         std::size_t cols,
                         std::size_t j,
                         float* sc,
                         float* sh,
                         float* sm) {
    const float c0 = c[j];
    const float c1 = c[j + cols];
    const float c2 = c[j + 2 * cols];
    const float c3 = c[j + 3 * cols];
    const float c4 = c[j + 4 * cols];
    sc[j] = (((c0 + c1) + c2) + c3) + c4;
    const float a0 = std::abs(h[j]);
    const float a1 = std::abs(h[j + cols]);
    const float a2 = std::abs(h[j + 2 * cols]);
    const float a3 = std::abs(h[j + 3 * cols]);
    const float a4 = std::abs(h[j + 4 * cols]);
    sh[j] = (((a0 + a1) + a2) + a3) + a4;
    float m = a0;
    m = a1 > m ? a1 : m;
    m = a2 > m ? a2 : m;
    m = a3 > m ? a3 : m;
    m = a4 > m ? a4 : m;
    sm[j] = m;
}

// The portable path's classification of one pixel (ClassifyRowSumK2 in cas_filter.cpp).
inline bool PixelScalar(const float* sc,
                        const float* sh,
                        const float* sm,
                        float hj,
                        float cj,
                        const CasK2Thresholds& t,
                        std::size_t j,
                        float* y,
                        std::uint8_t* cls) {
    const float wc = (((sc[j - 2] + sc[j - 1]) + sc[j]) + sc[j + 1]) + sc[j + 2];
    const float wh = (((sh[j - 2] + sh[j - 1]) + sh[j]) + sh[j + 1]) + sh[j + 2];
    float wm = sm[j - 2];
    wm = sm[j - 1] > wm ? sm[j - 1] : wm;
    wm = sm[j] > wm ? sm[j] : wm;
    wm = sm[j + 1] > wm ? sm[j + 1] : wm;
    wm = sm[j + 2] > wm ? sm[j + 2] : wm;
    const float max_h = t.global ? t.global_max_h : wm;
    const bool gs0 = (wh < t.h_sum_min * max_h) | ((max_h <= 0.0F) & (0.0F < t.h_sum_min));
    const bool gc0 = wc < t.G;
    const bool removed = (cj <= t.A) & gs0 & gc0;
    const bool fill = !gs0 & (cj == 0.0F);
    y[j] = removed ? 0.0F : hj;
    cls[j] = static_cast<std::uint8_t>(static_cast<unsigned>(removed) |
                                       (static_cast<unsigned>(fill) << 1U));
    return fill;
}

#ifdef CASMAP_CAS_ROW_AVX2
// a > m ? a : m, as maxps defines it (the second operand when either is NaN or they tie).
__attribute__((target("avx2"), always_inline)) inline __m256 MaxKeep(__m256 a, __m256 m) {
    return _mm256_max_ps(a, m);
}

template <bool kGlobal>
__attribute__((target("avx2"))) std::size_t RowAvx2(const float* h,
                                                    const float* c,
                                                    std::size_t cols,
                                                    std::size_t row,
                                                    const CasK2Thresholds& t,
                                                    float* scratch,
                                                    float* y,
                                                    std::uint8_t* cls,
                                                    std::size_t* fills,
                                                    std::size_t n_fills) {
    float* sc = scratch;
    float* sh = scratch + cols + 8;
    float* sm = scratch + 2 * cols + 16;
    const std::size_t top = (row - 2) * cols;
    const float* h0 = h + top;
    const float* c0 = c + top;
    const __m256 abs_mask = _mm256_castsi256_ps(_mm256_set1_epi32(0x7FFFFFFF));
    std::size_t j = 0;
    for (; j + 8 <= cols; j += 8) {
        const float* hp = h0 + j;
        const float* cp = c0 + j;
        const __m256 s = _mm256_add_ps(
            _mm256_add_ps(
                _mm256_add_ps(_mm256_add_ps(_mm256_loadu_ps(cp), _mm256_loadu_ps(cp + cols)),
                              _mm256_loadu_ps(cp + 2 * cols)),
                _mm256_loadu_ps(cp + 3 * cols)),
            _mm256_loadu_ps(cp + 4 * cols));
        const __m256 a0 = _mm256_and_ps(_mm256_loadu_ps(hp), abs_mask);
        const __m256 a1 = _mm256_and_ps(_mm256_loadu_ps(hp + cols), abs_mask);
        const __m256 a2 = _mm256_and_ps(_mm256_loadu_ps(hp + 2 * cols), abs_mask);
        const __m256 a3 = _mm256_and_ps(_mm256_loadu_ps(hp + 3 * cols), abs_mask);
        const __m256 a4 = _mm256_and_ps(_mm256_loadu_ps(hp + 4 * cols), abs_mask);
        const __m256 sum =
            _mm256_add_ps(_mm256_add_ps(_mm256_add_ps(_mm256_add_ps(a0, a1), a2), a3), a4);
        const __m256 m = MaxKeep(a4, MaxKeep(a3, MaxKeep(a2, MaxKeep(a1, a0))));
        _mm256_storeu_ps(sc + j, s);
        _mm256_storeu_ps(sh + j, sum);
        _mm256_storeu_ps(sm + j, m);
    }
    for (; j < cols; ++j) {
        ColumnScalar(h0, c0, cols, j, sc, sh, sm);
    }

    const std::size_t off = row * cols;
    const float* hr = h + off;
    const float* cr = c + off;
    float* yr = y + off;
    std::uint8_t* clr = cls + off;
    const __m256 A = _mm256_set1_ps(t.A);
    const __m256 G = _mm256_set1_ps(t.G);
    const __m256 h_sum_min = _mm256_set1_ps(t.h_sum_min);
    const __m256 global_max = _mm256_set1_ps(t.global_max_h);
    const __m256 zero = _mm256_setzero_ps();
    const __m256 empty_gs0 = 0.0F < t.h_sum_min ? _mm256_castsi256_ps(_mm256_set1_epi32(-1)) : zero;
    j = 2;
    for (; j + 10 <= cols; j += 8) {
        const __m256 wc =
            _mm256_add_ps(_mm256_add_ps(_mm256_add_ps(_mm256_add_ps(_mm256_loadu_ps(sc + j - 2),
                                                                    _mm256_loadu_ps(sc + j - 1)),
                                                      _mm256_loadu_ps(sc + j)),
                                        _mm256_loadu_ps(sc + j + 1)),
                          _mm256_loadu_ps(sc + j + 2));
        const __m256 wh =
            _mm256_add_ps(_mm256_add_ps(_mm256_add_ps(_mm256_add_ps(_mm256_loadu_ps(sh + j - 2),
                                                                    _mm256_loadu_ps(sh + j - 1)),
                                                      _mm256_loadu_ps(sh + j)),
                                        _mm256_loadu_ps(sh + j + 1)),
                          _mm256_loadu_ps(sh + j + 2));
        __m256 max_h = global_max;
        if constexpr (!kGlobal) {
            max_h = MaxKeep(
                _mm256_loadu_ps(sm + j + 2),
                MaxKeep(_mm256_loadu_ps(sm + j + 1),
                        MaxKeep(_mm256_loadu_ps(sm + j), MaxKeep(_mm256_loadu_ps(sm + j - 1),
                                                                 _mm256_loadu_ps(sm + j - 2)))));
        }
        const __m256 gs0 =
            _mm256_or_ps(_mm256_cmp_ps(wh, _mm256_mul_ps(h_sum_min, max_h), _CMP_LT_OQ),
                         _mm256_and_ps(_mm256_cmp_ps(max_h, zero, _CMP_LE_OQ), empty_gs0));
        const __m256 gc0 = _mm256_cmp_ps(wc, G, _CMP_LT_OQ);
        const __m256 cj = _mm256_loadu_ps(cr + j);
        const __m256 removed =
            _mm256_and_ps(_mm256_and_ps(_mm256_cmp_ps(cj, A, _CMP_LE_OQ), gs0), gc0);
        const __m256 fill = _mm256_andnot_ps(gs0, _mm256_cmp_ps(cj, zero, _CMP_EQ_OQ));
        _mm256_storeu_ps(yr + j, _mm256_andnot_ps(removed, _mm256_loadu_ps(hr + j)));
        const auto rm = static_cast<unsigned>(_mm256_movemask_ps(removed));
        auto fm = static_cast<unsigned>(_mm256_movemask_ps(fill));
        const std::uint64_t bytes = kSpread[rm] | (kSpread[fm] << 1U);
        std::memcpy(clr + j, &bytes, sizeof(bytes));
        while (fm != 0) {
            fills[n_fills++] = off + j + static_cast<std::size_t>(std::countr_zero(fm));
            fm &= fm - 1;
        }
    }
    for (; j + 2 < cols; ++j) {
        if (PixelScalar(sc, sh, sm, hr[j], cr[j], t, j, yr, clr)) {
            fills[n_fills++] = off + j;
        }
    }
    return n_fills;
}

#endif

}  // namespace

bool CasRowK2Available() {
#ifdef CASMAP_CAS_ROW_AVX2
    static const bool avx2 = __builtin_cpu_supports("avx2") != 0;
    return avx2;
#else
    return false;
#endif
}

std::size_t CasRowK2(const float* h,
                     const float* c,
                     std::size_t cols,
                     std::size_t row,
                     const CasK2Thresholds& t,
                     float* scratch,
                     float* y,
                     std::uint8_t* cls,
                     std::size_t* fills,
                     std::size_t n_fills) {
#ifdef CASMAP_CAS_ROW_AVX2
    return t.global ? RowAvx2<true>(h, c, cols, row, t, scratch, y, cls, fills, n_fills)
                    : RowAvx2<false>(h, c, cols, row, t, scratch, y, cls, fills, n_fills);
#else
    (void)h, (void)c, (void)cols, (void)row, (void)t, (void)scratch, (void)y, (void)cls,
        (void)fills;
    return n_fills;
#endif
}

}  // namespace casmap::mapper::detail
