#pragma once

// The settable part of the Kalman mapper mode (KalmanMapperConfig, kalman_mapper.hpp): the
// LMS 200 noise model and the Mahalanobis gate. Kept apart from the mapper so filter parameter
// sets (filter_params.hpp) can carry it without the mapper's headers.

namespace casmap::mapper {

/// Height variance of one point, the noise model of elevation_mapping's laser sensor processor:
///   var_z = u_z^2 range_sigma^2 + (1 - u_z^2) (beam_constant + beam_angle * l)^2,
/// u_z the unit beam direction's world z, l the range. Defaults: the LMS 200.
struct KalmanNoiseConfig {
    double range_sigma_m = 0.005;         // LMS 200 statistical error, 1 sigma (mm mode)
    double beam_constant_m = 0.0;         // lateral spread at zero range
    double beam_angle_rad = 0.0022;       // half the LMS 200's ~0.25 deg beam divergence
    double min_variance_m2 = 1e-6;        // floor of a cell's variance (1 mm sigma)
    double mahalanobis_gate = 2.5;        // elevation_mapping's default threshold
    double multi_height_noise_m2 = 1e-4;  // variance added per measurement outside the gate
    /// Throws InputError naming the field ("kalman.<field>") and the rule.
    void Validate() const;
};

}  // namespace casmap::mapper
