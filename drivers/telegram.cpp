#include "casmap/drivers/telegram.hpp"

#include <cstdio>

#include "casmap/core/input_error.hpp"
#include "casmap/drivers/telegram_detail.hpp"

namespace casmap::drivers {
namespace {

using detail::GetU16;
using detail::Hex;
using detail::PutU16;

Telegram Request(std::uint8_t command, std::vector<std::uint8_t> data = {}) {
    Telegram t;
    t.address = kHostAddress;
    t.command = command;
    t.data = std::move(data);
    return t;
}

Telegram Reply(std::uint8_t request, std::vector<std::uint8_t> data, std::uint8_t status) {
    Telegram t;
    t.address = kReplyAddressBit;
    t.command = static_cast<std::uint8_t>(request | cmd::kReplyBit);
    t.data = std::move(data);
    t.status = status;
    return t;
}

void PutAscii(std::vector<std::uint8_t>& data,
              std::size_t at,
              std::string_view text,
              std::size_t width) {
    for (std::size_t i = 0; i < width; ++i) {
        data[at + i] = static_cast<std::uint8_t>(i < text.size() ? text[i] : ' ');
    }
}

std::uint16_t MeasuredHeader(const MeasuredValues& v) {
    if (v.values.size() > 0x3FF) {
        throw MakeInputError("LMS 200 telegram 0xB0", "value count",
                             std::to_string(v.values.size()), "at most 1023");
    }
    if (v.partial_index > 3) {
        throw MakeInputError("LMS 200 telegram 0xB0", "partial_index",
                             std::to_string(v.partial_index), "0..3");
    }
    if (v.realtime_index.size() > 2) {
        throw MakeInputError("LMS 200 telegram 0xB0", "realtime_index bytes",
                             std::to_string(v.realtime_index.size()), "0..2");
    }
    if (!IsMeasuredValues(v.command)) {
        throw MakeInputError("LMS 200 measured values", "command", Hex(v.command),
                             "0xB0, 0xB6, 0xB7 or 0xBF");
    }
    unsigned header = static_cast<unsigned>(v.values.size());
    header |= static_cast<unsigned>(v.partial_index) << 11U;
    header |= (v.partial ? 1U : 0U) << 13U;
    header |= (v.units == core::RangeUnits::kMillimetre ? 1U : 0U) << 14U;
    return static_cast<std::uint16_t>(header);
}

/// Blocks before the header word: sample size (B6, BF), first and last beam (B7, BF).
void PutLeadingBlocks(const MeasuredValues& v, std::vector<std::uint8_t>& out) {
    if (v.command == cmd::kMeanValues || v.command == cmd::kMeanSubRange) {
        out.push_back(v.sample_size);
    }
    if (v.command == cmd::kSubRange || v.command == cmd::kMeanSubRange) {
        PutU16(out, v.first_beam);
        PutU16(out, v.last_beam);
    }
}

std::size_t LeadingBlockSize(std::uint8_t command) {
    switch (command) {
        case cmd::kMeanValues:
            return 1;
        case cmd::kSubRange:
            return 4;
        case cmd::kMeanSubRange:
            return 5;
        default:
            return 0;
    }
}

}  // namespace

bool IsMeasuredValues(std::uint8_t command) {
    return command == cmd::kValues || command == cmd::kMeanValues || command == cmd::kSubRange ||
           command == cmd::kMeanSubRange;
}

std::uint16_t Crc16(std::span<const std::uint8_t> bytes) {
    std::uint16_t crc = 0;
    std::uint8_t prev = 0;
    for (const std::uint8_t b : bytes) {
        if ((crc & 0x8000U) != 0) {
            crc = static_cast<std::uint16_t>(((crc & 0x7FFFU) << 1U) ^ 0x8005U);
        } else {
            crc = static_cast<std::uint16_t>(crc << 1U);
        }
        crc ^= static_cast<std::uint16_t>((prev << 8U) | b);
        prev = b;
    }
    return crc;
}

void AppendTelegram(const Telegram& telegram, std::vector<std::uint8_t>& out) {
    const std::size_t len = telegram.Len();
    if (len > kMaxLen) {
        throw MakeInputError("LMS 200 telegram " + CommandName(telegram.command), "LEN",
                             std::to_string(len), "at most " + std::to_string(kMaxLen));
    }
    const std::size_t start = out.size();
    out.push_back(kStx);
    out.push_back(telegram.address);
    PutU16(out, static_cast<std::uint16_t>(len));
    out.push_back(telegram.command);
    out.insert(out.end(), telegram.data.begin(), telegram.data.end());
    if (telegram.IsReply()) {
        out.push_back(telegram.status);
    }
    const std::uint16_t crc = Crc16(std::span(out).subspan(start));
    PutU16(out, crc);
}

std::vector<std::uint8_t> EncodeTelegram(const Telegram& telegram) {
    std::vector<std::uint8_t> out;
    out.reserve(telegram.Len() + kFrameOverhead);
    AppendTelegram(telegram, out);
    return out;
}

std::optional<Telegram> DecodeTelegram(std::span<const std::uint8_t> frame, FrameError* error) {
    const auto fail = [error](FrameError e) -> std::optional<Telegram> {
        if (error != nullptr) {
            *error = e;
        }
        return std::nullopt;
    };
    if (frame.size() < kFrameOverhead + 1) {
        return fail(FrameError::kShort);
    }
    if (frame[0] != kStx) {
        return fail(FrameError::kNoStx);
    }
    const std::size_t len = GetU16(frame, 2);
    const bool reply = (frame[1] & kReplyAddressBit) != 0;
    if (len < (reply ? 2U : 1U) || len > kMaxLen || frame.size() != len + kFrameOverhead) {
        return fail(FrameError::kBadLen);
    }
    const std::size_t crc_at = 4 + len;
    if (Crc16(frame.first(crc_at)) != GetU16(frame, crc_at)) {
        return fail(FrameError::kBadCrc);
    }
    Telegram t;
    t.address = frame[1];
    t.command = frame[4];
    const std::size_t data_end = reply ? crc_at - 1 : crc_at;
    t.data.assign(frame.begin() + 5, frame.begin() + static_cast<std::ptrdiff_t>(data_end));
    t.status = reply ? frame[crc_at - 1] : kStatusOk;
    if (error != nullptr) {
        *error = FrameError::kNone;
    }
    return t;
}

// ---------------------------------------------------------------------------------------------

Telegram MakeModeRequest(std::uint8_t mode_byte) { return Request(cmd::kMode, {mode_byte}); }

Telegram MakeInstallationRequest(std::string_view password) {
    if (password.size() != 8) {
        throw MakeInputError("LMS 200 telegram 0x20", "password", std::string(password),
                             "exactly 8 characters");
    }
    std::vector<std::uint8_t> data{mode::kInstallation};
    data.insert(data.end(), password.begin(), password.end());
    return Request(cmd::kMode, std::move(data));
}

Telegram MakeBaudRequest(int baud) { return MakeModeRequest(BaudModeByte(baud)); }
Telegram MakeStatusRequest() { return Request(cmd::kStatus); }
Telegram MakeErrorRequest() { return Request(cmd::kErrors); }
Telegram MakeTypeRequest() { return Request(cmd::kType); }

Telegram MakeVariantRequest(const Variant& variant) {
    std::vector<std::uint8_t> data;
    PutU16(data, variant.angle_deg);
    PutU16(data, variant.resolution_cdeg);
    return Request(cmd::kVariant, std::move(data));
}

Telegram MakeReadConfigRequest() { return Request(cmd::kReadConfig); }
Telegram MakeWriteConfigRequest(const ConfigBlock& config) {
    return Request(cmd::kWriteConfig, config.bytes);
}
Telegram MakeScanRequest() { return Request(cmd::kScan, {0x01}); }
Telegram MakeResetRequest() { return Request(cmd::kReset); }

Telegram MakeModeReply(std::uint8_t result, std::uint8_t status) {
    return Reply(cmd::kMode, {result}, status);
}

Telegram MakeStatusReply(const DeviceStatus& d, std::uint8_t status) {
    std::vector<std::uint8_t> data(kStatusDataSize, 0);
    // data[i - 1] holds payload index i.
    PutAscii(data, 0, d.software_version, 7);
    data[7] = d.operating_mode;
    data[8] = d.device_status;
    data[101] = d.measuring_mode;
    data[106] = static_cast<std::uint8_t>(d.variant.angle_deg & 0xFFU);
    data[107] = static_cast<std::uint8_t>(d.variant.angle_deg >> 8U);
    data[108] = static_cast<std::uint8_t>(d.variant.resolution_cdeg & 0xFFU);
    data[109] = static_cast<std::uint8_t>(d.variant.resolution_cdeg >> 8U);
    data[115] = static_cast<std::uint8_t>(d.baud_word & 0xFFU);
    data[116] = static_cast<std::uint8_t>(d.baud_word >> 8U);
    data[119] = d.address;
    data[121] = d.units;
    data[122] = 1;  // laser on
    PutAscii(data, 123, d.boot_version, 7);
    return Reply(cmd::kStatus, std::move(data), status);
}

Telegram MakeErrorReply(std::span<const std::pair<std::uint8_t, std::uint8_t>> errors,
                        std::uint8_t status) {
    std::vector<std::uint8_t> data;
    for (const auto& [type, number] : errors) {
        data.push_back(type);
        data.push_back(number);
    }
    return Reply(cmd::kErrors, std::move(data), status);
}

Telegram MakeTypeReply(std::string_view type, std::uint8_t status) {
    std::vector<std::uint8_t> data(21, ' ');
    PutAscii(data, 0, type, 21);
    return Reply(cmd::kType, std::move(data), status);
}

Telegram MakeVariantReply(bool accepted, const Variant& variant, std::uint8_t status) {
    std::vector<std::uint8_t> data{static_cast<std::uint8_t>(accepted ? 1 : 0)};
    PutU16(data, variant.angle_deg);
    PutU16(data, variant.resolution_cdeg);
    return Reply(cmd::kVariant, std::move(data), status);
}

Telegram MakeConfigReply(const ConfigBlock& config, std::uint8_t status) {
    return Reply(cmd::kReadConfig, config.bytes, status);
}

Telegram MakeWriteConfigReply(bool accepted, const ConfigBlock& config, std::uint8_t status) {
    std::vector<std::uint8_t> data{static_cast<std::uint8_t>(accepted ? 1 : 0)};
    data.insert(data.end(), config.bytes.begin(), config.bytes.end());
    return Reply(cmd::kWriteConfig, std::move(data), status);
}

Telegram MakeNotAcknowledged(std::uint8_t status) {
    Telegram t;
    t.address = kReplyAddressBit;
    t.command = cmd::kNotAcknowledged;
    t.status = status;
    return t;
}

Telegram MakeResetReply(std::uint8_t status) {
    Telegram t;
    t.address = kReplyAddressBit;
    t.command = cmd::kResetReply;
    t.status = status;
    return t;
}

Telegram MakePowerOnTelegram(std::string_view type, std::uint8_t status) {
    std::vector<std::uint8_t> data(21, ' ');
    PutAscii(data, 0, type, 21);
    Telegram t = Reply(cmd::kPowerOn, std::move(data), status);
    t.command = cmd::kPowerOn;  // unsolicited: not a reply code (0x10 | 0x80 is 0x90 anyway)
    return t;
}

Telegram MakeMeasuredValues(const MeasuredValues& v) {
    std::vector<std::uint8_t> data;
    const std::uint16_t header = MeasuredHeader(v);
    data.reserve(7 + 2 * v.values.size() + v.realtime_index.size());
    PutLeadingBlocks(v, data);
    PutU16(data, header);
    for (const std::uint16_t value : v.values) {
        PutU16(data, value);
    }
    data.insert(data.end(), v.realtime_index.begin(), v.realtime_index.end());
    Telegram t = Reply(cmd::kScan, std::move(data), v.status);
    t.command = v.command;
    return t;
}

void AppendMeasuredValues(const MeasuredValues& v, std::vector<std::uint8_t>& out) {
    const std::uint16_t header = MeasuredHeader(v);
    const std::size_t len =
        1 + LeadingBlockSize(v.command) + 2 + 2 * v.values.size() + v.realtime_index.size() + 1;
    if (len > kMaxLen) {
        throw MakeInputError("LMS 200 telegram 0xB0", "LEN", std::to_string(len),
                             "at most " + std::to_string(kMaxLen));
    }
    const std::size_t start = out.size();
    out.push_back(kStx);
    out.push_back(kReplyAddressBit);
    PutU16(out, static_cast<std::uint16_t>(len));
    out.push_back(v.command);
    PutLeadingBlocks(v, out);
    PutU16(out, header);
    for (const std::uint16_t value : v.values) {
        PutU16(out, value);
    }
    out.insert(out.end(), v.realtime_index.begin(), v.realtime_index.end());
    out.push_back(v.status);
    PutU16(out, Crc16(std::span(out).subspan(start)));
}

}  // namespace casmap::drivers
