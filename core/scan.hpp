#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <string_view>
#include <vector>

namespace casmap::core {

/// What the scanner reported for one beam. Mirrors the LMS 200's special codes
/// (telegram listing p.124; see shared/reference/lms200_protocol.md and core/lms200.hpp).
enum class BeamStatus : std::uint8_t {
    kOk = 0,          // a valid range
    kNoReturn = 1,    // 8191: not valid / no echo
    kDazzle = 2,      // 8190: dazzled
    kOverflow = 3,    // 8189: operation overflow
    kLowSignal = 4,   // 8187: S/N too small
    kReadError = 5,   // 8186: channel-1 read error
    kOutOfRange = 6,  // 8183: value > maximum of the range mode
};
inline constexpr int kBeamStatusCount = 7;

/// Truth label of a simulated beam: why the scanner reported what it did. Never an input
/// to the mapper; only metrics and datasets read it.
enum class BeamLabel : std::uint8_t {
    kValid = 0,     // a single surface within the footprint, ranged correctly (within noise)
    kMixed = 1,     // echoes of several surfaces merged; the range lies between them
    kMissing = 2,   // a surface was there but no valid echo was reported
    kSpike = 3,     // an artifact: wrap-around overflow, short or random spike
    kNoTarget = 4,  // nothing within range
    kDazzled = 5,   // a surface was there but its echo saturated the receiver (8190, dazzle)
};
inline constexpr int kBeamLabelCount = 6;

struct Beam {
    float range_m = 0.0F;  // metres along the beam; meaningful only when status == kOk
    BeamStatus status = BeamStatus::kNoReturn;
    std::uint16_t raw = 0;  // the value as the scanner sent it (0 if unknown)
};

/// One sweep of a 2-D scanner. Beam i points at start_angle_rad + i * angle_step_rad about
/// sensor +z (sensor frame: x forward, y left, z up) and was measured at
/// stamp_s + beam_time_offset_s[i] (or stamp_s + i * beam_period_s when the offsets are empty).
struct Scan {
    double stamp_s = 0.0;          // time of beam 0
    double start_angle_rad = 0.0;  // sensor frame, counter-clockwise from +x
    double angle_step_rad = 0.0;
    double beam_period_s = 0.0;              // lets the mapper undo motion during a sweep
    std::vector<double> beam_time_offset_s;  // optional per-beam offsets (interleaved modes)
    std::vector<Beam> beams;

    [[nodiscard]] double BeamTime(std::size_t i) const {
        return stamp_s + (beam_time_offset_s.empty() ? static_cast<double>(i) * beam_period_s
                                                     : beam_time_offset_s[i]);
    }
    [[nodiscard]] double BeamAngle(std::size_t i) const {
        return start_angle_rad + static_cast<double>(i) * angle_step_rad;
    }
};

/// Simulation-only companion of a Scan: one label per beam plus the true centre-ray range.
struct ScanTruth {
    std::vector<BeamLabel> labels;
    std::vector<float> true_range_m;  // centre ray's exact distance, NaN when it hit nothing
};

[[nodiscard]] std::string_view ToString(BeamStatus status);
[[nodiscard]] std::string_view ToString(BeamLabel label);
[[nodiscard]] std::optional<BeamLabel> BeamLabelFromString(std::string_view name);

}  // namespace casmap::core
