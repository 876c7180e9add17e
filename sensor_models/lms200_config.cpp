#include "casmap/sensor_models/lms200_config.hpp"

#include <cmath>
#include <sstream>
#include <string>

#include "casmap/core/input_error.hpp"

namespace casmap::sensor_models {
namespace {

std::string Str(double v) {
    std::ostringstream s;
    s << v;
    return s.str();
}

[[noreturn]] void Reject(const std::string& field,
                         const std::string& value,
                         const std::string& rule) {
    throw MakeInputError("", "lms200." + field, value, rule);
}

void RequireRange(const char* field, double v, double lo, double hi) {
    if (!(std::isfinite(v) && v >= lo && v <= hi)) {
        Reject(field, Str(v), "allowed: " + Str(lo) + ".." + Str(hi));
    }
}

void RequirePositive(const char* field, double v) {
    if (!(std::isfinite(v) && v > 0.0)) {
        Reject(field, Str(v), "must be > 0");
    }
}

void RequireProbability(const char* field, double v) { RequireRange(field, v, 0.0, 1.0); }

}  // namespace

void Lms200Config::Validate() const {
    const double res = angular_resolution_deg;
    if (res != 1.0 && res != 0.5 && res != 0.25) {
        Reject("angular_resolution_deg", Str(res), "allowed: 0.25, 0.5, 1");
    }
    if (field_of_view_deg != 180.0 && field_of_view_deg != 100.0) {
        Reject("field_of_view_deg", Str(field_of_view_deg), "allowed: 100, 180");
    }
    if (res == 0.25 && field_of_view_deg != 100.0) {
        Reject("field_of_view_deg", Str(field_of_view_deg),
               "0.25 deg resolution needs the 100 deg field of view");
    }
    RequirePositive("max_trace_range_m", max_trace_range_m);
    RequireRange("spot_diameter_at_exit_m", spot_diameter_at_exit_m, 0.0, 1.0);
    RequireRange("divergence_rad", divergence_rad, 0.0, 0.1);
    if (subrays_per_pulse != 1 && subrays_per_pulse != 7 && subrays_per_pulse != 19 &&
        subrays_per_pulse != 37) {
        Reject("subrays_per_pulse", std::to_string(subrays_per_pulse), "allowed: 1, 7, 19, 37");
    }
    RequirePositive("echo_width_m", echo_width_m);
    if (!(lobe_bound_fraction > 0.0 && lobe_bound_fraction < 1.0)) {
        Reject("lobe_bound_fraction", Str(lobe_bound_fraction), "allowed: 0 < x < 1");
    }
    RequireRange("compact_spread_m", compact_spread_m, 0.0, 0.5 * echo_width_m);
    RequirePositive("r10_m", r10_m);
    if (!(r10_reflectivity > 0.0 && r10_reflectivity <= 1.0)) {
        Reject("r10_reflectivity", Str(r10_reflectivity), "allowed: 0 < x <= 1");
    }
    RequirePositive("soft_edge_db", soft_edge_db);
    RequireProbability("low_signal_fraction", low_signal_fraction);
    RequireRange("min_range_m", min_range_m, 0.0, 10.0);
    RequireRange("retro_gain", retro_gain, 1.0, 1e5);
    RequireRange("saturation_peak", saturation_peak, 1.0, 1e12);
    RequirePositive("noise_sigma0_mm_units_m", noise_sigma0_mm_units_m);
    RequirePositive("noise_sigma0_cm_units_m", noise_sigma0_cm_units_m);
    RequireRange("noise_sigma_cap_factor", noise_sigma_cap_factor, 1.0, 100.0);
    RequireRange("material_bias_max_mm_units_m", material_bias_max_mm_units_m, 0.0, 1.0);
    RequireRange("material_bias_max_cm_units_m", material_bias_max_cm_units_m, 0.0, 1.0);
    RequireRange("dark_bias_m", dark_bias_m, -1.0, 1.0);
    RequireProbability("dark_bias_reflectivity", dark_bias_reflectivity);
    RequireRange("drift_amplitude_m", drift_amplitude_m, -1.0, 1.0);
    RequirePositive("drift_time_constant_s", drift_time_constant_s);
    RequireProbability("p_wrap", p_wrap);
    RequireProbability("p_short", p_short);
    RequireProbability("p_rand", p_rand);
    RequireProbability("p_dropout", p_dropout);
    if (!(sun_direction_world.allFinite() && sun_direction_world.norm() > 0.0)) {
        Reject("sun_direction_world",
               "[" + Str(sun_direction_world.x()) + ", " + Str(sun_direction_world.y()) + ", " +
                   Str(sun_direction_world.z()) + "]",
               "must be a finite non-zero vector");
    }
    RequireRange("sun_cone_deg", sun_cone_deg, 0.0, 90.0);
    RequireRange("sun_irradiance_w_m2", sun_irradiance_w_m2, 0.0, 1.0e4);
    RequireProbability("p_sun", p_sun);
    RequirePositive("mixed_tolerance_m", mixed_tolerance_m);
    if (!(target_min_weight > 0.0 && target_min_weight <= 1.0)) {
        Reject("target_min_weight", Str(target_min_weight), "allowed: 0 < x <= 1");
    }
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
