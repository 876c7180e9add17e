// The waveform's exp (sensor_models/gaussian_terms.hpp) against std::exp: within 2 ulp over
// its whole domain [-708, 0], and GaussianTerms (whichever vector clone this CPU runs) agrees
// with the scalar closed form to the same accuracy, and bit for bit with the scalar
// ExpNonPositive (run files must not depend on the CPU's clone).
#include "casmap/sensor_models/gaussian_terms.hpp"

#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>
#include <random>
#include <string>
#include <vector>

namespace casmap::sensor_models {
namespace {

// |a - b| in units of b's ulp.
double Ulps(double a, double b) {
    const double ulp = std::nextafter(b, std::numeric_limits<double>::infinity()) - b;
    return std::abs(a - b) / ulp;
}

// One random pulse: 1..kMaxSubrays echoes at 0.5-8 m with energies 1e-3..1e3, a width sigma
// of 1.5-51.5 mm (c = 1 / (2 sigma^2)) and a waveform position x within +-1 sigma of an echo.
struct Pulse {
    std::vector<EchoSample> samples;
    double c = 0.0;
    double x = 0.0;
};

Pulse RandomPulse(std::mt19937_64& gen) {
    std::uniform_real_distribution<double> range(0.5, 8.0);
    std::uniform_real_distribution<double> energy(1e-3, 1e3);
    Pulse p;
    p.samples.resize(1 + gen() % kMaxSubrays);
    for (auto& e : p.samples) {
        e = {range(gen), energy(gen)};
    }
    const double sigma = 0.0015 + 0.05 * static_cast<double>(gen() % 100) / 100.0;
    p.c = 0.5 / (sigma * sigma);
    p.x = p.samples[gen() % p.samples.size()].range_m +
          (static_cast<double>(gen() % 200) - 100.0) * 0.01 * sigma;
    return p;
}

TEST(GaussianTerms, ExpIsWithinTwoUlpOnItsDomain) {
    const std::uint64_t seed = 20261128;
    SCOPED_TRACE("seed " + std::to_string(seed));
    std::mt19937_64 gen(seed);
    std::uniform_real_distribution<double> wide(-708.0, 0.0);
    std::uniform_real_distribution<double> near(-18.0, 0.0);  // the waveform's cutoff
    double worst = 0.0;
    for (int i = 0; i < 2'000'000; ++i) {
        const double t = i % 2 == 0 ? wide(gen) : near(gen);
        worst = std::max(worst, Ulps(ExpNonPositive(t), std::exp(t)));
    }
    // Exact points: 0, the ends, multiples of ln 2 / 2 (reduction edges), tiny exponents.
    for (const double t : {0.0, -0.0, -708.0, -1e-300, -1e-17, -0.34657359027997264,
                           -0.34657359027997267, -0.6931471805599453, -18.0, -745.0 / 1.052}) {
        if (t >= -708.0) {
            worst = std::max(worst, Ulps(ExpNonPositive(t), std::exp(t)));
        }
    }
    EXPECT_LE(worst, 2.0);
    EXPECT_EQ(ExpNonPositive(0.0), 1.0);
}

TEST(GaussianTerms, TermsMatchTheClosedForm) {
    std::mt19937_64 gen(7);
    for (int trial = 0; trial < 2000; ++trial) {
        const Pulse p = RandomPulse(gen);
        const std::vector<EchoSample>& s = p.samples;
        const std::size_t n = s.size();
        const double c = p.c;
        const double x = p.x;
        std::vector<double> term(n);
        GaussianTerms(s.data(), n, x, c, term.data());
        for (std::size_t i = 0; i < n; ++i) {
            const double d = x - s[i].range_m;
            if (d * d * c > 708.0) {
                continue;  // outside the domain (the waveform never asks: cutoff 6 sigma)
            }
            const double exact = s[i].energy * std::exp(-d * d * c);
            EXPECT_LE(Ulps(term[i], exact), 3.0) << "trial " << trial << " hit " << i;
        }
    }
}

TEST(GaussianTerms, EveryCloneGivesTheScalarBits) {
    // This file is built without FMA contraction (tests/sensor_models/CMakeLists.txt), as the
    // library is: the clone this CPU runs (AVX-512, AVX2 + FMA or SSE2) must reproduce the
    // scalar formula exactly, else a run file's ranges would depend on the CPU.
    const std::uint64_t seed = 20261129;
    SCOPED_TRACE("seed " + std::to_string(seed));
    std::mt19937_64 gen(seed);
    std::size_t differing = 0;
    for (int trial = 0; trial < 2000; ++trial) {
        const Pulse p = RandomPulse(gen);
        const std::vector<EchoSample>& s = p.samples;
        const std::size_t n = s.size();
        const double c = p.c;
        const double x = p.x;
        std::vector<double> term(n);
        GaussianTerms(s.data(), n, x, c, term.data());
        for (std::size_t i = 0; i < n; ++i) {
            const double d = x - s[i].range_m;
            const double t = -d * d * c;
            if (t < -708.0) {
                continue;  // outside the domain (the waveform never asks: cutoff 6 sigma)
            }
            const double scalar = s[i].energy * ExpNonPositive(t);
            differing +=
                std::bit_cast<std::uint64_t>(term[i]) != std::bit_cast<std::uint64_t>(scalar);
        }
    }
    EXPECT_EQ(differing, 0U);
}

}  // namespace
}  // namespace casmap::sensor_models
