#pragma once

#include <cstdint>
#include <optional>

#include "casmap/core/scan.hpp"

namespace casmap::core {

/// Measuring modes of the LMS 200 (telegram listing; shared/reference/lms200_protocol.md).
/// k8m in cm units is the "80 m" mode. Bit widths: 13 (8 m), 14 (16 m), 15 (32 m).
enum class RangeMode : std::uint8_t { k8m, k16m, k32m };
enum class RangeUnits : std::uint8_t { kMillimetre, kCentimetre };

struct Lms200Format {
    RangeMode mode = RangeMode::k8m;
    RangeUnits units = RangeUnits::kMillimetre;

    [[nodiscard]] int ValueBits() const;            // 13, 14 or 15
    [[nodiscard]] std::uint16_t ValueMask() const;  // 0x1FFF, 0x3FFF, 0x7FFF
    [[nodiscard]] double UnitM() const { return units == RangeUnits::kMillimetre ? 0.001 : 0.01; }
    /// Largest valid range the mode can report (m): the first special code minus one unit.
    [[nodiscard]] double MaxRangeM() const;
    /// The raw value for a special status (e.g. kNoReturn -> 8191 in the 13-bit modes).
    [[nodiscard]] std::uint16_t CodeFor(BeamStatus status) const;
    /// Raw value -> Beam. Values below the special codes are ranges; flag bits above the value
    /// mask (8 m mode: field A/B, dazzle) are ignored here.
    [[nodiscard]] Beam Decode(std::uint16_t raw) const;
    /// Range in metres -> raw value, rounded to the unit. Ranges beyond MaxRangeM() get the
    /// "value > maximum" code.
    [[nodiscard]] std::uint16_t EncodeRange(double range_m) const;
    bool operator==(const Lms200Format&) const = default;
};

/// Angular resolutions of the LMS 200 and their scan timing (75 Hz mirror; finer resolutions
/// interleave 2 or 4 mirror turns).
struct Lms200Timing {
    static constexpr double kMirrorRateHz = 75.0;
    static constexpr double kTurnPeriodS = 1.0 / kMirrorRateHz;
    /// Seconds between adjacent 1-degree pulses within one turn: (1/75) / 360.
    static constexpr double kBeamPeriodS = kTurnPeriodS / 360.0;
};

}  // namespace casmap::core
