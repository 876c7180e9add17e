// The four conventional filters of the paper's benchmark. Border handling for all of them:
// pixels beyond the map edge replicate the nearest edge pixel (OpenCV BORDER_REPLICATE), the
// mode cv::medianBlur uses internally; the paper states none.
#include <algorithm>
#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>
#include <vector>

#include "casmap/mapper/baseline_nan.hpp"
#include "casmap/mapper/filters.hpp"

namespace casmap::mapper {
namespace {

cv::Mat View(const core::MapF& map) {
    // OpenCV only reads through this header; the data stays owned by the Raster.
    return cv::Mat(map.rows, map.cols, CV_32F, const_cast<float*>(map.data.data()));
}

core::MapF FromMat(const cv::Mat& m) {
    core::MapF out(m.rows, m.cols);
    cv::Mat dst(m.rows, m.cols, CV_32F, out.data.data());
    m.convertTo(dst, CV_32F);
    return out;
}

// Median of the window with the centre repeated `center_weight` times (1 = plain median);
// edge pixels replicated.
core::MapF WeightedCentreMedian(const core::MapF& h, int window, int center_weight) {
    core::MapF out(h.rows, h.cols);
    const int k = window / 2;
    std::vector<float> samples;
    samples.reserve(static_cast<std::size_t>(window * window + center_weight));
    for (int i = 0; i < h.rows; ++i) {
        for (int j = 0; j < h.cols; ++j) {
            samples.clear();
            for (int di = -k; di <= k; ++di) {
                const int r = std::clamp(i + di, 0, h.rows - 1);
                for (int dj = -k; dj <= k; ++dj) {
                    samples.push_back(h.at(r, std::clamp(j + dj, 0, h.cols - 1)));
                }
            }
            for (int w = 1; w < center_weight; ++w) {
                samples.push_back(h.at(i, j));
            }
            const auto mid = samples.begin() + static_cast<std::ptrdiff_t>(samples.size() / 2);
            std::nth_element(samples.begin(), mid, samples.end());
            out.at(i, j) = *mid;
        }
    }
    return out;
}

// Local mean and variance over the window, in double, edges replicated.
void LocalMoments(const core::MapF& h, int window, cv::Mat& mean, cv::Mat& var) {
    cv::Mat src;
    View(h).convertTo(src, CV_64F);
    const cv::Size ksize(window, window);
    cv::boxFilter(src, mean, CV_64F, ksize, cv::Point(-1, -1), true, cv::BORDER_REPLICATE);
    cv::Mat sq;
    cv::boxFilter(src.mul(src), sq, CV_64F, ksize, cv::Point(-1, -1), true, cv::BORDER_REPLICATE);
    var = sq - mean.mul(mean);
}

}  // namespace

double WienerNoise(const core::MapF& elevation, const BaselineParams& params) {
    if (params.unknown == Unknown::kNaN) {
        return detail::NanWienerNoise(elevation, params);
    }
    if (params.noise) {
        return *params.noise;
    }
    if (elevation.data.empty()) {
        return 0.0;
    }
    cv::Mat mean;
    cv::Mat var;
    LocalMoments(elevation, params.window, mean, var);
    return cv::mean(var)[0];  // as scipy.signal.wiener does (with its own border)
}

core::MapF WienerFilter(const core::MapF& elevation, const BaselineParams& params) {
    if (params.unknown == Unknown::kNaN) {
        return detail::NanWiener(elevation, params);
    }
    if (elevation.data.empty()) {
        return elevation;
    }
    // Adaptive Wiener filter (Lim 1990; scipy.signal.wiener): y = m + (1 - n/v)(x - m) where the
    // local variance v exceeds the noise power n, else the local mean m.
    cv::Mat mean;
    cv::Mat var;
    LocalMoments(elevation, params.window, mean, var);
    const double noise = params.noise ? *params.noise : cv::mean(var)[0];
    core::MapF out(elevation.rows, elevation.cols);
    for (int i = 0; i < elevation.rows; ++i) {
        const double* m = mean.ptr<double>(i);
        const double* v = var.ptr<double>(i);
        for (int j = 0; j < elevation.cols; ++j) {
            const double x = static_cast<double>(elevation.at(i, j));
            // v <= n (not scipy's v < n) only differs when v == n, where both give m, and
            // avoids 0/0 on flat patches with zero noise.
            const double y = v[j] <= noise ? m[j] : (x - m[j]) * (1.0 - noise / v[j]) + m[j];
            out.at(i, j) = static_cast<float>(y);
        }
    }
    return out;
}

core::MapF AverageFilter(const core::MapF& elevation, const BaselineParams& params) {
    if (params.unknown == Unknown::kNaN) {
        return detail::NanAverage(elevation, params);
    }
    if (elevation.data.empty()) {
        return elevation;
    }
    cv::Mat dst;
    cv::blur(View(elevation), dst, cv::Size(params.window, params.window), cv::Point(-1, -1),
             cv::BORDER_REPLICATE);
    return FromMat(dst);
}

core::MapF MedianFilter(const core::MapF& elevation, const BaselineParams& params) {
    if (params.unknown == Unknown::kNaN) {
        return detail::NanWeightedMedian(elevation, params.window, 1);
    }
    if (elevation.data.empty()) {
        return elevation;
    }
    if (params.window <= 5) {
        // cv::medianBlur handles CV_32F only for 3x3 and 5x5; it replicates the border.
        cv::Mat dst;
        cv::medianBlur(View(elevation), dst, params.window);
        return FromMat(dst);
    }
    return WeightedCentreMedian(elevation, params.window, 1);
}

core::MapF CwmFilter(const core::MapF& elevation, const BaselineParams& params) {
    if (params.unknown == Unknown::kNaN) {
        return detail::NanWeightedMedian(elevation, params.window, params.center_weight);
    }
    return WeightedCentreMedian(elevation, params.window, params.center_weight);
}

}  // namespace casmap::mapper
