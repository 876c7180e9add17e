#pragma once

// The waveform's Gaussians (return formation, docs/sensor-model.md): a branch-free exp for
// non-positive exponents and the per-hit loop that uses it. Private to sensor_models (and its
// tests).

#include <bit>
#include <cstddef>
#include <cstdint>

#include "casmap/sensor_models/lms200_model.hpp"

namespace casmap::sensor_models {

// exp(t) for -708 <= t <= 0 (callers clamp), within 2 ulp of the exact value: t = k ln 2 + r,
// |r| <= ln 2 / 2 (Cody-Waite, ln 2 split in two so k ln 2_hi is exact), e^r by its Taylor
// polynomial of degree 13 (truncation < 5e-18), times 2^k built in the exponent bits. Inline
// and branch-free, so loops over a pulse's hits vectorise; the waveform's Gaussians use it
// (docs/sensor-model.md, return formation; its error is ~1e-16 of a value whose root the
// waveform search locates to 5e-5 m, far below the float rounding of a stored range).
[[nodiscard]] inline double ExpNonPositive(double t) {
    constexpr double kLog2e = 1.4426950408889634074;
    constexpr double kLn2Hi = 0x1.62e42fee00000p-1;
    constexpr double kLn2Lo = 0x1.a39ef35793c76p-33;
    constexpr double kShift = 0x1.8p52;  // adding it rounds to an integer held in the low bits
    const double kd = t * kLog2e + kShift;
    const double k = kd - kShift;
    const double r = (t - k * kLn2Hi) - k * kLn2Lo;
    double p = 1.0 / 6227020800.0;  // 1 / 13!
    p = p * r + 1.0 / 479001600.0;
    p = p * r + 1.0 / 39916800.0;
    p = p * r + 1.0 / 3628800.0;
    p = p * r + 1.0 / 362880.0;
    p = p * r + 1.0 / 40320.0;
    p = p * r + 1.0 / 5040.0;
    p = p * r + 1.0 / 720.0;
    p = p * r + 1.0 / 120.0;
    p = p * r + 1.0 / 24.0;
    p = p * r + 1.0 / 6.0;
    p = p * r + 0.5;
    p = p * r + 1.0;
    p = p * r + 1.0;
    // The low bits of kd hold k (two's complement); + 1023, shifted into the exponent field.
    const auto scale = std::bit_cast<double>((std::bit_cast<std::uint64_t>(kd) + 1023U) << 52);
    return p * scale;
}

/// term[i] = samples[i].energy * ExpNonPositive(-(x - samples[i].range_m)^2 c), i < count
/// (callers keep the exponents >= -708; the waveform's cutoff keeps them >= -18).
void GaussianTerms(const EchoSample* __restrict samples,
                   std::size_t count,
                   double x,
                   double c,
                   double* __restrict term);

}  // namespace casmap::sensor_models
