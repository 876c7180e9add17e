#include "casmap/mapper/baseline_nan.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

namespace casmap::mapper::detail {
namespace {

constexpr float kNaN = std::numeric_limits<float>::quiet_NaN();

// Known values of the window around (i, j), clipped to the map.
void Known(const core::MapF& h, int i, int j, int k, std::vector<float>& out) {
    out.clear();
    for (int r = std::max(0, i - k); r <= std::min(h.rows - 1, i + k); ++r) {
        for (int c = std::max(0, j - k); c <= std::min(h.cols - 1, j + k); ++c) {
            if (!std::isnan(h.at(r, c))) {
                out.push_back(h.at(r, c));
            }
        }
    }
}

struct Moments {
    double mean = 0.0;
    double var = 0.0;
};

Moments LocalMoments(const std::vector<float>& v) {
    double s = 0.0;
    double s2 = 0.0;
    for (const float x : v) {
        s += static_cast<double>(x);
        s2 += static_cast<double>(x) * static_cast<double>(x);
    }
    const auto n = static_cast<double>(v.size());
    Moments m;
    m.mean = s / n;
    m.var = std::max(0.0, s2 / n - m.mean * m.mean);
    return m;
}

}  // namespace

core::MapF NanAverage(const core::MapF& h, const BaselineParams& p) {
    core::MapF out(h.rows, h.cols, kNaN);
    std::vector<float> v;
    for (int i = 0; i < h.rows; ++i) {
        for (int j = 0; j < h.cols; ++j) {
            if (!std::isnan(h.at(i, j))) {
                Known(h, i, j, p.window / 2, v);
                out.at(i, j) = static_cast<float>(LocalMoments(v).mean);
            }
        }
    }
    return out;
}

core::MapF NanWeightedMedian(const core::MapF& h, int window, int centre_weight) {
    core::MapF out(h.rows, h.cols, kNaN);
    std::vector<float> v;
    for (int i = 0; i < h.rows; ++i) {
        for (int j = 0; j < h.cols; ++j) {
            if (std::isnan(h.at(i, j))) {
                continue;
            }
            Known(h, i, j, window / 2, v);
            v.insert(v.end(), static_cast<std::size_t>(centre_weight - 1), h.at(i, j));
            std::sort(v.begin(), v.end());
            const std::size_t n = v.size();
            out.at(i, j) = n % 2 == 1 ? v[n / 2] : 0.5F * (v[n / 2 - 1] + v[n / 2]);
        }
    }
    return out;
}

double NanWienerNoise(const core::MapF& h, const BaselineParams& p) {
    if (p.noise) {
        return *p.noise;
    }
    std::vector<float> v;
    double sum = 0.0;
    std::size_t n = 0;
    for (int i = 0; i < h.rows; ++i) {
        for (int j = 0; j < h.cols; ++j) {
            if (!std::isnan(h.at(i, j))) {
                Known(h, i, j, p.window / 2, v);
                sum += LocalMoments(v).var;
                ++n;
            }
        }
    }
    return n > 0 ? sum / static_cast<double>(n) : 0.0;
}

core::MapF NanWiener(const core::MapF& h, const BaselineParams& p) {
    const double noise = NanWienerNoise(h, p);
    core::MapF out(h.rows, h.cols, kNaN);
    std::vector<float> v;
    for (int i = 0; i < h.rows; ++i) {
        for (int j = 0; j < h.cols; ++j) {
            const auto x = static_cast<double>(h.at(i, j));
            if (std::isnan(x)) {
                continue;
            }
            Known(h, i, j, p.window / 2, v);
            const Moments m = LocalMoments(v);
            const double y =
                m.var <= noise ? m.mean : (x - m.mean) * (1.0 - noise / m.var) + m.mean;
            out.at(i, j) = static_cast<float>(y);
        }
    }
    return out;
}

}  // namespace casmap::mapper::detail
