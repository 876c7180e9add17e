#pragma once

// Detail of mapper/cas_filter.cpp: the window statistics of one output row of the CAS filter
// (Eq. 7-10's window sums of c and |h| and the window maximum of |h|) as separable column and
// row passes over plain float rows, which the compiler vectorises; k = 2 fused. Private to
// mapper (not installed).

#include <cstddef>
#include <vector>

// The hot row loops are compiled twice, for AVX2 and the baseline, and picked at load time
// (GCC function multi-versioning). Both run the same element-wise operations in the same
// order (no FMA, no reassociation), so the output is identical on every x86-64 machine.
#if defined(__x86_64__) && defined(__GNUC__) && !defined(__clang__)
#define CASMAP_VECTOR_CLONES __attribute__((target_clones("avx2", "default")))
#else
#define CASMAP_VECTOR_CLONES
#endif

namespace casmap::mapper::detail {

// Window statistics of one output row, per column j in [k, cols - k).
struct RowStats {
    std::vector<float> col_c, col_h, col_max;  // vertical (2k+1) sum / sum / max
    std::vector<float> win_c, win_h, win_max;  // the whole window
    explicit RowStats(std::size_t n)
        : col_c(n), col_h(n), col_max(n), win_c(n), win_h(n), win_max(n) {}
};

/// The window statistics of the output row whose window starts at input row `top`, from the
/// |h| map `abs_h` and the certainty map `c` (both `cols` wide).
void ComputeRowStats(
    const float* abs_h, const float* c, std::size_t cols, int top, int k, RowStats& s);

// The fused path's column statistics straight from the signed heights: |h| is taken on the
// fly (exact, so the same bits as ColumnStatsK2 on a precomputed |h| map), which saves the
// pass that wrote the |h| map.
void ColumnStatsK2Signed(const float* h, const float* c, std::size_t cols, int top, RowStats& s);

/// dst[i] = |src[i]| for i < n.
void AbsInto(const float* __restrict src, std::size_t n, float* __restrict dst);

}  // namespace casmap::mapper::detail
