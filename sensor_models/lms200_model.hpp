#pragma once

#include <Eigen/Core>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <span>
#include <vector>

#include "casmap/core/pose.hpp"
#include "casmap/core/scan.hpp"
#include "casmap/sensor_models/lms200_config.hpp"

namespace casmap::sensor_models {

/// Largest number of sub-rays per pulse (subrays_per_pulse = 37).
inline constexpr std::size_t kMaxSubrays = 37;

/// splitmix64 finaliser (Steele, Lea, Flood 2014): the mixing step of every seed below.
/// Inline: it runs several times per pulse.
[[nodiscard]] inline std::uint64_t SplitMix64(std::uint64_t x) {
    std::uint64_t z = x + 0x9E3779B97F4A7C15ULL;
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ULL;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBULL;
    return z ^ (z >> 31);
}

/// Deterministic random numbers for one pulse: a splitmix64 stream seeded from
/// (run seed, scan index, beam index, stream tag), so results never depend on thread count
/// or evaluation order.
class PulseRng {
public:
    PulseRng(std::uint64_t seed,
             std::uint64_t scan_index,
             std::uint32_t beam,
             std::uint32_t stream);
    /// SplitMix64(seed), computed once per run: the same stream without that first hash.
    struct SeedKey {
        std::uint64_t hash = 0;
    };
    PulseRng(SeedKey key, std::uint64_t scan_index, std::uint32_t beam, std::uint32_t stream);
    [[nodiscard]] std::uint64_t NextU64() {
        state_ += 0x9E3779B97F4A7C15ULL;
        return SplitMix64(state_);
    }
    /// Uniform in [0, 1).
    [[nodiscard]] double Uniform() { return static_cast<double>(NextU64() >> 11) * 0x1.0p-53; }
    /// Standard normal (a 256-layer ziggurat: one 64-bit draw for 98.5 % of the values).
    [[nodiscard]] double Normal();

private:
    std::uint64_t state_;
};

/// One sub-ray of a pulse, sensor frame (x forward, y left, z up), metres.
struct Subray {
    Eigen::Vector3d origin = Eigen::Vector3d::Zero();
    Eigen::Vector3d direction = Eigen::Vector3d::UnitX();  // unit
};

/// Where a pulse leaves and its rotated transverse basis, in the frame of a pose.
struct PulseFrame {
    Eigen::Vector3d origin = Eigen::Vector3d::Zero();  // sensor origin
    Eigen::Vector3d axis = Eigen::Vector3d::UnitX();   // beam axis (unit)
    Eigen::Vector3d u1 = Eigen::Vector3d::UnitY();     // transverse, in the scan plane (rotated)
    Eigen::Vector3d u2 = Eigen::Vector3d::UnitZ();     // transverse, across it (rotated)
};

/// What one sub-ray hit, as the sensor model needs it.
struct SubrayHit {
    double distance_m = std::numeric_limits<double>::infinity();  // along the sub-ray; inf = miss
    double cos_incidence = 1.0;     // |cos| of the angle between the ray and the surface normal
    double reflectivity = 0.0;      // diffuse reflectance at 905 nm, 0..1
    std::uint32_t surface_id = 0;   // identifies the material for the per-material bias
    bool retro_reflective = false;  // a retro-reflector: energy x retro_gain, may saturate

    [[nodiscard]] bool valid() const {
        return distance_m < std::numeric_limits<double>::infinity();
    }
};

/// A pulse's sub-ray hits as parallel arrays (the simulator's hit batch): element i belongs to
/// sub-ray i; distance_m[i] = +inf (or NaN) marks a miss, whose other fields are not read.
/// Equivalent to the SubrayHit list {double(distance_m[i]), double(cos_incidence[i]),
/// double(reflectivity[i]), surface_id[i], retro_reflective[i] != 0}.
struct SubrayHitArrays {
    const float* distance_m = nullptr;
    const float* cos_incidence = nullptr;
    const float* reflectivity = nullptr;
    const std::uint8_t* retro_reflective = nullptr;  // non-zero: a retro-reflector
    const std::uint32_t* surface_id = nullptr;
    std::size_t count = 0;
};

/// One sub-ray echo in the range domain: its range and received energy (units of the
/// detection threshold T: a full-footprint 10 % target at R10 gives exactly 1).
struct EchoSample {
    double range_m = 0.0;
    double energy = 0.0;
};

/// A lobe of the received waveform: its peak, the bounds used for the centroid, the centroid.
struct Lobe {
    double peak = 0.0;          // waveform value at the peak (units of T)
    double peak_range_m = 0.0;  // where the peak is
    double lo_m = 0.0;          // lobe bounds: neighbouring minima or lobe_bound_fraction x peak
    double hi_m = 0.0;
    double centroid_m = 0.0;  // energy centroid of the waveform over [lo_m, hi_m]
};

/// Reference algorithm (sensor_model.md 4.3): the waveform sum_i E_i g(x - r_i), g a Gaussian
/// of FWHM echo_width_m and unit height; every local maximum is a lobe, bounded by its
/// neighbouring minima and by bound_fraction x its peak; its centroid is exact (closed-form
/// integrals of the Gaussians over the bounds). `sorted` must be sorted by range. Writes the
/// lobes nearest first into `out` and returns their count. Never allocates.
std::size_t WaveformLobes(std::span<const EchoSample> sorted,
                          double echo_width_m,
                          double bound_fraction,
                          std::span<Lobe> out);

/// Closed form for hits that span much less than the echo width: one lobe at the
/// energy-weighted mean range, peak sum(E) exp(-var / (2 sigma^2)) (second order in spread),
/// bounds = the hits' extent. Any order.
[[nodiscard]] Lobe CompactLobe(std::span<const EchoSample> samples, double echo_width_m);

/// Energy fractions of the sub-rays of a Gaussian beam I ~ exp(-2 rho^2) (rho in units of the
/// 1/e^2 radius): each ring gets its annulus' energy, split evenly. Sums to 1.
/// Ring radii rho = 0, 0.4, 0.8, (1.0); counts 1, 6, 12, (18). Index 0 is the centre ray.
void SubrayWeights(int subrays_per_pulse, std::span<double> weights);

/// Outcome of one pulse: the beam as the scanner reports it plus its truth.
struct PulseResult {
    core::Beam beam;
    core::BeamLabel label = core::BeamLabel::kNoTarget;
    float true_range_m = std::numeric_limits<float>::quiet_NaN();  // centre ray's exact distance
    /// Noise-free range of the detected echo (NaN when none): what labels are judged on.
    double echo_range_m = std::numeric_limits<double>::quiet_NaN();
};

/// Where and when a pulse is fired; only the sun model needs the world direction.
struct PulseContext {
    std::uint64_t scan_index = 0;
    std::uint32_t beam = 0;
    double time_s = 0.0;  // scanner time since power-on (warm-up drift)
    Eigen::Vector3d beam_direction_world = Eigen::Vector3d::UnitX();
};

/// The SICK LMS 200 sensor model: beam geometry and timing, footprint sub-rays, return
/// formation, detection, noise, codes and truth labels. Immutable and thread-safe; all
/// randomness comes from PulseRng(seed, scan, beam, ...).
class Lms200Model {
public:
    /// Validates the config (throws InputError naming the field).
    explicit Lms200Model(const Lms200Config& config, std::uint64_t seed = 0);

    [[nodiscard]] const Lms200Config& config() const { return config_; }
    [[nodiscard]] std::uint64_t seed() const { return seed_; }

    /// 181 (1 deg / 180), 361, 101, 201 or 401 beams.
    [[nodiscard]] std::size_t BeamCount() const { return beam_count_; }
    /// Angle of beam 0 about sensor +z (rad): -fov/2.
    [[nodiscard]] double StartAngleRad() const;
    [[nodiscard]] double AngleStepRad() const;
    [[nodiscard]] double BeamAngleRad(std::size_t beam) const;
    /// Seconds from beam 0 to beam i: turn (i mod turns) of the 75 Hz mirror plus the angular
    /// position within the turn (a 180 deg sweep takes half a turn).
    [[nodiscard]] double BeamTimeOffsetS(std::size_t beam) const;
    /// The largest BeamTimeOffsetS of the scan (s).
    [[nodiscard]] double MaxBeamTimeOffsetS() const { return max_beam_offset_s_; }
    /// Mirror turns per scan: 1 (1 deg), 2 (0.5 deg), 4 (0.25 deg).
    [[nodiscard]] int TurnsPerScan() const { return turns_; }
    /// Time for one complete scan (s): turns x 1/75.
    [[nodiscard]] double ScanPeriodS() const;
    /// An empty Scan with the angles, beam period and per-beam time offsets filled in.
    [[nodiscard]] core::Scan MakeScan(double stamp_s) const;

    /// Sub-rays per pulse: 1 when ideal, else subrays_per_pulse. Index 0 is the centre ray.
    [[nodiscard]] std::size_t SubrayCount() const { return subray_count_; }
    /// How far sub-rays must be traced (m).
    [[nodiscard]] double TraceRangeM() const { return config_.max_trace_range_m; }
    /// The sub-rays of pulse (scan_index, beam) in the sensor frame: a cone from the exit
    /// aperture (diameter D0) with the divergence of the beam, the ring pattern rotated by a
    /// per-pulse random angle. out.size() must be SubrayCount().
    void PulseSubrays(std::uint64_t scan_index, std::size_t beam, std::span<Subray> out) const;
    /// The same sub-rays expressed in the frame of `frame_T_sensor` (e.g. world_T_sensor).
    void PulseSubrays(std::uint64_t scan_index,
                      std::size_t beam,
                      const core::Pose& frame_T_sensor,
                      std::span<Subray> out) const;
    /// The beam axis and per-pulse rotated transverse basis of pulse (scan_index, beam).
    [[nodiscard]] PulseFrame PulseBasis(std::uint64_t scan_index,
                                        std::size_t beam,
                                        const core::Pose& frame_T_sensor) const;
    /// Calls fn(i, origin, direction) for each of the SubrayCount() sub-rays of a pulse
    /// (the same rays as PulseSubrays, without a buffer; for the simulator's hot loop).
    template <class Fn>
    void ForEachSubray(const PulseFrame& f, Fn&& fn) const {
        for (std::size_t i = 0; i < subray_count_; ++i) {
            const Eigen::Vector3d t = ring_cos_[i] * f.u1 + ring_sin_[i] * f.u2;
            fn(i, Eigen::Vector3d(f.origin + origin_offset_[i] * t),
               Eigen::Vector3d(dir_scale_[i] * (f.axis + dir_slope_[i] * t)));
        }
    }
    /// The same rays as ForEachSubray rounded to float, written structure-of-arrays (the
    /// simulator's ray batch): each array receives SubrayCount() values. Bit-identical to
    /// casting ForEachSubray's rays; a loop the compiler can vectorise.
    void SubraysSoA(const PulseFrame& f,
                    float* __restrict ox,
                    float* __restrict oy,
                    float* __restrict oz,
                    float* __restrict dx,
                    float* __restrict dy,
                    float* __restrict dz) const {
        for (std::size_t i = 0; i < subray_count_; ++i) {
            const double c = ring_cos_[i];
            const double s = ring_sin_[i];
            const double tx = c * f.u1.x() + s * f.u2.x();
            const double ty = c * f.u1.y() + s * f.u2.y();
            const double tz = c * f.u1.z() + s * f.u2.z();
            const double off = origin_offset_[i];
            const double slope = dir_slope_[i];
            const double scale = dir_scale_[i];
            ox[i] = static_cast<float>(f.origin.x() + off * tx);
            oy[i] = static_cast<float>(f.origin.y() + off * ty);
            oz[i] = static_cast<float>(f.origin.z() + off * tz);
            dx[i] = static_cast<float>(scale * (f.axis.x() + slope * tx));
            dy[i] = static_cast<float>(scale * (f.axis.y() + slope * ty));
            dz[i] = static_cast<float>(scale * (f.axis.z() + slope * tz));
        }
    }
    /// The return of one pulse from its sub-ray hits (hits[i] belongs to PulseSubrays' ray i).
    [[nodiscard]] PulseResult FormReturn(const PulseContext& pulse,
                                         std::span<const SubrayHit> hits) const;
    /// The same return from the hits as parallel arrays (bit-identical to the span overload
    /// on the equivalent SubrayHit list; no per-hit struct, vectorised echo energies).
    [[nodiscard]] PulseResult FormReturn(const PulseContext& pulse,
                                         const SubrayHitArrays& hits) const;
    /// The per-run bias of a material (m), drawn from the seed and the surface id.
    [[nodiscard]] double MaterialBiasM(std::uint32_t surface_id) const;

private:
    template <class Hits>
    [[nodiscard]] PulseResult FormReturnImpl(const PulseContext& pulse, const Hits& hits) const;
    template <class Hits>
    [[nodiscard]] PulseResult IdealReturn(const Hits& hits) const;
    void Encode(double range_m, PulseRng& rng, core::BeamLabel lost, PulseResult& out) const;
    void SetCode(core::BeamStatus status, core::BeamLabel label, PulseResult& out) const;
    void SetSpike(double range_m, PulseResult& out) const;
    // BeamTimeOffsetS from the beam index (beam_offset_s_ caches it per beam).
    [[nodiscard]] double ComputeBeamTimeOffsetS(std::size_t beam) const;

    Lms200Config config_;
    std::uint64_t seed_ = 0;
    std::size_t beam_count_ = 0;
    std::size_t subray_count_ = 0;
    int turns_ = 1;
    double weights_[kMaxSubrays] = {};
    // Sub-ray i of the unrotated pattern: transverse unit vector (cos, sin) of its azimuth,
    // origin offset rho a0 and direction slope rho theta / 2 (normalised by dir_scale_).
    double ring_cos_[kMaxSubrays] = {};
    double ring_sin_[kMaxSubrays] = {};
    double origin_offset_[kMaxSubrays] = {};
    double dir_slope_[kMaxSubrays] = {};
    double dir_scale_[kMaxSubrays] = {};
    double sure_peak_ = 1.0;          // peak with detection probability kSureProbability
    PulseRng::SeedKey seed_key_;      // first hash of every PulseRng, from the seed
    std::uint64_t bias_key_ = 0;      // first hash of the material biases, from the seed
    std::vector<double> bias_table_;  // MaterialBiasM of the first surface ids
    std::vector<double> beam_cos_;
    std::vector<double> beam_sin_;
    std::vector<double> beam_offset_s_;  // BeamTimeOffsetS per beam
    double max_beam_offset_s_ = 0.0;
};

}  // namespace casmap::sensor_models
