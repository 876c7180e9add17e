#pragma once

#include <cstddef>
#include <span>
#include <vector>

#include "casmap/mapper/filter_params.hpp"

namespace casmap::mapper {

/// The weighted median of Fig. 5 (weight 1 on the centre and its four direct neighbours, 2 on
/// the rest of the (2k+1)^2 window; 45 samples for k = 2, output the 23rd) for every index in
/// `fills`: out[idx] = median around h[idx]. h and c are row-major maps `cols` wide and every
/// index lies at least k cells from the border. With WmEmpty::kSkip, cells with c = 0 are left
/// out (lower median of the rest; a cell with none keeps out[idx]).
void SkeletonMedian(const float* h,
                    const float* c,
                    int cols,
                    int k,
                    WmEmpty wm_empty,
                    std::span<const std::size_t> fills,
                    float* out);

}  // namespace casmap::mapper
