#include "casmap/scenegen/domain.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "casmap/core/check.hpp"
#include "casmap/core/input_error.hpp"
#include "casmap/scenegen/scene_writer.hpp"

namespace casmap::scenegen {
namespace {

constexpr double kMaxRateDegS = 37.5;  // the table's joint rate limit (Fig. 2 caption)

std::string Text(const Range& r) {
    return "[" + FormatNumber(r.min) + ", " + FormatNumber(r.max) + "]";
}

// A period at least long enough for amplitude A to stay within the rate limit.
double DrawPeriod(const Range& period, double amplitude_deg, Rng& rng) {
    const double shortest = 2.0 * std::numbers::pi * amplitude_deg / kMaxRateDegS;
    return rng.Draw({std::max(period.min, shortest), std::max(period.max, shortest)});
}

}  // namespace

std::vector<RangeField> DomainConfig::Ranges() {
    return {{"table_speed_m_s", &table_speed_m_s, 0.01, 1.0},
            {"sensor_height_m", &sensor_height_m, 0.3, 3.0},
            {"mount_pitch_deg", &mount_pitch_deg, 25.0, 40.0},
            {"lateral_offset_m", &lateral_offset_m, -2.0, 2.0},
            {"roll_amplitude_deg", &roll_amplitude_deg, 0.0, 15.0},
            {"roll_period_s", &roll_period_s, 0.5, 60.0},
            {"pitch_amplitude_deg", &pitch_amplitude_deg, 0.0, 7.5},
            {"pitch_period_s", &pitch_period_s, 0.5, 60.0},
            {"vehicle_speed_m_s", &vehicle_speed_m_s, 0.1, 3.0},
            {"vehicle_mount_pitch_deg", &vehicle_mount_pitch_deg, 0.0, 45.0},
            {"vehicle_mount_height_m", &vehicle_mount_height_m, 0.1, 1.5},
            {"noise_sigma0_m", &noise_sigma0_m, 0.0, 0.05},
            {"divergence_rad", &divergence_rad, 0.0, 0.015},
            {"echo_width_m", &echo_width_m, 0.1, 5.0},
            {"lobe_bound_fraction", &lobe_bound_fraction, 0.01, 0.9},
            {"p_short", &p_short, 0.0, 0.1},
            {"p_dropout", &p_dropout, 0.0, 0.5},
            {"position_bias_m", &position_bias_m, -1.0, 1.0},
            {"attitude_bias_deg", &attitude_bias_deg, -10.0, 10.0},
            {"position_jitter_m", &position_jitter_m, 0.0, 0.1},
            {"attitude_jitter_deg", &attitude_jitter_deg, 0.0, 5.0}};
}

void DomainConfig::Validate(const std::string& where) const {
    const core::Check check(where, "domain.");
    DomainConfig copy = *this;  // Ranges() hands out pointers into its object
    for (const RangeField& f : copy.Ranges()) {
        const Range& r = *f.range;
        if (!(std::isfinite(r.min) && std::isfinite(r.max) && f.lo <= r.min && r.min <= r.max &&
              r.max <= f.hi)) {
            check.Fail(
                f.key, Text(r),
                "allowed: " + FormatNumber(f.lo) + " <= min <= max <= " + FormatNumber(f.hi));
        }
    }
    double total = 0.0;
    for (const double w : motion_weights) {
        if (!(w >= 0.0 && std::isfinite(w))) {
            check.Fail("motion_weights", FormatNumber(w), "each weight must be finite and >= 0");
        }
        total += w;
    }
    if (!(total > 0.0)) {
        check.Fail("motion_weights", "all 0", "at least one weight must be > 0");
    }
    if (angular_resolutions_deg.empty()) {
        check.Fail("angular_resolutions_deg", "[]", "list at least one of 0.25, 0.5, 1");
    }
    for (const double r : angular_resolutions_deg) {
        if (r != 0.25 && r != 0.5 && r != 1.0) {
            check.Fail("angular_resolutions_deg", FormatNumber(r), "allowed: 0.25, 0.5, 1");
        }
    }
    if (range_modes.empty()) {
        check.Fail("range_modes", "[]", "list at least one of 8m, 16m, 32m, 80m");
    }
    for (const std::string& m : range_modes) {
        if (m != "8m" && m != "16m" && m != "32m" && m != "80m") {
            check.Fail("range_modes", m, "allowed: 8m, 16m, 32m (mm units), 80m (cm units)");
        }
    }
    if (!(triangle_probability >= 0.0 && triangle_probability <= 1.0)) {
        check.Fail("triangle_probability", FormatNumber(triangle_probability), "allowed: 0..1");
    }
    if (!(pose_error_probability >= 0.0 && pose_error_probability <= 1.0)) {
        check.Fail("pose_error_probability", FormatNumber(pose_error_probability), "allowed: 0..1");
    }
}

DomainDraw DrawDomain(const DomainConfig& k, Rng& rng) {
    DomainDraw d;
    d.motion = kMotionNames[rng.Pick(k.motion_weights.data(), k.motion_weights.size())];
    const bool vehicle = d.motion == std::string("vehicle");
    const double table_speed = rng.Draw(k.table_speed_m_s);
    const double vehicle_speed = rng.Draw(k.vehicle_speed_m_s);
    d.speed_m_s = vehicle ? vehicle_speed : table_speed;
    d.sensor_height_m = rng.Draw(k.sensor_height_m);
    const double table_pitch = rng.Draw(k.mount_pitch_deg);
    const double vehicle_pitch = rng.Draw(k.vehicle_mount_pitch_deg);
    d.mount_pitch_deg = vehicle ? vehicle_pitch : table_pitch;
    d.lateral_offset_m = rng.Draw(k.lateral_offset_m);
    d.roll_amplitude_deg = rng.Draw(k.roll_amplitude_deg);
    d.roll_period_s = DrawPeriod(k.roll_period_s, d.roll_amplitude_deg, rng);
    d.pitch_amplitude_deg = rng.Draw(k.pitch_amplitude_deg);
    d.pitch_period_s = DrawPeriod(k.pitch_period_s, d.pitch_amplitude_deg, rng);
    d.pitch_center_deg = rng.Draw({25.0 + d.pitch_amplitude_deg, 40.0 - d.pitch_amplitude_deg});
    d.roll_triangle = rng.Chance(k.triangle_probability);
    d.pitch_triangle = rng.Chance(k.triangle_probability);
    d.vehicle_mount_height_m = rng.Draw(k.vehicle_mount_height_m);
    d.angular_resolution_deg =
        k.angular_resolutions_deg[rng.Below(k.angular_resolutions_deg.size())];
    d.field_of_view_deg = d.angular_resolution_deg == 0.25 ? 100.0 : 180.0;
    d.range_mode = k.range_modes[rng.Below(k.range_modes.size())];
    d.noise_sigma0_m = rng.Draw(k.noise_sigma0_m);
    d.divergence_rad = rng.Draw(k.divergence_rad);
    d.echo_width_m = rng.Draw(k.echo_width_m);
    d.lobe_bound_fraction = rng.Draw(k.lobe_bound_fraction);
    d.p_short = rng.Draw(k.p_short);
    d.p_dropout = rng.Draw(k.p_dropout);
    d.pose_error = rng.Chance(k.pose_error_probability);
    for (int i = 0; i < 3; ++i) {
        d.position_bias_m[i] = rng.Draw(k.position_bias_m);
        d.attitude_bias_deg[i] = rng.Draw(k.attitude_bias_deg);
    }
    d.position_jitter_m = rng.Draw(k.position_jitter_m);
    d.attitude_jitter_deg = rng.Draw(k.attitude_jitter_deg);
    d.sensor_seed = rng.Next();
    d.pose_error_seed = rng.Next();
    return d;
}

}  // namespace casmap::scenegen
