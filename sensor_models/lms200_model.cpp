#include "casmap/sensor_models/lms200_model.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>

#include "casmap/sensor_models/lms200_internal.hpp"

// Lms200Model's geometry and timing: the sub-ray pattern and weights, beam angles and time
// offsets, empty scans, per-pulse sub-rays and material biases. Return formation is in
// lms200_return.cpp, the waveform in waveform.cpp, PulseRng in pulse_rng.cpp.

namespace casmap::sensor_models {

namespace {

constexpr double kTwoPi = 2.0 * std::numbers::pi;
constexpr std::uint64_t kBiasTag = 0x6d6174657269616cULL;  // "material"
// Material biases of the first surface ids, drawn once per model (the same values).
constexpr std::size_t kBiasTableSize = 256;

}  // namespace

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

}  // namespace casmap::sensor_models
