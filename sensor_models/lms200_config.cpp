#include "casmap/sensor_models/lms200_config.hpp"

#include <cmath>
#include <string>

#include "casmap/core/check.hpp"
#include "casmap/core/text.hpp"

namespace casmap::sensor_models {

void Lms200Config::Validate() const {
    const core::Check check("", "lms200.");
    const double res = angular_resolution_deg;
    check.That(res == 1.0 || res == 0.5 || res == 0.25, "angular_resolution_deg", res,
               "allowed: 0.25, 0.5, 1");
    check.That(field_of_view_deg == 180.0 || field_of_view_deg == 100.0, "field_of_view_deg",
               field_of_view_deg, "allowed: 100, 180");
    check.That(res != 0.25 || field_of_view_deg == 100.0, "field_of_view_deg", field_of_view_deg,
               "0.25 deg resolution needs the 100 deg field of view");
    check.Positive("max_trace_range_m", max_trace_range_m);
    check.InRange("spot_diameter_at_exit_m", spot_diameter_at_exit_m, 0.0, 1.0);
    check.InRange("divergence_rad", divergence_rad, 0.0, 0.1);
    check.That(subrays_per_pulse == 1 || subrays_per_pulse == 7 || subrays_per_pulse == 19 ||
                   subrays_per_pulse == 37,
               "subrays_per_pulse", subrays_per_pulse, "allowed: 1, 7, 19, 37");
    check.Positive("echo_width_m", echo_width_m);
    check.That(lobe_bound_fraction > 0.0 && lobe_bound_fraction < 1.0, "lobe_bound_fraction",
               lobe_bound_fraction, "allowed: 0 < x < 1");
    check.InRange("compact_spread_m", compact_spread_m, 0.0, 0.5 * echo_width_m);
    check.Positive("r10_m", r10_m);
    check.That(r10_reflectivity > 0.0 && r10_reflectivity <= 1.0, "r10_reflectivity",
               r10_reflectivity, "allowed: 0 < x <= 1");
    check.Positive("soft_edge_db", soft_edge_db);
    check.Probability("low_signal_fraction", low_signal_fraction);
    check.InRange("min_range_m", min_range_m, 0.0, 10.0);
    check.InRange("retro_gain", retro_gain, 1.0, 1e5);
    check.InRange("saturation_peak", saturation_peak, 1.0, 1e12);
    check.Positive("noise_sigma0_mm_units_m", noise_sigma0_mm_units_m);
    check.Positive("noise_sigma0_cm_units_m", noise_sigma0_cm_units_m);
    check.InRange("noise_sigma_cap_factor", noise_sigma_cap_factor, 1.0, 100.0);
    check.InRange("material_bias_max_mm_units_m", material_bias_max_mm_units_m, 0.0, 1.0);
    check.InRange("material_bias_max_cm_units_m", material_bias_max_cm_units_m, 0.0, 1.0);
    check.InRange("dark_bias_m", dark_bias_m, -1.0, 1.0);
    check.Probability("dark_bias_reflectivity", dark_bias_reflectivity);
    check.InRange("drift_amplitude_m", drift_amplitude_m, -1.0, 1.0);
    check.Positive("drift_time_constant_s", drift_time_constant_s);
    check.Probability("p_wrap", p_wrap);
    check.Probability("p_short", p_short);
    check.Probability("p_rand", p_rand);
    check.Probability("p_dropout", p_dropout);
    const Eigen::Vector3d& sun = sun_direction_world;
    check.That(sun.allFinite() && sun.norm() > 0.0, "sun_direction_world",
               "[" + core::FormatNumber(sun.x()) + ", " + core::FormatNumber(sun.y()) + ", " +
                   core::FormatNumber(sun.z()) + "]",
               "must be a finite non-zero vector");
    check.InRange("sun_cone_deg", sun_cone_deg, 0.0, 90.0);
    check.InRange("sun_irradiance_w_m2", sun_irradiance_w_m2, 0.0, 1.0e4);
    check.Probability("p_sun", p_sun);
    check.Positive("mixed_tolerance_m", mixed_tolerance_m);
    check.That(target_min_weight > 0.0 && target_min_weight <= 1.0, "target_min_weight",
               target_min_weight, "allowed: 0 < x <= 1");
}

double Lms200Config::NoiseSigma0M() const {
    return format.units == core::RangeUnits::kMillimetre ? noise_sigma0_mm_units_m
                                                         : noise_sigma0_cm_units_m;
}

double Lms200Config::MaterialBiasMaxM() const {
    return format.units == core::RangeUnits::kMillimetre ? material_bias_max_mm_units_m
                                                         : material_bias_max_cm_units_m;
}

}  // namespace casmap::sensor_models
