// The LMS 200's baud rates and its configuration block (telegram.hpp): mode bytes and baud
// words, the output format a configuration sets, and the checks of a configuration block
// (protocol reference notes, sections 2 and 4: host commands, configuration layout).
#include <optional>
#include <string>

#include "casmap/core/check.hpp"
#include "casmap/core/input_error.hpp"
#include "casmap/drivers/telegram.hpp"
#include "casmap/drivers/telegram_detail.hpp"

namespace casmap::drivers {
namespace {

using detail::Hex;

}  // namespace

bool IsLmsBaud(int baud) {
    return baud == 9600 || baud == 19200 || baud == 38400 || baud == 500000;
}

void CheckLmsBaud(int baud, const std::string& field) {
    core::Check().That(IsLmsBaud(baud), field, baud,
                       "the LMS 200 has 9600, 19200, 38400 or 500000 baud");
}

std::uint8_t BaudModeByte(int baud) {
    switch (baud) {
        case 9600:
            return mode::kBaud9600;
        case 19200:
            return mode::kBaud19200;
        case 38400:
            return mode::kBaud38400;
        case 500000:
            return mode::kBaud500000;
        default:
            CheckLmsBaud(baud, "baud");
    }
    return 0;
}

std::optional<int> BaudFromModeByte(std::uint8_t mode_byte) {
    switch (mode_byte) {
        case mode::kBaud9600:
            return 9600;
        case mode::kBaud19200:
            return 19200;
        case mode::kBaud38400:
            return 38400;
        case mode::kBaud500000:
            return 500000;
        default:
            return std::nullopt;
    }
}

std::uint16_t BaudWord(int baud) {
    return static_cast<std::uint16_t>(0x8000 | (1000000 / baud - 1));
}

bool Variant::IsValid() const {
    if (angle_deg != 100 && angle_deg != 180) {
        return false;
    }
    if (resolution_cdeg == 100 || resolution_cdeg == 50) {
        return true;
    }
    return resolution_cdeg == 25 && angle_deg == 100;
}

ConfigBlock ConfigBlock::Default(std::size_t size) {
    ConfigBlock c;
    c.bytes.assign(size, 0);
    c.bytes[5] = 0x00;  // 8 m / 80 m, fields A, B, dazzle
    c.bytes[6] = 0x01;  // mm
    return c;
}

core::Lms200Format FormatOf(const ConfigBlock& config) {
    core::Lms200Format f;
    const std::uint8_t m = config.measuring_mode();
    if (m <= 0x02) {
        f.mode = core::RangeMode::k8m;
    } else if (m <= 0x04) {
        f.mode = core::RangeMode::k16m;
    } else if (m <= 0x06) {
        f.mode = core::RangeMode::k32m;
    } else {
        throw MakeInputError("LMS 200 configuration", "measuring mode (byte D)", Hex(m),
                             "supported: 0x00-0x06");
    }
    const std::uint8_t u = config.units();
    if (u > 1) {
        throw MakeInputError("LMS 200 configuration", "units (byte E)", Hex(u),
                             "supported: 0 = cm, 1 = mm");
    }
    f.units = u == 1 ? core::RangeUnits::kMillimetre : core::RangeUnits::kCentimetre;
    return f;
}

void CheckConfigBlock(const ConfigBlock& config, const std::string& what) {
    if (config.bytes.size() != ConfigBlock::kLongSize &&
        config.bytes.size() != ConfigBlock::kShortSize) {
        throw MakeInputError(what, "configuration size", std::to_string(config.bytes.size()),
                             "34 or 32 bytes");
    }
    (void)FormatOf(config);
    if (config.availability() > 7) {
        throw MakeInputError(what, "availability (byte C)", Hex(config.availability()),
                             "bits 0-2 only (0x00-0x07)");
    }
    if (config.sensitivity() > 3) {
        throw MakeInputError(what, "sensitivity (byte B, peak threshold)",
                             std::to_string(config.sensitivity()),
                             "0 standard, 1 medium, 2 low, 3 high");
    }
}

std::uint8_t ModeByteOf(const core::Lms200Format& format) {
    switch (format.mode) {
        case core::RangeMode::k8m:
            return 0x00;
        case core::RangeMode::k16m:
            return 0x04;
        case core::RangeMode::k32m:
            return 0x06;
    }
    return 0x00;
}

std::uint8_t UnitsByteOf(const core::Lms200Format& format) {
    return format.units == core::RangeUnits::kMillimetre ? 1 : 0;
}

}  // namespace casmap::drivers
