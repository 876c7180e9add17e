#pragma once

// Domain randomisation for datasets: the ranges a spec gives for the rig (table or vehicle),
// the LMS 200's settings and the pose-estimate error, and one draw of them per sample. Plain
// numbers only: pipeline/ turns a draw into rig and sensor configs. Limits are the table's
// (Fig. 2 caption: |roll| <= 15 deg, pitch 25..40 deg nose down, rates <= 37.5 deg/s,
// v <= 1 m/s), the vehicle's (v <= 3 m/s) and the LMS 200's documented settings.

#include <Eigen/Core>
#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "casmap/scenegen/random.hpp"
#include "casmap/scenegen/scene_generator.hpp"

namespace casmap::scenegen {

/// Motions in the order of DomainConfig::motion_weights.
inline constexpr std::array<const char*, 5> kMotionNames = {"T", "TR", "TP", "TRP", "vehicle"};

struct DomainConfig {
    std::array<double, 5> motion_weights{1.0, 1.0, 1.0, 1.0, 1.0};  // T, TR, TP, TRP, vehicle
    // Table.
    Range table_speed_m_s{0.3, 1.0};
    Range sensor_height_m{0.8, 1.3};
    Range mount_pitch_deg{25.0, 40.0};  // T, TR (nose down)
    Range lateral_offset_m{-0.3, 0.3};  // course centre line from the linear axis
    Range roll_amplitude_deg{3.0, 14.0};
    Range roll_period_s{2.0, 6.0};
    Range pitch_amplitude_deg{2.0, 7.0};
    Range pitch_period_s{1.5, 5.0};
    double triangle_probability = 0.3;  // roll/pitch profile triangular, else sinusoidal
    // Vehicle.
    Range vehicle_speed_m_s{0.5, 1.5};
    Range vehicle_mount_pitch_deg{9.0, 14.0};
    Range vehicle_mount_height_m{0.3, 0.45};  // above the chassis centre of mass
    // LMS 200 (docs/sensor-model.md; sensor_models/lms200_config.hpp).
    std::vector<double> angular_resolutions_deg{1.0, 0.5, 0.25};  // 0.25 uses the 100 deg FOV
    std::vector<std::string> range_modes{"8m", "16m"};            // 8m, 16m, 32m (mm), 80m (cm)
    Range noise_sigma0_m{0.003, 0.010};    // datasheet 5 mm 1 sigma in mm mode
    Range divergence_rad{0.003, 0.008};    // literature bracket 3-15 mrad
    Range echo_width_m{0.7, 1.3};          // pulse-width (mixed pixel) scale
    Range lobe_bound_fraction{0.1, 0.25};  // where merged echoes split
    Range p_short{0.0, 5e-4};              // spurious short ranges per pulse
    Range p_dropout{0.0, 3e-3};            // lost pulses
    // Pose-estimate error (rig/pose_error.hpp), applied with this probability.
    double pose_error_probability = 0.3;
    Range position_bias_m{-0.01, 0.01};
    Range attitude_bias_deg{-0.5, 0.5};
    Range position_jitter_m{0.0, 0.005};
    Range attitude_jitter_deg{0.0, 0.2};

    [[nodiscard]] std::vector<RangeField> Ranges();
    /// Throws InputError "<where>: domain.<key> = <value> (<rule>)" for the first bad field.
    void Validate(const std::string& where) const;
};

/// One sample's drawn rig, sensor and pose-error values (all of them go to the manifest).
struct DomainDraw {
    std::string motion = "T";
    double speed_m_s = 1.0;
    double sensor_height_m = 1.0;
    double mount_pitch_deg = 40.0;  // table T/TR, or the vehicle's
    double lateral_offset_m = 0.0;
    double roll_amplitude_deg = 0.0;
    double roll_period_s = 2.0;
    bool roll_triangle = false;  // triangular profile (constant rate 4 A / T), else sinusoid
    double pitch_center_deg = 32.5;
    double pitch_amplitude_deg = 0.0;
    double pitch_period_s = 2.0;
    bool pitch_triangle = false;
    double vehicle_mount_height_m = 0.35;
    double angular_resolution_deg = 1.0;
    double field_of_view_deg = 180.0;
    std::string range_mode = "8m";
    double noise_sigma0_m = 0.005;
    double divergence_rad = 0.0044;
    double echo_width_m = 1.0;
    double lobe_bound_fraction = 0.15;
    double p_short = 2e-4;
    double p_dropout = 1e-3;
    bool pose_error = false;
    Eigen::Vector3d position_bias_m = Eigen::Vector3d::Zero();
    Eigen::Vector3d attitude_bias_deg = Eigen::Vector3d::Zero();
    double position_jitter_m = 0.0;
    double attitude_jitter_deg = 0.0;
    std::uint64_t sensor_seed = 1;      // simulator noise
    std::uint64_t pose_error_seed = 1;  // pose-error noise
};

/// Draws every value (the same number of draws whatever the motion, so one field's change
/// never shifts another's). Roll/pitch periods are drawn above 2 pi A / 37.5 deg/s so the
/// table's rate limit holds; the pitch centre keeps centre +- amplitude within 25..40 deg.
[[nodiscard]] DomainDraw DrawDomain(const DomainConfig& config, Rng& rng);

}  // namespace casmap::scenegen
