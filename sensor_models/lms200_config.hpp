#pragma once

#include <Eigen/Core>
#include <cstdint>

#include "casmap/core/lms200.hpp"

namespace casmap::sensor_models {

/// How the reported range is formed from the footprint's sub-ray echoes
/// (shared/reference/sensor_model.md section 4.3; docs/sensor-model.md).
enum class ReturnAlgorithm : std::uint8_t {
    kWaveform,  // the range-domain waveform for every pulse (the reference)
    kAuto,      // closed form when the hits span <= compact_spread_m, else the waveform
};

/// Every parameter of the simulated SICK LMS 200. Sources: [V] verified, [M] datasheet or
/// literature as quoted, [A] assumption (shared/reference/sensor_model.md, sections 0 and 4).
/// Each error physics has its own switch so it can be turned off in isolation.
struct Lms200Config {
    // --- Geometry and telegram format -------------------------------------------------------
    double angular_resolution_deg = 1.0;  // [V] 1, 0.5 or 0.25 (sicktoolbox variants)
    double field_of_view_deg = 180.0;     // [V] 180 or 100; 0.25 deg needs 100
    core::Lms200Format format{};          // [V] 8 m mode in mm (the power-on default)
    /// [A] One centre ray per beam, exact distance, no footprint, noise, quantisation or errors.
    bool ideal = false;
    /// [A] Sub-rays are traced this far (m). A 100 % target at normal incidence falls 10 dB
    /// below the threshold at ~100 m with R10 = 10 m, so nothing beyond can be detected.
    double max_trace_range_m = 100.0;

    // --- Footprint (section 4.1) -----------------------------------------------------------
    double spot_diameter_at_exit_m = 0.013;  // [A] D0, like SICK LMS5xx HR (13 mm)
    double divergence_rad = 0.0044;          // [A] 0.25 deg full angle; bracket 3-15 mrad
    int subrays_per_pulse = 19;              // [A] 1, 7, 19 (default, HELIOS++ BSQ 3) or 37
    bool rotate_pattern_per_pulse = true;    // [A] fresh random rotation of the ring pattern

    // --- Return formation (sections 4.2, 4.3) ----------------------------------------------
    double echo_width_m = 1.0;          // [A]+[E] effective echo FWHM W in the range domain
    double lobe_bound_fraction = 0.15;  // [A]+[E] a lobe ends where it falls below 0.15 x peak
    ReturnAlgorithm return_algorithm = ReturnAlgorithm::kAuto;
    /// [A] kAuto: hits spanning at most this (m) use the closed form (weighted mean range and
    /// a second-order peak); the waveform centroid differs by < 0.25 mm at 0.15 m (unit test).
    double compact_spread_m = 0.15;

    // --- Detection (section 4.4) -----------------------------------------------------------
    double r10_m = 10.0;               // [M] datasheet: 10 m range at 10 % reflectivity
    double r10_reflectivity = 0.10;    // [M] the 10 % of the datasheet figure
    bool soft_threshold = true;        // [A] logistic detection probability around T
    double soft_edge_db = 1.5;         // [A] logistic scale in dB of E/T
    double low_signal_fraction = 0.5;  // [A] undetected lobe >= 0.5 T reports 8187, else 8191
    double min_range_m = 0.2;          // [A] closer echoes report 8191 (Gazebo SickLMS200 0.2 m)
    /// [A] Echo of a retro-reflector over that of a white (100 %) diffuser at the same range
    /// and incidence, per unit of its `reflectivity`: sheeting returns R_A ~ 250-600 cd/lx/m^2
    /// against 1/pi for a white Lambertian surface (docs/sensor-model.md "Retro-reflectors").
    double retro_gain = 1000.0;
    /// [A] A detected lobe whose peak reaches this (units of T) saturates the receiver: the
    /// scanner reports dazzle (8190). 50 dB above T; a white diffuser peaks at 2.5e4 T at the
    /// 0.2 m minimum range, so only retro-reflectors (within ~3 m by default) saturate.
    double saturation_peak = 1e5;

    // --- Range noise and bias (section 4.5); only on valid echoes ----------------------------
    bool noise_enabled = true;
    double noise_sigma0_mm_units_m = 0.005;  // [M] datasheet statistical error 1 sigma, mm mode
    double noise_sigma0_cm_units_m = 0.010;  // [A] cm mode
    double noise_sigma_cap_factor = 4.0;     // [A] sigma = sigma0 sqrt(T/E), in [1, 4] sigma0
    bool bias_enabled = true;
    double material_bias_max_mm_units_m = 0.015;  // [M] datasheet systematic error +-15 mm
    double material_bias_max_cm_units_m = 0.040;  // [M] datasheet, cm mode about +-4 cm
    double dark_bias_m = 0.008;                   // [A] +8 mm x (1 - rho / 0.5) for rho < 0.5
    double dark_bias_reflectivity = 0.5;          // [A] reflectivity where the dark term vanishes
    bool drift_enabled = false;                   // [M]/[A] warm-up drift A (1 - exp(-t / tau))
    double drift_amplitude_m = 0.010;             // [A] placeholder A
    double drift_time_constant_s = 3600.0;        // [A] placeholder tau

    // --- Artifacts and missing data (sections 4.4, 4.6) ------------------------------------
    bool wrap_enabled = true;  // [A] 16 m mode: undetected overflow wraps modulo 16.384 m
    double p_wrap = 1.0;       // [A] probability that an over-range echo wraps
    bool spikes_enabled = true;
    double p_short = 2e-4;  // [A] per pulse, range ~ U(min_range, true range)
    double p_rand = 5e-5;   // [A] per pulse, range ~ U(min_range, max range of the mode)
    bool dropout_enabled = true;
    double p_dropout = 1e-3;                             // [A] per pulse -> 8191
    bool sun_enabled = false;                            // [A] sun dazzle
    Eigen::Vector3d sun_direction_world{0.0, 0.0, 1.0};  // [A] towards the sun, world frame
    double sun_cone_deg = 2.0;                           // [A] beam within 2 deg -> 8190
    double sun_irradiance_w_m2 = 0.0;                    // [A] diffuse sunlight on the scene
    double p_sun = 0.01;                                 // [A] extra dropout per 1000 W/m^2

    // --- Truth labels (docs/sensor-model.md) ------------------------------------------------
    /// [A] A valid echo is labelled mixed when its noise-free range lies farther than this
    /// from every surface group the footprint hit (sub-ray hits chained by gaps <= this).
    /// 60 mm is the paper's Fig. 3 criterion.
    double mixed_tolerance_m = 0.06;
    /// [A] A target is "within range" when sub-rays carrying at least this share of the
    /// footprint's weight hit surfaces closer than the mode's maximum range.
    double target_min_weight = 0.5;

    /// Throws InputError "lms200.<field> = <value> (<rule>)" for the first invalid field.
    void Validate() const;

    /// Standard deviation and bias bound for the configured units.
    [[nodiscard]] double NoiseSigma0M() const;
    [[nodiscard]] double MaterialBiasMaxM() const;
};

}  // namespace casmap::sensor_models
