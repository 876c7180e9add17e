#include "casmap/mapper/cas_window_stats.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>

namespace casmap::mapper::detail {
namespace {

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
CASMAP_VECTOR_CLONES void ColumnStatsK2(
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
}

CASMAP_VECTOR_CLONES void RowStatsK2(
    const float* abs_h, const float* c, std::size_t cols, int top, RowStats& s) {
    ColumnStatsK2(abs_h, c, cols, top, s);
    const float* __restrict sc = s.col_c.data();
    const float* __restrict sh = s.col_h.data();
    const float* __restrict sm = s.col_max.data();
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

}  // namespace

CASMAP_VECTOR_CLONES void ColumnStatsK2Signed(
    const float* h, const float* c, std::size_t cols, int top, RowStats& s) {
    const std::size_t off = static_cast<std::size_t>(top) * cols;
    const float* __restrict h0 = h + off;
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
        sh[j] = (((std::abs(h0[j]) + std::abs(h1[j])) + std::abs(h2[j])) + std::abs(h3[j])) +
                std::abs(h4[j]);
    }
    for (std::size_t j = 0; j < cols; ++j) {
        float m = std::abs(h0[j]);
        const float a1 = std::abs(h1[j]);
        const float a2 = std::abs(h2[j]);
        const float a3 = std::abs(h3[j]);
        const float a4 = std::abs(h4[j]);
        m = a1 > m ? a1 : m;
        m = a2 > m ? a2 : m;
        m = a3 > m ? a3 : m;
        m = a4 > m ? a4 : m;
        sm[j] = m;
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

CASMAP_VECTOR_CLONES void AbsInto(const float* __restrict src,
                                  std::size_t n,
                                  float* __restrict dst) {
    for (std::size_t i = 0; i < n; ++i) {
        dst[i] = std::abs(src[i]);
    }
}

}  // namespace casmap::mapper::detail
