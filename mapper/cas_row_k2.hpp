#pragma once

// Detail of mapper/cas_filter.cpp: one output row of the CAS filter in its default form (k = 2,
// sum g_s, no E term), written with AVX2 intrinsics. Column statistics and the Eq. 7
// classification run in one pass per row, |h| is taken once per input value, and the filled
// pixels come out of the comparison masks directly. Every float operation is the one the
// portable path does, in the same order (adds left to right, max as `a > m ? a : m`, no FMA),
// so the output is bit-identical (tests/mapper/cas_filter_golden_test.cpp).

#include <cstddef>
#include <cstdint>

namespace casmap::mapper::detail {

/// Eq. 7-10 thresholds of the default form.
struct CasK2Thresholds {
    float A = 0.0F;
    float G = 0.0F;
    float h_sum_min = 0.0F;
    float global_max_h = 0.0F;  // used when `global`
    bool global = false;
};

/// True when this CPU runs the AVX2 row kernel.
[[nodiscard]] bool CasRowK2Available();

/// Classifies output row `row` (2 <= row < rows - 2) of the `cols`-wide maps `h` (elevation)
/// and `c` (certainty): writes y[2 .. cols-2) and cls[2 .. cols-2) of that row (0 kept, 1
/// removed, 2 filled) and appends the filled pixels' indices to fills[n_fills ..]; returns
/// the new count. `scratch` holds at least
/// 3 * cols + 24 floats. Requires CasRowK2Available().
std::size_t CasRowK2(const float* h,
                     const float* c,
                     std::size_t cols,
                     std::size_t row,
                     const CasK2Thresholds& t,
                     float* scratch,
                     float* y,
                     std::uint8_t* cls,
                     std::size_t* fills,
                     std::size_t n_fills);

}  // namespace casmap::mapper::detail
