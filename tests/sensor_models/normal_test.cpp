// PulseRng::Normal (the ziggurat of scripts/gen_ziggurat_tables.py) against the standard normal's
// closed forms: moments, the CDF at many points (erf), the tails beyond 3 and 4 sigma and beyond
// the ziggurat's base r (the tail sampler), symmetry, and a Kolmogorov-Smirnov distance. Fixed
// seeds (printed), so the test is deterministic; every bound is 5 standard errors.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

#include "casmap/sensor_models/lms200_model.hpp"

namespace casmap::sensor_models {
namespace {

constexpr std::uint64_t kSeed = 20261128;
constexpr std::size_t kDraws = 4'000'000;
constexpr std::size_t kPerStream = 1000;  // like the model: many short per-pulse streams

double Phi(double x) { return 0.5 * std::erfc(-x / std::sqrt(2.0)); }

// kDraws normals from streams (seed, scan k, beam 7, stream 2), kPerStream each.
const std::vector<double>& Draws() {
    static const std::vector<double> draws = [] {
        std::vector<double> v;
        v.reserve(kDraws);
        for (std::uint64_t k = 0; v.size() < kDraws; ++k) {
            PulseRng rng(kSeed, k, 7, 2);
            for (std::size_t i = 0; i < kPerStream; ++i) {
                v.push_back(rng.Normal());
            }
        }
        return v;
    }();
    return draws;
}

TEST(Normal, MomentsMatchTheStandardNormal) {
    SCOPED_TRACE("seed " + std::to_string(kSeed));
    const auto& z = Draws();
    const double n = static_cast<double>(z.size());
    double m1 = 0;
    double m2 = 0;
    double m3 = 0;
    double m4 = 0;
    for (const double x : z) {
        ASSERT_TRUE(std::isfinite(x));
        m1 += x;
        m2 += x * x;
        m3 += x * x * x;
        m4 += x * x * x * x;
    }
    m1 /= n;
    m2 /= n;
    m3 /= n;
    m4 /= n;
    EXPECT_NEAR(m1, 0.0, 5.0 / std::sqrt(n));
    EXPECT_NEAR(m2, 1.0, 5.0 * std::sqrt(2.0 / n));
    EXPECT_NEAR(m3, 0.0, 5.0 * std::sqrt(15.0 / n));  // var(z^3) = 15
    EXPECT_NEAR(m4, 3.0, 5.0 * std::sqrt(96.0 / n));  // var(z^4) = 105 - 9
}

TEST(Normal, CdfMatchesErfAtManyPoints) {
    SCOPED_TRACE("seed " + std::to_string(kSeed));
    std::vector<double> z = Draws();
    std::sort(z.begin(), z.end());
    const double n = static_cast<double>(z.size());
    // Every 0.05 from -4.5 to 4.5, which crosses many of the 256 layer edges.
    for (int k = -90; k <= 90; ++k) {
        const double x = 0.05 * k;
        const double p = Phi(x);
        const double empirical =
            static_cast<double>(std::lower_bound(z.begin(), z.end(), x) - z.begin()) / n;
        EXPECT_NEAR(empirical, p, 5.0 * std::sqrt(p * (1.0 - p) / n) + 1.0 / n) << "x = " << x;
    }
    // Kolmogorov-Smirnov: sup |F_n - Phi| (5 sigma of sqrt(n) D is far beyond 1.95, p = 0.001).
    double d = 0.0;
    for (std::size_t i = 0; i < z.size(); i += 7) {  // every 7th order statistic suffices
        const double p = Phi(z[i]);
        d = std::max({d, std::abs(static_cast<double>(i + 1) / n - p),
                      std::abs(static_cast<double>(i) / n - p)});
    }
    EXPECT_LT(std::sqrt(n) * d, 1.95);
}

TEST(Normal, TailsBeyondThreeAndFourSigmaAndTheBase) {
    SCOPED_TRACE("seed " + std::to_string(kSeed));
    const auto& z = Draws();
    const double n = static_cast<double>(z.size());
    // r = 3.6541528853610088: beyond it every value comes from the tail sampler.
    for (const double t : {2.0, 3.0, 3.6541528853610088, 4.0, 4.5}) {
        const double p = 2.0 * Phi(-t);
        const auto count = static_cast<double>(
            std::count_if(z.begin(), z.end(), [t](double x) { return std::abs(x) > t; }));
        const double expected = p * n;
        EXPECT_NEAR(count, expected, 5.0 * std::sqrt(expected) + 1.0) << "|z| > " << t;
        const auto upper =
            static_cast<double>(std::count_if(z.begin(), z.end(), [t](double x) { return x > t; }));
        EXPECT_NEAR(upper, expected / 2.0, 5.0 * std::sqrt(expected / 2.0) + 1.0) << "z > " << t;
    }
    const auto negative =
        static_cast<double>(std::count_if(z.begin(), z.end(), [](double x) { return x < 0.0; }));
    EXPECT_NEAR(negative / n, 0.5, 5.0 * 0.5 / std::sqrt(n));
}

TEST(Normal, TheTailSamplerFollowsTheConditionalTail) {
    // Beyond r only the tail sampler draws: P(|z| > t | |z| > r) = Phi(-t) / Phi(-r). 64 M draws
    // give ~16500 tail values (an exponential tail without the rejection step would put 28 %
    // instead of 24.5 % beyond 4: 10 standard errors).
    constexpr double kR = 3.6541528853610088;
    const std::uint64_t seed = kSeed + 1;
    SCOPED_TRACE("seed " + std::to_string(seed));
    std::vector<double> tail;
    for (std::uint64_t k = 0; k < 64'000; ++k) {
        PulseRng rng(seed, k, 1, 2);
        for (int i = 0; i < 1000; ++i) {
            const double x = std::abs(rng.Normal());
            if (x > kR) {
                tail.push_back(x);
            }
        }
    }
    const double n = static_cast<double>(tail.size());
    EXPECT_NEAR(n, 64e6 * 2.0 * Phi(-kR), 5.0 * std::sqrt(64e6 * 2.0 * Phi(-kR)));
    for (const double t : {3.7, 3.8, 3.9, 4.0, 4.2, 4.5, 5.0}) {
        const double p = Phi(-t) / Phi(-kR);
        const auto count = static_cast<double>(
            std::count_if(tail.begin(), tail.end(), [t](double x) { return x > t; }));
        EXPECT_NEAR(count / n, p, 5.0 * std::sqrt(p * (1.0 - p) / n) + 1.0 / n) << "t = " << t;
    }
}

TEST(Normal, SameStreamSameDrawsOtherStreamOthers) {
    PulseRng a(kSeed, 3, 5, 2);
    PulseRng b(kSeed, 3, 5, 2);
    PulseRng c(kSeed, 3, 6, 2);
    int differ = 0;
    for (int i = 0; i < 1000; ++i) {
        const double x = a.Normal();
        ASSERT_EQ(x, b.Normal());
        differ += x != c.Normal() ? 1 : 0;
    }
    EXPECT_EQ(differ, 1000);
}

}  // namespace
}  // namespace casmap::sensor_models
