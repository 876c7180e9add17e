#include "casmap/rig/profile.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "casmap/core/input_error.hpp"

namespace casmap::rig {

namespace {

constexpr double kDegToRad = std::numbers::pi / 180.0;

}  // namespace

ProfileShape ParseProfileShape(const std::string& text, const std::string& field) {
    if (text == "sinusoid") {
        return ProfileShape::kSinusoid;
    }
    if (text == "triangle") {
        return ProfileShape::kTriangle;
    }
    throw MakeInputError("", field, text, "allowed: sinusoid, triangle");
}

const char* ProfileShapeName(ProfileShape shape) {
    return shape == ProfileShape::kSinusoid ? "sinusoid" : "triangle";
}

ProfileSample EvaluateProfile(const AngleProfile& profile, double t_s) {
    const double amplitude = profile.amplitude_deg * kDegToRad;
    const double center = profile.center_deg * kDegToRad;
    const double cycles = t_s / profile.period_s + profile.phase_deg / 360.0;
    if (profile.shape == ProfileShape::kSinusoid) {
        const double omega = 2.0 * std::numbers::pi / profile.period_s;
        const double angle = 2.0 * std::numbers::pi * cycles;
        return {center + amplitude * std::sin(angle), amplitude * omega * std::cos(angle)};
    }
    // Triangle in phase with the sinusoid: up from the centre, down through it, back up.
    const double u = cycles - std::floor(cycles);
    const double rate = 4.0 * amplitude / profile.period_s;
    if (u < 0.25) {
        return {center + amplitude * 4.0 * u, rate};
    }
    if (u < 0.75) {
        return {center + amplitude * (2.0 - 4.0 * u), -rate};
    }
    return {center + amplitude * (4.0 * u - 4.0), rate};
}

double PeakRateDegS(const AngleProfile& profile) {
    const double factor = profile.shape == ProfileShape::kSinusoid ? 2.0 * std::numbers::pi : 4.0;
    return factor * std::abs(profile.amplitude_deg) / profile.period_s;
}

ProfileSample SpeedSchedule::Evaluate(double t_s) const {
    const double accel = speed_m_s / ramp_s;
    const double t = std::clamp(t_s, 0.0, Duration());
    const double ramp_distance = 0.5 * speed_m_s * ramp_s;
    if (t < ramp_s) {
        return {start_m + 0.5 * accel * t * t, accel * t};
    }
    if (t <= ramp_s + cruise_s) {
        return {start_m + ramp_distance + speed_m_s * (t - ramp_s), speed_m_s};
    }
    const double left = Duration() - t;  // time until standstill
    const double end_m = start_m + 2.0 * ramp_distance + speed_m_s * cruise_s;
    return {end_m - 0.5 * accel * left * left, accel * left};
}

}  // namespace casmap::rig
