#include <cmath>
#include <cstddef>
#include <cstdint>

#include "casmap/sensor_models/lms200_model.hpp"
#include "casmap/sensor_models/ziggurat_tables.hpp"

// PulseRng: the per-pulse random streams and their ziggurat normal sampler.

namespace casmap::sensor_models {

PulseRng::PulseRng(std::uint64_t seed,
                   std::uint64_t scan_index,
                   std::uint32_t beam,
                   std::uint32_t stream)
    : PulseRng(SeedKey{SplitMix64(seed)}, scan_index, beam, stream) {}

PulseRng::PulseRng(SeedKey key,
                   std::uint64_t scan_index,
                   std::uint32_t beam,
                   std::uint32_t stream) {
    std::uint64_t s = key.hash;
    s = SplitMix64(s ^ scan_index);
    s = SplitMix64(s ^ ((static_cast<std::uint64_t>(beam) << 8) | stream));
    state_ = s;
}

double PulseRng::Normal() {
    // Ziggurat of 256 layers of equal area (Marsaglia & Tsang 2000; tables exact to double,
    // solved by scripts/gen_ziggurat_tables.py). One 64-bit draw: bits 0-7 pick the layer,
    // bit 8 the sign, bits 11-63 the position x = j w_i in it; x < x_{i+1} lies under the
    // curve (an integer compare, 98.5 % of the draws). Otherwise the base layer samples the
    // tail beyond r (Marsaglia 1964) and the others test the wedge against exp(-x^2 / 2).
    for (;;) {
        const std::uint64_t bits = NextU64();
        const std::size_t layer = bits & 0xFFU;
        const bool negative = (bits & 0x100U) != 0;
        const std::uint64_t j = bits >> 11;
        const double x = static_cast<double>(j) * ziggurat::kW[layer];
        if (j < ziggurat::kK[layer]) {
            return negative ? -x : x;
        }
        if (layer == 0) {
            double a = 0.0;
            double b = 0.0;
            do {
                a = -std::log(1.0 - Uniform()) * ziggurat::kInvR;
                b = -std::log(1.0 - Uniform());
            } while (b + b < a * a);
            return negative ? -(ziggurat::kR + a) : ziggurat::kR + a;
        }
        const double y =
            ziggurat::kF[layer] + Uniform() * (ziggurat::kF[layer + 1] - ziggurat::kF[layer]);
        if (y < std::exp(-0.5 * x * x)) {
            return negative ? -x : x;
        }
    }
}

}  // namespace casmap::sensor_models
