#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>

#include "casmap/sensor_models/gaussian_terms.hpp"
#include "casmap/sensor_models/lms200_model.hpp"

// Return formation's waveform (docs/sensor-model.md 4.3): the Gaussians of the sub-ray echoes,
// their lobes (WaveformLobes, reference algorithm) and the closed form for compact hits
// (CompactLobe).

namespace casmap::sensor_models {

// Widest vectors the CPU has (GCC on x86-64: AVX-512, AVX2 or SSE2 clones, chosen at load
// time). Bit-identical results on every clone: the target is built with -ffp-contract=off, so
// the v3/v4 clones do not fuse the polynomial into FMAs the SSE2 clone cannot have.
#if defined(__GNUC__) && !defined(__clang__) && defined(__x86_64__)
__attribute__((target_clones("arch=x86-64-v4", "arch=x86-64-v3", "default")))
#endif
void GaussianTerms(const EchoSample* __restrict samples,
                   std::size_t count,
                   double x,
                   double c,
                   double* __restrict term) {
    for (std::size_t i = 0; i < count; ++i) {
        const double d = x - samples[i].range_m;
        term[i] = samples[i].energy * ExpNonPositive(-d * d * c);
    }
}

namespace {

// sigma of a Gaussian from its full width at half maximum: FWHM = 2 sqrt(2 ln 2) sigma.
constexpr double kFwhmPerSigma = 2.3548200450309493;
// Gaussian contributions beyond this many sigma are ignored (exp(-18) ~ 1.5e-8 of the peak).
constexpr double kCutoffSigmas = 6.0;
// Hits farther apart than this many sigma form independent waveform segments.
constexpr double kSegmentGapSigmas = 12.0;

// The waveform f(x) = sum E_i exp(-(x - r_i)^2 / (2 sigma^2)) and its derivative, over hits
// sorted by range.
class Waveform {
public:
    Waveform(std::span<const EchoSample> sorted, double sigma)
        : samples_(sorted), sigma_(sigma), inv_2s2_(0.5 / (sigma * sigma)) {}

    [[nodiscard]] double Value(double x) const {
        double f = 0.0;
        ForTerms(x, [&f](std::size_t, double term) { f += term; });
        return f;
    }
    // Sign-carrying derivative up to the positive factor 1 / sigma^2.
    [[nodiscard]] double Slope(double x) const {
        double g = 0.0;
        ForTerms(x, [&](std::size_t i, double term) { g -= (x - samples_[i].range_m) * term; });
        return g;
    }
    // Closed-form integral of f and of x f over [a, b]: the lobe's energy and first moment.
    void Moments(double a, double b, double& m0, double& m1) const {
        const double k = sigma_ * std::sqrt(std::numbers::pi / 2.0);
        const double inv = 1.0 / (std::numbers::sqrt2 * sigma_);
        m0 = 0.0;
        m1 = 0.0;
        for (const EchoSample& s : samples_) {
            const double da = a - s.range_m;
            const double db = b - s.range_m;
            const double i0 = k * (std::erf(db * inv) - std::erf(da * inv));
            const double i1 =
                s.range_m * i0 + sigma_ * sigma_ *
                                     (ExpNonPositive(std::max(-da * da * inv_2s2_, -708.0)) -
                                      ExpNonPositive(std::max(-db * db * inv_2s2_, -708.0)));
            m0 += s.energy * i0;
            m1 += s.energy * i1;
        }
    }
    [[nodiscard]] double sigma() const { return sigma_; }

private:
    // use(i, E_i exp(-(x - r_i)^2 / (2 sigma^2))) for each hit i within the cutoff, in order.
    // Those hits are one run [lo, hi) of the sorted hits (x - r_i falls as r_i grows), so the
    // Gaussians are computed without a test per hit, a vectorised block of up to kMaxSubrays
    // at a time, and handed on in hit order (the sums then add in the same order as a loop
    // that skips the others).
    template <class Use>
    void ForTerms(double x, Use use) const {
        const std::size_t n = samples_.size();
        const EchoSample* __restrict s = samples_.data();
        const double cut = kCutoffSigmas * sigma_;
        std::size_t lo = 0;
        while (lo < n && x - s[lo].range_m >= cut) {
            ++lo;
        }
        std::size_t hi = lo;
        while (hi < n && x - s[hi].range_m > -cut) {
            ++hi;
        }
        double term[kMaxSubrays];
        for (std::size_t first = lo; first < hi; first += kMaxSubrays) {
            const std::size_t m = std::min(hi - first, kMaxSubrays);
            GaussianTerms(s + first, m, x, inv_2s2_, term);
            for (std::size_t i = 0; i < m; ++i) {
                use(first + i, term[i]);
            }
        }
    }

    std::span<const EchoSample> samples_;
    double sigma_;
    double inv_2s2_;
};

// Root of g(x) = 0 in [a, b] where g(a) and g(b) differ in sign: Illinois regula falsi to
// 0.05 mm (a few evaluations for these smooth sums of Gaussians).
template <class G>
double Root(const G& g, double a, double b) {
    double fa = g(a);
    double fb = g(b);
    int side = 0;
    for (int it = 0; it < 40 && std::abs(b - a) > 5e-5; ++it) {
        const double x = (fb - fa) != 0.0 ? b - fb * (b - a) / (fb - fa) : 0.5 * (a + b);
        const double fx = g(x);
        if (fx == 0.0) {
            return x;
        }
        if ((fx > 0.0) == (fb > 0.0)) {
            b = x;
            fb = fx;
            if (side == -1) {
                fa *= 0.5;
            }
            side = -1;
        } else {
            a = x;
            fa = fx;
            if (side == 1) {
                fb *= 0.5;
            }
            side = 1;
        }
    }
    return std::abs(fa) < std::abs(fb) ? a : b;
}

// The extremum between a and b (the slope changes sign there).
double RefineExtremum(const Waveform& w, double a, double b) {
    return Root([&w](double x) { return w.Slope(x); }, a, b);
}

// Where the waveform crosses c between a and b.
double Crossing(const Waveform& w, double a, double b, double c) {
    return Root([&w, c](double x) { return w.Value(x) - c; }, a, b);
}

// Steps outward from `from` by one sigma until the waveform falls below c; returns the bound.
double OuterBound(const Waveform& w, double from, double dir, double c) {
    double inner = from;
    double outer = from + dir * w.sigma();
    for (int it = 0; it < 64 && w.Value(outer) >= c; ++it) {
        inner = outer;
        outer += dir * w.sigma();
    }
    return Crossing(w, std::min(inner, outer), std::max(inner, outer), c);
}

// The waveform's slope (up to 1 / sigma^2, like Waveform::Slope) on the grid x_k = x0 + k h,
// k = 1, 2, ..., one step per Next(): each hit's Gaussian advances by two products,
// exp(-(d + h)^2 c) = exp(-d^2 c) q with q = exp(-(2 d h + h^2) c), q' = q exp(-2 h^2 c),
// instead of an exp per hit and point. A hit enters with exact exps when it comes within the
// cutoff (as in Waveform); the products drift by ~k^2 ulp, which moves only the sign of a slope
// that is ~1e-13 of its terms (an extremum on a grid point; it is refined with exact exps).
class GridSlope {
public:
    GridSlope(std::span<const EchoSample> samples, double sigma, double x0, double h)
        : samples_(samples),
          sigma_(sigma),
          c_(0.5 / (sigma * sigma)),
          x0_(x0),
          h_(h),
          b2_(std::exp(-2.0 * h * h * c_)) {}

    [[nodiscard]] double Next() {
        ++k_;
        const double x = x0_ + static_cast<double>(k_) * h_;
        double g = 0.0;
        for (std::size_t i = 0; i < samples_.size(); ++i) {
            const double d = x - samples_[i].range_m;
            State& st = state_[i];
            if (std::abs(d) < kCutoffSigmas * sigma_) {
                if (st.step != k_ - 1) {  // (re-)enters the cutoff window: exact start
                    st.value = std::exp(-d * d * c_);
                    st.ratio = std::exp(-(2.0 * d * h_ + h_ * h_) * c_);
                } else {
                    st.value *= st.ratio;
                    st.ratio *= b2_;
                }
                st.step = k_;
                g -= d * samples_[i].energy * st.value;
            }
        }
        return g;
    }

private:
    struct State {
        double value = 0.0;                               // exp(-d^2 c) at the last step
        double ratio = 0.0;                               // to the next step
        std::size_t step = static_cast<std::size_t>(-2);  // step it was last advanced at
    };
    std::span<const EchoSample> samples_;
    double sigma_;
    double c_;
    double x0_;
    double h_;
    double b2_;
    std::size_t k_ = 0;
    std::array<State, kMaxSubrays> state_{};
};

// Lobes of one segment (hits closer than kSegmentGapSigmas apart).
std::size_t SegmentLobes(std::span<const EchoSample> seg,
                         double sigma,
                         double bound_fraction,
                         std::span<Lobe> out) {
    const Waveform w(seg, sigma);
    // Extrema lie between the first and last hit; f rises before the first and falls after
    // the last. Scan the slope's sign on a sigma/4 grid and refine each change.
    std::array<double, 2 * kMaxSubrays + 2> maxima{};
    std::array<double, 2 * kMaxSubrays + 2> minima{};
    std::size_t n_max = 0;
    std::size_t n_min = 0;
    const double first = seg.front().range_m;
    const double last = seg.back().range_m;
    const double h = 0.25 * sigma;
    const auto steps = static_cast<std::size_t>(std::ceil((last - first) / h));
    if (steps == 0) {
        maxima[n_max++] = first;
    } else {
        double x_prev = first;
        bool rising_prev = true;  // f' > 0 left of every hit
        GridSlope grid(seg, sigma, first, h);
        const bool by_grid = seg.size() <= kMaxSubrays;  // its state holds one pulse's hits
        for (std::size_t k = 1; k <= steps; ++k) {
            const double x = k == steps ? last : first + static_cast<double>(k) * h;
            const bool rising = k == steps ? false : (by_grid ? grid.Next() : w.Slope(x)) > 0.0;
            if (rising != rising_prev) {
                const double e = RefineExtremum(w, x_prev, x);
                if (rising_prev && n_max < maxima.size()) {
                    maxima[n_max++] = e;
                } else if (!rising_prev && n_min < minima.size()) {
                    minima[n_min++] = e;
                }
            }
            x_prev = x;
            rising_prev = rising;
        }
    }
    std::size_t count = 0;
    for (std::size_t j = 0; j < n_max && count < out.size(); ++j) {
        Lobe lobe;
        lobe.peak_range_m = maxima[j];
        lobe.peak = w.Value(maxima[j]);
        const double c = bound_fraction * lobe.peak;
        if (j == 0) {
            lobe.lo_m = OuterBound(w, maxima[j], -1.0, c);
        } else {
            const double m = minima[j - 1];
            lobe.lo_m = w.Value(m) >= c ? m : Crossing(w, m, maxima[j], c);
        }
        if (j + 1 >= n_max || j >= n_min) {
            lobe.hi_m = OuterBound(w, maxima[j], 1.0, c);
        } else {
            const double m = minima[j];
            lobe.hi_m = w.Value(m) >= c ? m : Crossing(w, maxima[j], m, c);
        }
        double m0 = 0.0;
        double m1 = 0.0;
        w.Moments(lobe.lo_m, lobe.hi_m, m0, m1);
        lobe.centroid_m = m0 > 0.0 ? m1 / m0 : lobe.peak_range_m;
        out[count++] = lobe;
    }
    return count;
}

}  // namespace

std::size_t WaveformLobes(std::span<const EchoSample> sorted,
                          double echo_width_m,
                          double bound_fraction,
                          std::span<Lobe> out) {
    const double sigma = echo_width_m / kFwhmPerSigma;
    std::size_t count = 0;
    std::size_t begin = 0;
    while (begin < sorted.size() && count < out.size()) {
        std::size_t end = begin + 1;
        while (end < sorted.size() &&
               sorted[end].range_m - sorted[end - 1].range_m <= kSegmentGapSigmas * sigma) {
            ++end;
        }
        count += SegmentLobes(sorted.subspan(begin, end - begin), sigma, bound_fraction,
                              out.subspan(count));
        begin = end;
    }
    return count;
}

Lobe CompactLobe(std::span<const EchoSample> samples, double echo_width_m) {
    const double sigma = echo_width_m / kFwhmPerSigma;
    Lobe lobe;
    if (samples.empty()) {
        return lobe;
    }
    // One pass, moments about the first range (no cancellation for ranges of many metres).
    const double r0 = samples.front().range_m;
    double e = 0.0;
    double m1 = 0.0;
    double m2 = 0.0;
    double lo = r0;
    double hi = r0;
    for (const EchoSample& s : samples) {
        const double d = s.range_m - r0;
        e += s.energy;
        m1 += s.energy * d;
        m2 += s.energy * d * d;
        lo = std::min(lo, s.range_m);
        hi = std::max(hi, s.range_m);
    }
    if (!(e > 0.0)) {
        return lobe;
    }
    const double mean = m1 / e;
    const double var = std::max(0.0, m2 / e - mean * mean);
    // exp(-x) to fourth order: x <= 0.016 for spreads up to compact_spread_m (error < 3e-9).
    const double x = var / (2.0 * sigma * sigma);
    lobe.peak = x < 0.02 ? e * (1.0 - x * (1.0 - x * (0.5 - x * (1.0 / 6.0)))) : e * std::exp(-x);
    lobe.peak_range_m = r0 + mean;
    lobe.centroid_m = r0 + mean;
    lobe.lo_m = lo;
    lobe.hi_m = hi;
    return lobe;
}

}  // namespace casmap::sensor_models
