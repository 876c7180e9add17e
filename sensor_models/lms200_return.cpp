#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>

#include "casmap/sensor_models/lms200_internal.hpp"
#include "casmap/sensor_models/lms200_model.hpp"
#include "casmap/sensor_models/scratch_array.hpp"

// Lms200Model's return formation (docs/sensor-model.md 4.2-4.5): echo energies of the sub-ray
// hits, spikes, dropouts, sun, detection of the first lobe, bias, noise, range codes and the
// truth label of one pulse.

namespace casmap::sensor_models {

namespace {

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
