#pragma once

// Constants shared by the Lms200Model sources (lms200_model.cpp: geometry, lms200_return.cpp:
// return formation). Private to sensor_models.

#include <cstdint>
#include <numbers>

namespace casmap::sensor_models {

// Random streams of one pulse (the stream tag of PulseRng).
inline constexpr std::uint32_t kStreamPattern = 1;
inline constexpr std::uint32_t kStreamReturn = 2;
// Detection probability above which the logistic need not be evaluated (an exact shortcut).
inline constexpr double kSureProbability = 0.999;

[[nodiscard]] inline double DegToRad(double deg) { return deg * std::numbers::pi / 180.0; }

}  // namespace casmap::sensor_models
