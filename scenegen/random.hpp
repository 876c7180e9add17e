#pragma once

// Seeds and random draws for generated data: a counter-based seed per sample (SplitMix64 of the
// dataset seed and the sample index, never of generation order) and a small xoshiro256**
// generator whose draws are the same on every platform and standard library (std::
// distributions are implementation-defined, so none is used).

#include <cstdint>

namespace casmap::scenegen {

/// SplitMix64 finaliser (Steele, Lea, Flood 2014): a bijective 64-bit mix.
[[nodiscard]] std::uint64_t SplitMix64(std::uint64_t x);

/// Seed of sample `index` of a dataset seeded `dataset_seed`: depends on nothing else.
[[nodiscard]] std::uint64_t SampleSeed(std::uint64_t dataset_seed, std::uint64_t index);

/// An inclusive interval of a drawn quantity; min == max fixes it.
struct Range {
    double min = 0.0;
    double max = 0.0;
    bool operator==(const Range&) const = default;
};

/// xoshiro256** (Blackman, Vigna 2018), seeded through SplitMix64.
class Rng {
public:
    explicit Rng(std::uint64_t seed);
    [[nodiscard]] std::uint64_t Next();
    /// Uniform in [0, 1) with 53 random bits.
    [[nodiscard]] double Uniform();
    /// Uniform in [range.min, range.max] (range.min when they are equal).
    [[nodiscard]] double Draw(const Range& range);
    /// Uniform integer in [0, n), n > 0.
    [[nodiscard]] std::uint64_t Below(std::uint64_t n);
    /// Integer count drawn uniformly from the integers in [floor(min), floor(max)].
    [[nodiscard]] int Count(const Range& range);
    /// True with probability p.
    [[nodiscard]] bool Chance(double p);
    /// Index drawn with probability proportional to weights[i] (all >= 0, sum > 0).
    [[nodiscard]] std::size_t Pick(const double* weights, std::size_t n);

private:
    std::uint64_t s_[4] = {};
};

}  // namespace casmap::scenegen
