#pragma once

// Commanded joint profiles of the table: a periodic roll/pitch oscillation and the carriage's
// trapezoidal speed schedule (constant acceleration ramps, cruise, constant deceleration).

#include <string>

namespace casmap::rig {

enum class ProfileShape { kSinusoid, kTriangle };

/// "sinusoid" | "triangle"; throws InputError naming `field` otherwise.
[[nodiscard]] ProfileShape ParseProfileShape(const std::string& text, const std::string& field);
[[nodiscard]] const char* ProfileShapeName(ProfileShape shape);

/// Oscillation centre +- amplitude with a period. Sinusoid: c + A sin(2 pi t / T + phase).
/// Triangle: same start and phase convention, constant rate 4 A / T between the extremes.
struct AngleProfile {
    ProfileShape shape = ProfileShape::kSinusoid;
    double center_deg = 0.0;
    double amplitude_deg = 0.0;
    double period_s = 2.0;
    double phase_deg = 0.0;
};

struct ProfileSample {
    double value_rad = 0.0;
    double rate_rad_s = 0.0;
};

/// The commanded angle and rate at time t (s).
[[nodiscard]] ProfileSample EvaluateProfile(const AngleProfile& profile, double t_s);

/// Largest |rate| of the profile (deg/s): 2 pi A / T for a sinusoid, 4 A / T for a triangle.
[[nodiscard]] double PeakRateDegS(const AngleProfile& profile);

/// Carriage travel: accelerate from rest over ramp_s, cruise, decelerate over ramp_s.
struct SpeedSchedule {
    double start_m = 0.0;
    double speed_m_s = 1.0;
    double ramp_s = 0.5;
    double cruise_s = 0.0;

    [[nodiscard]] double Duration() const { return 2.0 * ramp_s + cruise_s; }
    /// Position (m) and speed (m/s) at time t; constant outside [0, Duration()].
    [[nodiscard]] ProfileSample Evaluate(double t_s) const;
};

}  // namespace casmap::rig
