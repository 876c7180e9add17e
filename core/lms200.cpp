#include "casmap/core/lms200.hpp"

#include <cmath>

namespace casmap::core {
namespace {
// Offsets of the special codes below the all-ones value (telegram listing p.124 via
// ros-drivers/sicktoolbox_wrapper): 8191 no return, 8190 dazzle, 8189 overflow,
// 8187 S/N too small, 8186 read error, 8183 value > max.
constexpr std::uint16_t OffsetOf(BeamStatus status) {
    switch (status) {
        case BeamStatus::kNoReturn:
            return 0;
        case BeamStatus::kDazzle:
            return 1;
        case BeamStatus::kOverflow:
            return 2;
        case BeamStatus::kLowSignal:
            return 4;
        case BeamStatus::kReadError:
            return 5;
        case BeamStatus::kOutOfRange:
            return 8;
        case BeamStatus::kOk:
            break;
    }
    return 0;
}
}  // namespace

int Lms200Format::ValueBits() const {
    switch (mode) {
        case RangeMode::k8m:
            return 13;
        case RangeMode::k16m:
            return 14;
        case RangeMode::k32m:
            return 15;
    }
    return 13;
}

std::uint16_t Lms200Format::ValueMask() const {
    return static_cast<std::uint16_t>((1U << ValueBits()) - 1U);
}

double Lms200Format::MaxRangeM() const {
    return static_cast<double>(CodeFor(BeamStatus::kOutOfRange) - 1) * UnitM();
}

std::uint16_t Lms200Format::CodeFor(BeamStatus status) const {
    return static_cast<std::uint16_t>(ValueMask() - OffsetOf(status));
}

Beam Lms200Format::Decode(std::uint16_t raw) const {
    const std::uint16_t value = raw & ValueMask();
    Beam beam;
    beam.raw = raw;
    if (value < CodeFor(BeamStatus::kOutOfRange)) {
        beam.status = BeamStatus::kOk;
        beam.range_m = static_cast<float>(value * UnitM());
        return beam;
    }
    beam.status = BeamStatus::kNoReturn;  // unlisted codes in the special band: not valid
    for (const BeamStatus s :
         {BeamStatus::kNoReturn, BeamStatus::kDazzle, BeamStatus::kOverflow, BeamStatus::kLowSignal,
          BeamStatus::kReadError, BeamStatus::kOutOfRange}) {
        if (value == CodeFor(s)) {
            beam.status = s;
        }
    }
    return beam;
}

std::uint16_t Lms200Format::EncodeRange(double range_m) const {
    const double count = std::round(range_m / UnitM());
    if (!(count >= 0.0)) {
        return CodeFor(BeamStatus::kNoReturn);
    }
    if (count >= static_cast<double>(CodeFor(BeamStatus::kOutOfRange))) {
        return CodeFor(BeamStatus::kOutOfRange);
    }
    return static_cast<std::uint16_t>(count);
}

}  // namespace casmap::core
