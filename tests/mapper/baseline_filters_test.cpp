// Baselines against scipy references (golden files: tests/data/mapper/make_filter_golden.py)
// and against brute-force definitions.
#include <gtest/gtest.h>

#include <algorithm>
#include <fstream>
#include <random>
#include <string>
#include <vector>

#include "casmap/mapper/filters.hpp"

namespace casmap::mapper {
namespace {

constexpr int kRows = 24;
constexpr int kCols = 30;

core::MapF LoadGolden(const std::string& name) {
    const std::string path = std::string(CASMAP_SOURCE_DIR) + "/tests/data/mapper/" + name;
    std::ifstream in(path, std::ios::binary);
    EXPECT_TRUE(in.good()) << path;
    core::MapF map(kRows, kCols);
    in.read(reinterpret_cast<char*>(map.data.data()),
            static_cast<std::streamsize>(map.data.size() * sizeof(float)));
    EXPECT_TRUE(in.good()) << path << " is shorter than " << kRows << "x" << kCols;
    return map;
}

TEST(MedianFilter, EqualsScipyMedianEverywhere) {
    // scipy mode='nearest' replicates the edge like OpenCV, so even the border matches.
    const core::MapF out = MedianFilter(LoadGolden("filter_input.f32"), BaselineParams{});
    const core::MapF ref = LoadGolden("median5.f32");
    for (std::size_t i = 0; i < ref.data.size(); ++i) {
        ASSERT_EQ(out.data[i], ref.data[i]) << "pixel " << i;
    }
}

TEST(MedianFilter, GenericPathEqualsOpenCvPath) {
    // The 7x7 path is the CWM code with weight 1; check it against OpenCV at 5x5 by forcing it.
    const core::MapF in = LoadGolden("filter_input.f32");
    BaselineParams p;
    p.center_weight = 1;
    const core::MapF generic = CwmFilter(in, p);
    const core::MapF opencv = MedianFilter(in, p);
    EXPECT_EQ(generic.data, opencv.data);
}

TEST(AverageFilter, EqualsScipyUniformFilter) {
    const core::MapF out = AverageFilter(LoadGolden("filter_input.f32"), BaselineParams{});
    const core::MapF ref = LoadGolden("average5.f32");
    for (std::size_t i = 0; i < ref.data.size(); ++i) {
        ASSERT_NEAR(out.data[i], ref.data[i], 2e-6F) << "pixel " << i;
    }
}

TEST(WienerFilter, EqualsScipyWienerOnInterior) {
    BaselineParams p;
    p.noise = 0.001;
    const core::MapF out = WienerFilter(LoadGolden("filter_input.f32"), p);
    const core::MapF ref = LoadGolden("wiener5_n001.f32");
    // scipy pads with zeros, we replicate: compare where the 5x5 window fits.
    for (int i = 2; i < kRows - 2; ++i) {
        for (int j = 2; j < kCols - 2; ++j) {
            ASSERT_NEAR(out.at(i, j), ref.at(i, j), 1e-6F) << i << "," << j;
        }
    }
}

TEST(WienerFilter, DefaultNoiseIsMeanLocalVariance) {
    const core::MapF in = LoadGolden("filter_input.f32");
    const double noise = WienerNoise(in, BaselineParams{});
    // Brute-force mean of the replicated-border local variances.
    double sum = 0.0;
    for (int i = 0; i < kRows; ++i) {
        for (int j = 0; j < kCols; ++j) {
            double s = 0.0;
            double s2 = 0.0;
            for (int di = -2; di <= 2; ++di) {
                for (int dj = -2; dj <= 2; ++dj) {
                    const double v =
                        in.at(std::clamp(i + di, 0, kRows - 1), std::clamp(j + dj, 0, kCols - 1));
                    s += v;
                    s2 += v * v;
                }
            }
            sum += s2 / 25.0 - (s / 25.0) * (s / 25.0);
        }
    }
    EXPECT_NEAR(noise, sum / (kRows * kCols), 1e-9);
    BaselineParams given;
    given.noise = noise;
    EXPECT_EQ(WienerFilter(in, BaselineParams{}).data, WienerFilter(in, given).data);
}

TEST(CwmFilter, EqualsMedianWithCentreRepeated) {
    const unsigned seed = 7;
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> u(-1.0F, 1.0F);
    core::MapF in(12, 13);
    for (float& v : in.data) {
        v = u(rng);
    }
    for (const int w : {1, 3, 5, 9}) {
        BaselineParams p;
        p.center_weight = w;
        const core::MapF out = CwmFilter(in, p);
        for (int i = 2; i < in.rows - 2; ++i) {
            for (int j = 2; j < in.cols - 2; ++j) {
                std::vector<float> s;
                for (int di = -2; di <= 2; ++di) {
                    for (int dj = -2; dj <= 2; ++dj) {
                        s.push_back(in.at(i + di, j + dj));
                    }
                }
                s.insert(s.end(), static_cast<std::size_t>(w - 1), in.at(i, j));
                std::sort(s.begin(), s.end());
                ASSERT_EQ(out.at(i, j), s[s.size() / 2])
                    << "seed " << seed << " weight " << w << " at " << i << "," << j;
            }
        }
    }
}

TEST(CwmFilter, LargeCentreWeightKeepsEveryPixel) {
    core::MapF in(7, 7, 0.0F);
    in.at(3, 3) = 1.0F;  // an isolated spike: the plain median removes it
    BaselineParams p;
    p.center_weight = 25;  // 25 + 24 samples: the centre is always the median
    EXPECT_EQ(CwmFilter(in, p).at(3, 3), 1.0F);
    EXPECT_EQ(MedianFilter(in, BaselineParams{}).at(3, 3), 0.0F);
}

TEST(RunFilter, BaselinesReturnNoClasses) {
    const core::MapF in = LoadGolden("filter_input.f32");
    for (const FilterMethod m : {FilterMethod::kWiener, FilterMethod::kAverage,
                                 FilterMethod::kMedian, FilterMethod::kCwm}) {
        const FilterResult r = RunFilter(m, in, core::MapF{}, FilterParams{});
        EXPECT_TRUE(r.elevation.SameShape(in)) << ToString(m);
        EXPECT_EQ(r.classes.data.size(), 0U) << ToString(m);
    }
}

}  // namespace
}  // namespace casmap::mapper
