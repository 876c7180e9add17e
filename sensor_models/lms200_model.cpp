#include "casmap/sensor_models/lms200_model.hpp"

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <numbers>

#include "casmap/sensor_models/gaussian_terms.hpp"
#include "casmap/sensor_models/scratch_array.hpp"
#include "casmap/sensor_models/ziggurat_tables.hpp"

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

constexpr double kTwoPi = 2.0 * std::numbers::pi;
// sigma of a Gaussian from its full width at half maximum: FWHM = 2 sqrt(2 ln 2) sigma.
constexpr double kFwhmPerSigma = 2.3548200450309493;
// Gaussian contributions beyond this many sigma are ignored (exp(-18) ~ 1.5e-8 of the peak).
constexpr double kCutoffSigmas = 6.0;
// Hits farther apart than this many sigma form independent waveform segments.
constexpr double kSegmentGapSigmas = 12.0;
// Random streams of one pulse.
constexpr std::uint32_t kStreamPattern = 1;
constexpr std::uint32_t kStreamReturn = 2;
// Detection probability above which the logistic need not be evaluated (an exact shortcut).
constexpr double kSureProbability = 0.999;
constexpr std::uint64_t kBiasTag = 0x6d6174657269616cULL;  // "material"
// Material biases of the first surface ids, drawn once per model (the same values).
constexpr std::size_t kBiasTableSize = 256;

double DegToRad(double deg) { return deg * std::numbers::pi / 180.0; }

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

// Echo energy of one sub-ray hit, Lambertian lidar equation E = w rho cos(theta) / r^2 scaled
// by `scale` (sensor_model.md 4.2); a retro-reflector returns retro_gain x a white diffuser.
// One expression for both hit layouts, so they agree bit for bit.
inline double EchoEnergy(double weight,
                         double distance_m,
                         double cos_incidence,
                         double reflectivity,
                         bool retro,
                         double retro_gain,
                         double scale) {
    // Branch-free forms of the ternary and std::clamp (x * 1.0 == x, and min(max()) equals
    // clamp even for NaN and -0), so the loop over a pulse vectorises.
    const double d = std::max(distance_m, 1e-3);
    const double rho = reflectivity * (retro ? retro_gain : 1.0);
    return weight * rho * std::min(std::max(cos_incidence, 0.0), 1.0) * scale / (d * d);
}

// The two hit layouts FormReturn accepts, behind one interface.
struct HitList {
    std::span<const SubrayHit> hits;
    [[nodiscard]] std::size_t size() const { return hits.size(); }
    [[nodiscard]] bool Valid(std::size_t i) const { return hits[i].valid(); }
    [[nodiscard]] double Distance(std::size_t i) const { return hits[i].distance_m; }
    [[nodiscard]] double Reflectivity(std::size_t i) const { return hits[i].reflectivity; }
    [[nodiscard]] std::uint32_t SurfaceId(std::size_t i) const { return hits[i].surface_id; }
    // energy[i] for i < count (valid hits only).
    void Energies(
        const double* weights, double gain, double scale, std::size_t count, double* energy) const {
        for (std::size_t i = 0; i < count; ++i) {
            const SubrayHit& h = hits[i];
            if (h.valid()) {
                energy[i] = EchoEnergy(weights[i], h.distance_m, h.cos_incidence, h.reflectivity,
                                       h.retro_reflective, gain, scale);
            }
        }
    }
};

struct HitArrays {
    const SubrayHitArrays& hits;
    [[nodiscard]] std::size_t size() const { return hits.count; }
    [[nodiscard]] bool Valid(std::size_t i) const {
        return hits.distance_m[i] < std::numeric_limits<float>::infinity();
    }
    [[nodiscard]] double Distance(std::size_t i) const {
        return static_cast<double>(hits.distance_m[i]);
    }
    [[nodiscard]] double Reflectivity(std::size_t i) const {
        return static_cast<double>(hits.reflectivity[i]);
    }
    [[nodiscard]] std::uint32_t SurfaceId(std::size_t i) const { return hits.surface_id[i]; }
    // energy[i] for every i < count in one branch-free loop the compiler vectorises (a miss's
    // value is garbage and never read; IEEE arithmetic does not trap).
    void Energies(const double* __restrict weights,
                  double gain,
                  double scale,
                  std::size_t count,
                  double* __restrict energy) const {
        const float* __restrict dist = hits.distance_m;
        const float* __restrict cosi = hits.cos_incidence;
        const float* __restrict refl = hits.reflectivity;
        const std::uint8_t* __restrict retro = hits.retro_reflective;
        for (std::size_t i = 0; i < count; ++i) {
            energy[i] =
                EchoEnergy(weights[i], static_cast<double>(dist[i]), static_cast<double>(cosi[i]),
                           static_cast<double>(refl[i]), retro[i] != 0, gain, scale);
        }
    }
};

}  // namespace

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

void SubrayWeights(int subrays_per_pulse, std::span<double> weights) {
    // Ring radii (units of the 1/e^2 radius), ray counts and annulus bounds, [A] sensor_model
    // section 4.1. The 37-ray pattern adds a ring at 1.0 with the annulus [0.9, 1.1].
    static constexpr std::array<int, 4> kCounts = {1, 6, 12, 18};
    int rings = 0;
    std::array<double, 5> bounds{};
    switch (subrays_per_pulse) {
        case 1:
            rings = 1;
            bounds = {0.0, 1.0};
            break;
        case 7:
            rings = 2;
            bounds = {0.0, 0.2, 1.0};
            break;
        case 19:
            rings = 3;
            bounds = {0.0, 0.2, 0.6, 1.0};
            break;
        default:
            rings = 4;
            bounds = {0.0, 0.2, 0.6, 0.9, 1.1};
            break;
    }
    const auto energy = [](double rho) { return std::exp(-2.0 * rho * rho); };
    const double total = energy(0.0) - energy(bounds[static_cast<std::size_t>(rings)]);
    std::size_t i = 0;
    for (int r = 0; r < rings; ++r) {
        const auto ring = static_cast<std::size_t>(r);
        const double e = (energy(bounds[ring]) - energy(bounds[ring + 1])) / total;
        for (int k = 0; k < kCounts[ring] && i < weights.size(); ++k) {
            weights[i++] = e / kCounts[ring];
        }
    }
}

Lms200Model::Lms200Model(const Lms200Config& config, std::uint64_t seed)
    : config_(config), seed_(seed) {
    config_.Validate();
    beam_count_ = static_cast<std::size_t>(
                      std::lround(config_.field_of_view_deg / config_.angular_resolution_deg)) +
                  1;
    turns_ = static_cast<int>(std::lround(1.0 / config_.angular_resolution_deg));
    subray_count_ = config_.ideal ? 1 : static_cast<std::size_t>(config_.subrays_per_pulse);
    SubrayWeights(static_cast<int>(subray_count_), std::span<double>(weights_, subray_count_));
    // Ring pattern: ring k at rho = 0, 0.4, 0.8, 1.0 with 1, 6, 12, 18 rays evenly spaced.
    static constexpr std::array<double, 4> kRho = {0.0, 0.4, 0.8, 1.0};
    static constexpr std::array<int, 4> kCounts = {1, 6, 12, 18};
    // A cone from the exit aperture: at range r the ray at normalised radius rho sits at
    // rho * (D0 + theta r) / 2 from the axis (sensor_model.md 4.1).
    const double a0 = 0.5 * config_.spot_diameter_at_exit_m;
    const double half_div = 0.5 * config_.divergence_rad;
    std::size_t i = 0;
    for (std::size_t ring = 0; ring < kRho.size() && i < subray_count_; ++ring) {
        for (int k = 0; k < kCounts[ring] && i < subray_count_; ++k, ++i) {
            const double psi = kTwoPi * static_cast<double>(k) / static_cast<double>(kCounts[ring]);
            ring_cos_[i] = std::cos(psi);
            ring_sin_[i] = std::sin(psi);
            origin_offset_[i] = kRho[ring] * a0;
            dir_slope_[i] = kRho[ring] * half_div;
            dir_scale_[i] = 1.0 / std::sqrt(1.0 + dir_slope_[i] * dir_slope_[i]);
        }
    }
    seed_key_ = PulseRng::SeedKey{SplitMix64(seed_)};
    bias_key_ = SplitMix64(seed_ ^ kBiasTag);
    bias_table_.resize(kBiasTableSize);
    for (std::size_t id = 0; id < kBiasTableSize; ++id) {
        const std::uint64_t h = SplitMix64(bias_key_ ^ id);
        const double u = static_cast<double>(h >> 11) * 0x1.0p-53;
        bias_table_[id] = (2.0 * u - 1.0) * config_.MaterialBiasMaxM();
    }
    // Peak whose detection probability is kSureProbability: logit(q) = db / soft_edge_db.
    sure_peak_ = std::pow(
        10.0, config_.soft_edge_db * std::log(kSureProbability / (1.0 - kSureProbability)) / 10.0);
    beam_cos_.resize(beam_count_);
    beam_sin_.resize(beam_count_);
    for (std::size_t b = 0; b < beam_count_; ++b) {
        beam_cos_[b] = std::cos(BeamAngleRad(b));
        beam_sin_[b] = std::sin(BeamAngleRad(b));
    }
    beam_offset_s_.resize(beam_count_);
    for (std::size_t b = 0; b < beam_count_; ++b) {
        beam_offset_s_[b] = ComputeBeamTimeOffsetS(b);
        max_beam_offset_s_ = std::max(max_beam_offset_s_, beam_offset_s_[b]);
    }
}

double Lms200Model::StartAngleRad() const { return DegToRad(-0.5 * config_.field_of_view_deg); }

double Lms200Model::AngleStepRad() const { return DegToRad(config_.angular_resolution_deg); }

double Lms200Model::BeamAngleRad(std::size_t beam) const {
    return StartAngleRad() + static_cast<double>(beam) * AngleStepRad();
}

double Lms200Model::BeamTimeOffsetS(std::size_t beam) const {
    return beam < beam_offset_s_.size() ? beam_offset_s_[beam] : ComputeBeamTimeOffsetS(beam);
}

double Lms200Model::ComputeBeamTimeOffsetS(std::size_t beam) const {
    // Turn k of an interleaved scan measures the angles offset by k x resolution (partial-scan
    // index, sicktoolbox GetSickPartialScan); within a turn the mirror sweeps 360 deg per 1/75 s.
    const double turn = static_cast<double>(beam % static_cast<std::size_t>(turns_));
    const double angle_deg = static_cast<double>(beam) * config_.angular_resolution_deg;
    return (turn + angle_deg / 360.0) * core::Lms200Timing::kTurnPeriodS;
}

double Lms200Model::ScanPeriodS() const {
    return static_cast<double>(turns_) * core::Lms200Timing::kTurnPeriodS;
}

core::Scan Lms200Model::MakeScan(double stamp_s) const {
    core::Scan scan;
    scan.stamp_s = stamp_s;
    scan.start_angle_rad = StartAngleRad();
    scan.angle_step_rad = AngleStepRad();
    scan.beam_period_s = config_.angular_resolution_deg / 360.0 * core::Lms200Timing::kTurnPeriodS;
    if (turns_ > 1) {
        scan.beam_time_offset_s.resize(beam_count_);
        for (std::size_t i = 0; i < beam_count_; ++i) {
            scan.beam_time_offset_s[i] = beam_offset_s_[i];
        }
    }
    scan.beams.resize(beam_count_);
    return scan;
}

void Lms200Model::PulseSubrays(std::uint64_t scan_index,
                               std::size_t beam,
                               std::span<Subray> out) const {
    PulseSubrays(scan_index, beam, core::Pose{}, out);
}

PulseFrame Lms200Model::PulseBasis(std::uint64_t scan_index,
                                   std::size_t beam,
                                   const core::Pose& frame_T_sensor) const {
    const Eigen::Matrix3d rot = frame_T_sensor.rotation.toRotationMatrix();
    const double cb = beam_cos_[beam];
    const double sb = beam_sin_[beam];
    PulseFrame f;
    f.origin = frame_T_sensor.translation;
    f.axis = rot * Eigen::Vector3d(cb, sb, 0.0);
    f.u1 = rot * Eigen::Vector3d(-sb, cb, 0.0);  // in the scan plane
    f.u2 = rot.col(2);                           // across it
    if (config_.rotate_pattern_per_pulse && subray_count_ > 1) {
        // One rotation of the whole pattern per pulse: rotate the transverse basis instead.
        // A uniform angle as a random point of the unit disc, normalised (no trigonometry).
        PulseRng rng(seed_key_, scan_index, static_cast<std::uint32_t>(beam), kStreamPattern);
        double c = 1.0;
        double s = 0.0;
        for (;;) {
            c = 2.0 * rng.Uniform() - 1.0;
            s = 2.0 * rng.Uniform() - 1.0;
            const double r2 = c * c + s * s;
            if (r2 > 1e-12 && r2 <= 1.0) {
                const double inv = 1.0 / std::sqrt(r2);
                c *= inv;
                s *= inv;
                break;
            }
        }
        const Eigen::Vector3d v1 = c * f.u1 + s * f.u2;
        f.u2 = c * f.u2 - s * f.u1;
        f.u1 = v1;
    }
    return f;
}

void Lms200Model::PulseSubrays(std::uint64_t scan_index,
                               std::size_t beam,
                               const core::Pose& frame_T_sensor,
                               std::span<Subray> out) const {
    ForEachSubray(PulseBasis(scan_index, beam, frame_T_sensor),
                  [&out](std::size_t i, const Eigen::Vector3d& origin, const Eigen::Vector3d& dir) {
                      if (i < out.size()) {
                          out[i].origin = origin;
                          out[i].direction = dir;
                      }
                  });
}

double Lms200Model::MaterialBiasM(std::uint32_t surface_id) const {
    if (surface_id < bias_table_.size()) {
        return bias_table_[surface_id];
    }
    const std::uint64_t h = SplitMix64(bias_key_ ^ surface_id);
    const double u = static_cast<double>(h >> 11) * 0x1.0p-53;
    return (2.0 * u - 1.0) * config_.MaterialBiasMaxM();
}

template <class Hits>
PulseResult Lms200Model::IdealReturn(const Hits& hits) const {
    PulseResult r;
    const core::Lms200Format& f = config_.format;
    if (hits.size() == 0 || !hits.Valid(0) || hits.Distance(0) > config_.max_trace_range_m) {
        r.beam.status = core::BeamStatus::kNoReturn;
        r.beam.raw = f.CodeFor(core::BeamStatus::kNoReturn);
        r.label = core::BeamLabel::kNoTarget;
        return r;
    }
    r.true_range_m = static_cast<float>(hits.Distance(0));
    r.echo_range_m = hits.Distance(0);
    r.beam.status = core::BeamStatus::kOk;
    r.beam.range_m = r.true_range_m;
    r.beam.raw = f.EncodeRange(hits.Distance(0));
    r.label = core::BeamLabel::kValid;
    return r;
}

void Lms200Model::SetCode(core::BeamStatus status, core::BeamLabel label, PulseResult& out) const {
    out.beam.status = status;
    out.beam.range_m = 0.0F;
    out.beam.raw = config_.format.CodeFor(status);
    out.label = label;
}

void Lms200Model::SetSpike(double range_m, PulseResult& out) const {
    const core::Lms200Format& f = config_.format;
    const double units =
        std::clamp(std::round(range_m / f.UnitM()), 0.0,
                   static_cast<double>(f.CodeFor(core::BeamStatus::kOutOfRange) - 1));
    out.beam.raw = static_cast<std::uint16_t>(units);
    out.beam.status = core::BeamStatus::kOk;
    out.beam.range_m = static_cast<float>(units * f.UnitM());
    out.label = core::BeamLabel::kSpike;
}

void Lms200Model::Encode(double range_m,
                         PulseRng& rng,
                         core::BeamLabel lost,
                         PulseResult& out) const {
    const core::Lms200Format& f = config_.format;
    const double units = std::max(0.0, std::round(range_m / f.UnitM()));
    if (units >= static_cast<double>(f.CodeFor(core::BeamStatus::kOutOfRange))) {
        // Over-range: the 16 m mode's undetected overflow keeps the low 14 bits (the paper's
        // very short spurious ranges outdoors, sensor_model.md 1.2); otherwise "value > max".
        if (f.mode == core::RangeMode::k16m && config_.wrap_enabled &&
            rng.Uniform() < config_.p_wrap) {
            const auto raw =
                static_cast<std::uint16_t>(static_cast<std::uint64_t>(units) & f.ValueMask());
            out.beam = f.Decode(raw);
            out.label = core::BeamLabel::kSpike;
            return;
        }
        SetCode(core::BeamStatus::kOutOfRange, lost, out);
        return;
    }
    out.beam.raw = static_cast<std::uint16_t>(units);
    out.beam.status = core::BeamStatus::kOk;
    out.beam.range_m = static_cast<float>(units * f.UnitM());
}

PulseResult Lms200Model::FormReturn(const PulseContext& pulse,
                                    std::span<const SubrayHit> hits) const {
    return FormReturnImpl(pulse, HitList{hits});
}

PulseResult Lms200Model::FormReturn(const PulseContext& pulse, const SubrayHitArrays& hits) const {
    return FormReturnImpl(pulse, HitArrays{hits});
}

template <class Hits>
PulseResult Lms200Model::FormReturnImpl(const PulseContext& pulse, const Hits& hits) const {
    if (config_.ideal) {
        return IdealReturn(hits);
    }
    PulseResult r;
    const core::Lms200Format& f = config_.format;
    const double max_range = f.MaxRangeM();
    if (hits.size() > 0 && hits.Valid(0)) {
        r.true_range_m = static_cast<float>(hits.Distance(0));
    }
    // Echo energies, Lambertian lidar equation E = w rho cos(theta) / r^2, scaled so that a
    // full-footprint 10 % target at R10 gives exactly the threshold 1 (sensor_model.md 4.2).
    // Sorted by range (insertion sort, at most 37 entries) unless one span covers them all.
    ScratchArray<EchoSample, kMaxSubrays> samples;
    ScratchArray<std::size_t, kMaxSubrays> source;
    std::size_t n = 0;
    double in_range_weight = 0.0;
    double r_lo = std::numeric_limits<double>::infinity();
    double r_hi = -r_lo;
    const double scale = config_.r10_m * config_.r10_m / config_.r10_reflectivity;
    const std::size_t count = std::min(hits.size(), subray_count_);
    double energy[kMaxSubrays];
    hits.Energies(weights_, config_.retro_gain, scale, count, energy);
    for (std::size_t i = 0; i < count; ++i) {
        const double distance = hits.Distance(i);
        if (!hits.Valid(i) || distance > config_.max_trace_range_m) {
            continue;
        }
        if (distance <= max_range) {
            in_range_weight += weights_[i];
        }
        samples.EmplaceBack(distance, energy[i]);
        source.EmplaceBack(i);
        ++n;
        r_lo = std::min(r_lo, distance);
        r_hi = std::max(r_hi, distance);
    }
    const bool compact = config_.return_algorithm == ReturnAlgorithm::kAuto &&
                         r_hi - r_lo <= config_.compact_spread_m;
    // One surface group when all hits lie within the mixed tolerance (see the labels below).
    const bool one_group = compact && r_hi - r_lo <= config_.mixed_tolerance_m;
    if (!one_group) {
        for (std::size_t k = 1; k < n; ++k) {
            const EchoSample e = samples[k];
            const std::size_t src = source[k];
            std::size_t j = k;
            for (; j > 0 && samples[j - 1].range_m > e.range_m; --j) {
                samples[j] = samples[j - 1];
                source[j] = source[j - 1];
            }
            samples[j] = e;
            source[j] = src;
        }
    }
    const bool target = in_range_weight >= config_.target_min_weight - 1e-12;
    const core::BeamLabel lost = target ? core::BeamLabel::kMissing : core::BeamLabel::kNoTarget;
    PulseRng rng(seed_key_, pulse.scan_index, pulse.beam, kStreamReturn);

    // Short and random spikes (Probabilistic Robotics beam-model structure, [A]).
    if (config_.spikes_enabled) {
        const double u_rand = rng.Uniform();
        const double u_short = rng.Uniform();
        const double u_value = rng.Uniform();
        const double r_min = config_.min_range_m;
        if (u_rand < config_.p_rand) {
            SetSpike(r_min + u_value * (max_range - r_min), r);
            return r;
        }
        if (target && u_short < config_.p_short) {
            const double near = std::max(r_lo, r_min);
            SetSpike(r_min + u_value * (near - r_min), r);
            return r;
        }
    }
    if (config_.dropout_enabled && rng.Uniform() < config_.p_dropout) {
        SetCode(core::BeamStatus::kNoReturn, lost, r);
        return r;
    }
    if (config_.sun_enabled) {
        const double c =
            pulse.beam_direction_world.normalized().dot(config_.sun_direction_world.normalized());
        if (c >= std::cos(DegToRad(config_.sun_cone_deg))) {
            SetCode(core::BeamStatus::kDazzle, lost, r);
            return r;
        }
        if (rng.Uniform() < config_.p_sun * config_.sun_irradiance_w_m2 / 1000.0) {
            SetCode(core::BeamStatus::kNoReturn, lost, r);
            return r;
        }
    }
    if (n == 0) {
        SetCode(core::BeamStatus::kNoReturn, core::BeamLabel::kNoTarget, r);
        return r;
    }

    // Return formation: the first lobe that passes the detection threshold.
    const std::span<const EchoSample> sorted(samples.data(), n);
    ScratchArray<Lobe, kMaxSubrays> lobes;
    std::size_t n_lobes = 0;
    if (compact) {
        lobes.Construct(1);
        lobes[0] = CompactLobe(sorted, config_.echo_width_m);
        n_lobes = 1;
    } else {
        lobes.Construct(kMaxSubrays);
        n_lobes =
            WaveformLobes(sorted, config_.echo_width_m, config_.lobe_bound_fraction, lobes.span());
    }
    const Lobe* echo = nullptr;
    double strongest = 0.0;
    for (std::size_t j = 0; j < n_lobes && echo == nullptr; ++j) {
        const double peak = lobes[j].peak;
        strongest = std::max(strongest, peak);
        bool detected = peak >= 1.0;
        if (config_.soft_threshold) {
            // Logistic in 10 log10(E / T) with a soft_edge_db scale ([A], sensor_model.md 4.4).
            // Exact shortcut: P(peak) >= 0.999 above sure_peak_, so any u < 0.999 detects.
            const double u = rng.Uniform();
            if (u < kSureProbability && peak >= sure_peak_) {
                detected = true;
            } else {
                const double db = peak > 0.0 ? 10.0 * std::log10(peak) : -300.0;
                detected = u < 1.0 / (1.0 + std::exp(-db / config_.soft_edge_db));
            }
        }
        if (detected) {
            echo = &lobes[j];
        }
    }
    if (echo == nullptr) {
        for (std::size_t j = 0; j < n_lobes; ++j) {
            strongest = std::max(strongest, lobes[j].peak);
        }
        SetCode(strongest >= config_.low_signal_fraction ? core::BeamStatus::kLowSignal
                                                         : core::BeamStatus::kNoReturn,
                lost, r);
        return r;
    }
    r.echo_range_m = echo->centroid_m;
    if (echo->centroid_m < config_.min_range_m) {
        SetCode(core::BeamStatus::kNoReturn, lost, r);
        return r;
    }
    if (echo->peak >= config_.saturation_peak) {
        // The receiver saturates (a retro-reflector close by): the scanner reports dazzle.
        SetCode(core::BeamStatus::kDazzle, core::BeamLabel::kDazzled, r);
        return r;
    }

    // Noise and bias only on a valid echo (sensor_model.md 4.5).
    double measured = echo->centroid_m;
    if (config_.bias_enabled) {
        // The lobe's strongest contributor decides the material.
        std::size_t dominant = 0;
        double best = -1.0;
        for (std::size_t k = 0; k < n; ++k) {
            const bool inside =
                samples[k].range_m >= echo->lo_m && samples[k].range_m <= echo->hi_m;
            if (inside && samples[k].energy > best) {
                best = samples[k].energy;
                dominant = k;
            }
        }
        const std::size_t k = source[dominant];
        measured += MaterialBiasM(hits.SurfaceId(k));
        const double reflectivity = hits.Reflectivity(k);
        if (reflectivity < config_.dark_bias_reflectivity) {
            measured += config_.dark_bias_m * (1.0 - reflectivity / config_.dark_bias_reflectivity);
        }
    }
    if (config_.drift_enabled) {
        measured += config_.drift_amplitude_m *
                    (1.0 - std::exp(-std::max(0.0, pulse.time_s) / config_.drift_time_constant_s));
    }
    if (config_.noise_enabled) {
        const double gain =
            std::clamp(std::sqrt(1.0 / echo->peak), 1.0, config_.noise_sigma_cap_factor);
        measured += config_.NoiseSigma0M() * gain * rng.Normal();
    }
    Encode(measured, rng, lost, r);
    if (r.beam.status != core::BeamStatus::kOk || r.label == core::BeamLabel::kSpike) {
        return r;
    }

    // Truth: surfaces are runs of sub-ray hits chained by gaps <= tol; the echo is mixed when
    // its noise-free range is farther than tol from every surface (docs/sensor-model.md).
    const double tol = config_.mixed_tolerance_m;
    const double c = echo->centroid_m;
    const auto gap = [c](double lo, double hi) {
        return c < lo ? lo - c : (c > hi ? c - hi : 0.0);
    };
    double nearest = gap(r_lo, r_hi);
    if (!one_group) {
        nearest = std::numeric_limits<double>::infinity();
        double lo = samples[0].range_m;
        double hi = lo;
        for (std::size_t k = 1; k <= n; ++k) {
            if (k < n && samples[k].range_m - hi <= tol) {
                hi = samples[k].range_m;
                continue;
            }
            nearest = std::min(nearest, gap(lo, hi));
            if (k < n) {
                lo = samples[k].range_m;
                hi = lo;
            }
        }
    }
    r.label = nearest > tol ? core::BeamLabel::kMixed : core::BeamLabel::kValid;
    return r;
}

}  // namespace casmap::sensor_models
