#include "casmap/scenegen/random.hpp"

#include <cmath>

namespace casmap::scenegen {
namespace {
std::uint64_t Rotl(std::uint64_t x, int k) { return (x << k) | (x >> (64 - k)); }
}  // namespace

std::uint64_t SplitMix64(std::uint64_t x) {
    x += 0x9E3779B97F4A7C15ULL;
    x = (x ^ (x >> 30)) * 0xBF58476D1CE4E5B9ULL;
    x = (x ^ (x >> 27)) * 0x94D049BB133111EBULL;
    return x ^ (x >> 31);
}

std::uint64_t SampleSeed(std::uint64_t dataset_seed, std::uint64_t index) {
    // Two rounds so neighbouring (seed, index) pairs give unrelated seeds.
    return SplitMix64(SplitMix64(dataset_seed) ^ SplitMix64(index + 0x632BE59BD9B4E019ULL));
}

Rng::Rng(std::uint64_t seed) {
    std::uint64_t x = seed;
    for (std::uint64_t& s : s_) {
        x = SplitMix64(x);
        s = x;
    }
}

std::uint64_t Rng::Next() {
    const std::uint64_t result = Rotl(s_[1] * 5, 7) * 9;
    const std::uint64_t t = s_[1] << 17;
    s_[2] ^= s_[0];
    s_[3] ^= s_[1];
    s_[1] ^= s_[2];
    s_[0] ^= s_[3];
    s_[2] ^= t;
    s_[3] = Rotl(s_[3], 45);
    return result;
}

double Rng::Uniform() { return static_cast<double>(Next() >> 11) * 0x1.0p-53; }

double Rng::Draw(const Range& range) {
    const double u = Uniform();  // drawn even for a fixed range: later draws do not shift
    return range.min == range.max ? range.min : range.min + (range.max - range.min) * u;
}

std::uint64_t Rng::Below(std::uint64_t n) {
    // Modulo: the bias for n << 2^64 is negligible for scene generation.
    return Next() % n;
}

int Rng::Count(const Range& range) {
    const auto lo = static_cast<std::int64_t>(std::floor(range.min));
    const auto hi = static_cast<std::int64_t>(std::floor(range.max));
    return static_cast<int>(
        lo + static_cast<std::int64_t>(Below(static_cast<std::uint64_t>(hi - lo + 1))));
}

bool Rng::Chance(double p) { return Uniform() < p; }

std::size_t Rng::Pick(const double* weights, std::size_t n) {
    double total = 0.0;
    for (std::size_t i = 0; i < n; ++i) {
        total += weights[i];
    }
    double u = Uniform() * total;
    for (std::size_t i = 0; i < n; ++i) {
        if (u < weights[i]) {
            return i;
        }
        u -= weights[i];
    }
    for (std::size_t i = n; i-- > 0;) {  // rounding: the last index with weight
        if (weights[i] > 0.0) {
            return i;
        }
    }
    return 0;
}

}  // namespace casmap::scenegen
