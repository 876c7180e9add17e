#include <string>

#include "casmap/core/input_error.hpp"
#include "casmap/drivers/telegram.hpp"
#include "casmap/drivers/telegram_detail.hpp"

// Parsers of host and scanner telegrams (reference sections 2-4): exact lengths, payload indices
// with the CMD byte at 0 (sicktoolbox's convention).

namespace casmap::drivers {
namespace {

using detail::GetU16;
using detail::Hex;

InputError TelegramError(const Telegram& t,
                         const std::string& field,
                         const std::string& value,
                         const std::string& rule) {
    return MakeInputError("LMS 200 telegram " + CommandName(t.command), field, value, rule);
}

/// Payload = CMD + data (+ status), the indexing sicktoolbox uses.
std::uint8_t PayloadAt(const Telegram& t, std::size_t index) { return t.data.at(index - 1); }

void ExpectCommand(const Telegram& t, std::uint8_t command) {
    if (t.command != command) {
        throw TelegramError(t, "command", CommandName(t.command),
                            "expected " + CommandName(command));
    }
}

void ExpectDataSize(const Telegram& t, std::size_t size) {
    if (t.data.size() != size) {
        const std::size_t expected = size + (t.IsReply() ? 2 : 1);
        throw TelegramError(t, "LEN", std::to_string(t.Len()),
                            "expected " + std::to_string(expected));
    }
}

std::string GetAscii(const Telegram& t, std::size_t payload_index, std::size_t width) {
    std::string s;
    for (std::size_t i = 0; i < width; ++i) {
        s.push_back(static_cast<char>(PayloadAt(t, payload_index + i)));
    }
    return s;
}

}  // namespace

std::uint8_t ParseModeReply(const Telegram& t) {
    ExpectCommand(t, cmd::kMode | cmd::kReplyBit);
    ExpectDataSize(t, 1);
    return t.data[0];
}

DeviceStatus ParseStatusReply(const Telegram& t) {
    ExpectCommand(t, cmd::kStatus | cmd::kReplyBit);
    ExpectDataSize(t, kStatusDataSize);
    const std::span<const std::uint8_t> d(t.data);
    DeviceStatus s;
    s.software_version = GetAscii(t, 1, 7);
    s.operating_mode = PayloadAt(t, 8);
    s.device_status = PayloadAt(t, 9);
    s.measuring_mode = PayloadAt(t, 102);
    s.variant.angle_deg = GetU16(d, 106);
    s.variant.resolution_cdeg = GetU16(d, 108);
    s.baud_word = GetU16(d, 115);
    s.address = PayloadAt(t, 120);
    s.units = PayloadAt(t, 122);
    s.boot_version = GetAscii(t, 124, 7);
    return s;
}

std::vector<std::pair<std::uint8_t, std::uint8_t>> ParseErrorReply(const Telegram& t) {
    ExpectCommand(t, cmd::kErrors | cmd::kReplyBit);
    if (t.data.size() % 2 != 0) {
        throw TelegramError(t, "LEN", std::to_string(t.Len()), "2 + 2 * error pairs");
    }
    std::vector<std::pair<std::uint8_t, std::uint8_t>> errors;
    for (std::size_t i = 0; i + 1 < t.data.size(); i += 2) {
        errors.emplace_back(t.data[i], t.data[i + 1]);
    }
    return errors;
}

std::string ParseTypeReply(const Telegram& t) {
    ExpectCommand(t, cmd::kType | cmd::kReplyBit);
    if (t.data.empty()) {
        throw TelegramError(t, "LEN", std::to_string(t.Len()), "at least 3");
    }
    return {t.data.begin(), t.data.end()};
}

VariantReply ParseVariantReply(const Telegram& t) {
    ExpectCommand(t, cmd::kVariant | cmd::kReplyBit);
    ExpectDataSize(t, 5);
    VariantReply r;
    r.accepted = t.data[0] == 1;
    r.variant.angle_deg = GetU16(t.data, 1);
    r.variant.resolution_cdeg = GetU16(t.data, 3);
    return r;
}

ConfigBlock ParseConfigReply(const Telegram& t) {
    ExpectCommand(t, cmd::kReadConfig | cmd::kReplyBit);
    if (t.data.size() != ConfigBlock::kLongSize && t.data.size() != ConfigBlock::kShortSize) {
        throw TelegramError(t, "LEN", std::to_string(t.Len()), "expected 36 or 34");
    }
    ConfigBlock c;
    c.bytes = t.data;
    return c;
}

WriteConfigReply ParseWriteConfigReply(const Telegram& t) {
    ExpectCommand(t, cmd::kWriteConfig | cmd::kReplyBit);
    if (t.data.size() != ConfigBlock::kLongSize + 1 &&
        t.data.size() != ConfigBlock::kShortSize + 1) {
        throw TelegramError(t, "LEN", std::to_string(t.Len()), "expected 37 or 35");
    }
    WriteConfigReply r;
    r.accepted = t.data[0] == 1;
    r.config.bytes.assign(t.data.begin() + 1, t.data.end());
    return r;
}

MeasuredValues ParseMeasuredValues(const Telegram& t) {
    if (!IsMeasuredValues(t.command)) {
        throw TelegramError(t, "command", CommandName(t.command), "0xB0, 0xB6, 0xB7 or 0xBF");
    }
    MeasuredValues v;
    v.command = t.command;
    std::size_t at = 0;  // data index of the next block
    const bool mean = t.command == cmd::kMeanValues || t.command == cmd::kMeanSubRange;
    const bool sub = t.command == cmd::kSubRange || t.command == cmd::kMeanSubRange;
    const std::size_t lead = (mean ? 1U : 0U) + (sub ? 4U : 0U);
    if (t.data.size() < lead + 2) {
        throw TelegramError(t, "LEN", std::to_string(t.Len()),
                            "at least " + std::to_string(lead + 4));
    }
    if (mean) {
        v.sample_size = t.data[at++];
    }
    if (sub) {
        v.first_beam = GetU16(t.data, at);
        v.last_beam = GetU16(t.data, at + 2);
        at += 4;
    }
    const std::uint16_t header = GetU16(t.data, at);
    at += 2;
    const std::size_t count = header & 0x3FFU;
    const std::size_t values_end = at + 2 * count;
    if (t.data.size() < values_end || t.data.size() > values_end + 2) {
        throw TelegramError(t, "LEN", std::to_string(t.Len()),
                            std::to_string(lead + 4) + " + 2 * " + std::to_string(count) +
                                " values (header count) + 0..2 real-time index bytes");
    }
    if ((header & 0x8000U) != 0) {
        throw TelegramError(t, "header units bits", Hex(header, 4), "00 = cm, 01 = mm");
    }
    if ((header & 0x0400U) != 0) {
        throw TelegramError(t, "header bit 10", Hex(header, 4), "reserved, must be 0");
    }
    v.values.resize(count);
    for (std::size_t i = 0; i < count; ++i) {
        v.values[i] = GetU16(t.data, at + 2 * i);
    }
    v.units =
        (header & 0x4000U) != 0 ? core::RangeUnits::kMillimetre : core::RangeUnits::kCentimetre;
    v.partial_index = static_cast<std::uint8_t>((header >> 11U) & 0x3U);
    v.partial = (header & 0x2000U) != 0;
    v.realtime_index.assign(t.data.begin() + static_cast<std::ptrdiff_t>(values_end), t.data.end());
    v.status = t.status;
    return v;
}

Variant ParseVariantRequest(const Telegram& t) {
    ExpectCommand(t, cmd::kVariant);
    ExpectDataSize(t, 4);
    return Variant{GetU16(t.data, 0), GetU16(t.data, 2)};
}

ConfigBlock ParseWriteConfigRequest(const Telegram& t) {
    ExpectCommand(t, cmd::kWriteConfig);
    if (t.data.size() != ConfigBlock::kLongSize && t.data.size() != ConfigBlock::kShortSize) {
        throw TelegramError(t, "LEN", std::to_string(t.Len()), "expected 35 or 33");
    }
    ConfigBlock c;
    c.bytes = t.data;
    return c;
}

std::string CommandName(std::uint8_t command) { return Hex(command); }

}  // namespace casmap::drivers
