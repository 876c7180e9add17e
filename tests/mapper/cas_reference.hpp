#pragma once

// A plain scalar CAS filter (Eq. 7-10, the paper's forms and the optional ones) for tests:
// one pixel at a time, no vectorisation, the same order of float operations as
// mapper/cas_filter.cpp (column sums of the window first, each a left fold over rows
// top-down, then a left fold of those over columns left to right), so it gives the same bits.

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

#include "casmap/mapper/filters.hpp"

namespace casmap::mapper::test {

inline float RefWindowSum(const std::vector<float>& x, int cols, int i, int j, int k) {
    float total = 0.0F;
    for (int dj = -k; dj <= k; ++dj) {
        float col = x[static_cast<std::size_t>((i - k) * cols + j + dj)];
        for (int di = -k + 1; di <= k; ++di) {
            col += x[static_cast<std::size_t>((i + di) * cols + j + dj)];
        }
        total = dj == -k ? col : total + col;
    }
    return total;
}

inline float RefWindowMax(const std::vector<float>& x, int cols, int i, int j, int k) {
    float m = 0.0F;
    for (int di = -k; di <= k; ++di) {
        for (int dj = -k; dj <= k; ++dj) {
            m = std::max(m, x[static_cast<std::size_t>((i + di) * cols + j + dj)]);
        }
    }
    return m;
}

// Population variance of x / norm over the window (0 when norm <= 0), summed row by row.
inline float RefVariance(const std::vector<float>& x, int cols, int i, int j, int k, float norm) {
    if (norm <= 0.0F) {
        return 0.0F;
    }
    float sum = 0.0F;
    float sum2 = 0.0F;
    for (int di = -k; di <= k; ++di) {
        for (int dj = -k; dj <= k; ++dj) {
            const float v = x[static_cast<std::size_t>((i + di) * cols + j + dj)] / norm;
            sum += v;
            sum2 += v * v;
        }
    }
    const auto n = static_cast<float>((2 * k + 1) * (2 * k + 1));
    const float mean = sum / n;
    return sum2 / n - mean * mean;
}

// Lower median of the Fig. 5 skeleton's samples (weight 1 on the cross, 2 elsewhere).
inline bool RefSkeletonMedian(
    const core::MapF& h, const core::MapF& c, int i, int j, const CasParams& p, float& out) {
    std::vector<float> s;
    for (int di = -p.k; di <= p.k; ++di) {
        for (int dj = -p.k; dj <= p.k; ++dj) {
            if (p.wm_empty == WmEmpty::kSkip && c.at(i + di, j + dj) == 0.0F) {
                continue;
            }
            const int w = std::abs(di) + std::abs(dj) <= 1 ? 1 : 2;
            s.insert(s.end(), static_cast<std::size_t>(w), h.at(i + di, j + dj));
        }
    }
    if (s.empty()) {
        return false;
    }
    std::sort(s.begin(), s.end());
    out = s[(s.size() - 1) / 2];
    return true;
}

inline FilterResult ReferenceCas(const core::MapF& h, const core::MapF& c, const CasParams& p) {
    FilterResult r;
    r.elevation = h;
    r.classes = ClassMap(h.rows, h.cols, static_cast<std::uint8_t>(PixelClass::kBorder));
    std::vector<float> abs_h(h.data.size());
    for (std::size_t n = 0; n < abs_h.size(); ++n) {
        abs_h[n] = std::abs(h.data[n]);
    }
    const bool global = p.normalise == Normalise::kGlobal;
    const float max_h_all = *std::max_element(abs_h.begin(), abs_h.end());
    const float max_c_all = *std::max_element(c.data.begin(), c.data.end());
    const auto A = static_cast<float>(p.EffectiveA());
    const auto G = static_cast<float>(p.EffectiveG());
    const auto h_sum_min = static_cast<float>(p.h_sum_min);
    const int k = p.k;
    for (int i = k; i < h.rows - k; ++i) {
        for (int j = k; j < h.cols - k; ++j) {
            const float max_h = global ? max_h_all : RefWindowMax(abs_h, h.cols, i, j, k);
            bool gs0 = max_h > 0.0F ? RefWindowSum(abs_h, h.cols, i, j, k) < h_sum_min * max_h
                                    : 0.0F < h_sum_min;
            if (p.gs_mode == GsMode::kVariance) {
                gs0 = RefVariance(abs_h, h.cols, i, j, k, max_h) > static_cast<float>(p.B);
            }
            bool gc0 = RefWindowSum(c.data, h.cols, i, j, k) < G;
            if (p.e_term && !gc0) {
                const float max_c = global ? max_c_all : RefWindowMax(c.data, h.cols, i, j, k);
                gc0 = RefVariance(c.data, h.cols, i, j, k, max_c) > static_cast<float>(p.E);
            }
            const float cij = c.at(i, j);
            auto cls = PixelClass::kUntouched;
            if (cij <= A && gs0 && gc0) {
                cls = PixelClass::kRemoved;
                r.elevation.at(i, j) = 0.0F;
            } else if (!gs0 && cij == 0.0F) {
                cls = PixelClass::kFilled;
                float m = 0.0F;
                if (RefSkeletonMedian(h, c, i, j, p, m)) {
                    r.elevation.at(i, j) = m;
                }
            }
            r.classes.at(i, j) = static_cast<std::uint8_t>(cls);
        }
    }
    return r;
}

}  // namespace casmap::mapper::test
