#pragma once

// LMS 200 serial telegrams: framing, the SICK CRC-16, and builders/parsers for every host and
// scanner telegram of shared/reference/lms200_protocol.md (sections 1-5).
// Telegram layout: STX(0x02) ADR LEN(u16 LE, CMD..STATUS) CMD DATA [STATUS] CRC(u16 LE).

#include <array>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "casmap/core/lms200.hpp"

namespace casmap::drivers {

inline constexpr std::uint8_t kStx = 0x02;
inline constexpr std::uint8_t kAck = 0x06;  // raw byte before every accepted request's reply
inline constexpr std::uint8_t kNak = 0x15;  // raw byte on a bad frame or checksum
inline constexpr std::uint8_t kHostAddress = 0x00;
inline constexpr std::uint8_t kReplyAddressBit = 0x80;  // scanner replies at 0x80 | address
inline constexpr std::uint8_t kStatusOk = 0x10;         // status byte real LMS200-30106 send
/// Largest LEN accepted: 401 values (100 deg at 0.25 deg) + header + 2 real-time index bytes.
inline constexpr std::size_t kMaxLen = 808;
inline constexpr std::size_t kFrameOverhead = 6;  // STX ADR LEN(2) CRC(2)
inline constexpr std::size_t kMaxFrameBytes = kMaxLen + kFrameOverhead;

/// Command codes (host requests; a reply's code is the request code + 0x80).
namespace cmd {
inline constexpr std::uint8_t kReset = 0x10;
inline constexpr std::uint8_t kMode = 0x20;
inline constexpr std::uint8_t kScan = 0x30;
inline constexpr std::uint8_t kStatus = 0x31;
inline constexpr std::uint8_t kErrors = 0x32;
inline constexpr std::uint8_t kType = 0x3A;
inline constexpr std::uint8_t kVariant = 0x3B;
inline constexpr std::uint8_t kReadConfig = 0x74;
inline constexpr std::uint8_t kWriteConfig = 0x77;
inline constexpr std::uint8_t kPowerOn = 0x90;  // unsolicited, after power-on or reset
inline constexpr std::uint8_t kResetReply = 0x91;
inline constexpr std::uint8_t kNotAcknowledged = 0x92;  // logically invalid request
inline constexpr std::uint8_t kReplyBit = 0x80;
inline constexpr std::uint8_t kValues = 0xB0;        // complete or partial scan
inline constexpr std::uint8_t kMeanValues = 0xB6;    // mean over n scans
inline constexpr std::uint8_t kSubRange = 0xB7;      // beams first..last
inline constexpr std::uint8_t kMeanSubRange = 0xBF;  // mean over n scans of first..last
}  // namespace cmd

/// Operating-mode bytes of request 0x20 (names as in sicktoolbox).
namespace mode {
inline constexpr std::uint8_t kInstallation = 0x00;
inline constexpr std::uint8_t kDiagnostic = 0x10;
inline constexpr std::uint8_t kStreamAll = 0x24;           // continuous B0 stream
inline constexpr std::uint8_t kRequest = 0x25;             // values on request (idle)
inline constexpr std::uint8_t kStreamMean = 0x26;          // B6: mean of n scans (+ n)
inline constexpr std::uint8_t kStreamSubRange = 0x27;      // B7: beams first..last (+ 2 x u16)
inline constexpr std::uint8_t kStreamMeanSubRange = 0x28;  // BF (+ n, 2 x u16)
inline constexpr std::uint8_t kStreamPartial = 0x2A;       // B0 per mirror turn, partial index
inline constexpr std::uint8_t kBaud38400 = 0x40;
inline constexpr std::uint8_t kBaud19200 = 0x41;
inline constexpr std::uint8_t kBaud9600 = 0x42;
inline constexpr std::uint8_t kBaud500000 = 0x48;
}  // namespace mode

/// SICK CRC-16 (polynomial 0x8005, byte-pair form, init 0), reference section 1.
[[nodiscard]] std::uint16_t Crc16(std::span<const std::uint8_t> bytes);

/// One telegram without framing. Replies (address bit 7 set) carry a status byte.
struct Telegram {
    std::uint8_t address = kHostAddress;
    std::uint8_t command = 0;
    std::vector<std::uint8_t> data;   // bytes between CMD and STATUS (or CRC)
    std::uint8_t status = kStatusOk;  // only on the wire when IsReply()

    [[nodiscard]] bool IsReply() const { return (address & kReplyAddressBit) != 0; }
    [[nodiscard]] std::size_t Len() const { return 1 + data.size() + (IsReply() ? 1 : 0); }
    bool operator==(const Telegram&) const = default;
};

/// Frames a telegram: STX, ADR, LEN, CMD, DATA, [STATUS], CRC. Throws InputError if LEN > kMaxLen.
[[nodiscard]] std::vector<std::uint8_t> EncodeTelegram(const Telegram& telegram);
/// Appends the frame to `out` (no allocation once `out` has the capacity).
void AppendTelegram(const Telegram& telegram, std::vector<std::uint8_t>& out);

enum class FrameError : std::uint8_t { kNone, kShort, kNoStx, kBadLen, kBadCrc };
/// Decodes one complete frame (exactly one telegram, nothing after it). Never throws.
[[nodiscard]] std::optional<Telegram> DecodeTelegram(std::span<const std::uint8_t> frame,
                                                     FrameError* error = nullptr);

// ---------------------------------------------------------------------------------------------
// Baud rates and variants

/// Baud rates the LMS 200 has: 9600, 19200, 38400, 500000.
[[nodiscard]] bool IsLmsBaud(int baud);
/// Throws InputError naming `field` if `baud` is not an LMS 200 rate.
void CheckLmsBaud(int baud, const std::string& field);
/// 0x20 mode byte for a baud rate (0x42, 0x41, 0x40, 0x48); throws InputError otherwise.
[[nodiscard]] std::uint8_t BaudModeByte(int baud);
/// Baud rate for a 0x20 mode byte, or nullopt if the byte is no baud command.
[[nodiscard]] std::optional<int> BaudFromModeByte(std::uint8_t mode_byte);
/// Status-reply baud word: 0x8000 | (1e6 / baud - 1), e.g. 0x8019 for 38400.
[[nodiscard]] std::uint16_t BaudWord(int baud);
/// Seconds one byte takes on the line (8N1 = 10 bits).
[[nodiscard]] inline double ByteTimeS(int baud) { return 10.0 / static_cast<double>(baud); }

/// Angular field and resolution (request 0x3B, status bytes 107-110).
struct Variant {
    std::uint16_t angle_deg = 180;        // 100 or 180
    std::uint16_t resolution_cdeg = 100;  // 1/100 deg: 25, 50, 100 (25 only with 100 deg)
    [[nodiscard]] bool IsValid() const;
    [[nodiscard]] int BeamCount() const { return angle_deg * 100 / resolution_cdeg + 1; }
    /// Mirror turns one complete scan interlaces: 1 (1 deg), 2 (0.5 deg), 4 (0.25 deg).
    [[nodiscard]] int Turns() const { return 100 / resolution_cdeg; }
    bool operator==(const Variant&) const = default;
};

// ---------------------------------------------------------------------------------------------
// Configuration block (0x74 read -> 0xF4, 0x77 write -> 0xF7), reference section 4.

struct ConfigBlock {
    static constexpr std::size_t kLongSize = 34;   // V02.x firmware (default)
    static constexpr std::size_t kShortSize = 32;  // older firmware / RL's profile
    std::vector<std::uint8_t> bytes = std::vector<std::uint8_t>(kLongSize, 0);

    /// Availability bits (byte C): high availability, real-time indices, dazzle ignored.
    static constexpr std::uint8_t kHighAvailability = 0x01;
    static constexpr std::uint8_t kRealTimeIndices = 0x02;
    static constexpr std::uint8_t kDazzleIgnored = 0x04;

    [[nodiscard]] std::uint8_t stop_threshold() const { return bytes.at(2); }
    /// Peak threshold / sensitivity (byte B, second): 0 standard, 1 medium, 2 low, 3 high.
    [[nodiscard]] std::uint8_t sensitivity() const { return bytes.at(3); }
    [[nodiscard]] std::uint8_t availability() const { return bytes.at(4); }
    [[nodiscard]] std::uint8_t measuring_mode() const { return bytes.at(5); }
    [[nodiscard]] std::uint8_t units() const { return bytes.at(6); }  // 0 cm, 1 mm
    /// True when availability bit 1 asks for a real-time scan index after the values.
    [[nodiscard]] bool realtime_indices() const { return (availability() & kRealTimeIndices) != 0; }
    void set_sensitivity(std::uint8_t v) { bytes.at(3) = v; }
    void set_availability(std::uint8_t a) { bytes.at(4) = a; }
    void set_measuring_mode(std::uint8_t m) { bytes.at(5) = m; }
    void set_units(std::uint8_t u) { bytes.at(6) = u; }
    /// Default block: blanking 0, mode 0x00 (8 m / 80 m, fields A, B, dazzle), units mm.
    [[nodiscard]] static ConfigBlock Default(std::size_t size = kLongSize);
    bool operator==(const ConfigBlock&) const = default;
};

/// Value format of a configuration: measuring mode byte 0x00-0x06 and units 0/1. Throws
/// InputError for modes core::Lms200Format cannot decode (0x0F, 0x3F, ...) or units other than 0/1.
[[nodiscard]] core::Lms200Format FormatOf(const ConfigBlock& config);
/// Measuring-mode byte for a core format (0x00, 0x04, 0x06) and units byte (0 cm, 1 mm).
[[nodiscard]] std::uint8_t ModeByteOf(const core::Lms200Format& format);
[[nodiscard]] std::uint8_t UnitsByteOf(const core::Lms200Format& format);
/// Throws InputError naming the byte when a block is not one the virtual scanner and the
/// driver support: size 34 or 32, measuring mode 0x00-0x06, units 0/1, availability 0-7,
/// sensitivity 0-3.
void CheckConfigBlock(const ConfigBlock& config, const std::string& what);

// ---------------------------------------------------------------------------------------------
// Status block (0xB1, 152 data bytes). Indices are payload indices with CMD at 0 (STB's).

struct DeviceStatus {
    std::string software_version = "V02.10 ";      // 7 ASCII, payload 1-7
    std::uint8_t operating_mode = mode::kRequest;  // payload 8
    std::uint8_t device_status = 0;                // payload 9, 0 = OK
    std::uint8_t measuring_mode = 0;               // payload 102
    Variant variant;                               // payload 107-110
    std::uint16_t baud_word = 0x8067;              // payload 116-117
    std::uint8_t address = 0;                      // payload 120
    std::uint8_t units = 1;                        // payload 122, 0 cm, 1 mm
    std::string boot_version = "V01.00 ";          // payload 124-130
    bool operator==(const DeviceStatus&) const = default;
};
inline constexpr std::size_t kStatusDataSize = 152;

// ---------------------------------------------------------------------------------------------
// Measured values (0xB0), reference section 3.

struct MeasuredValues {
    std::uint8_t command = cmd::kValues;  // 0xB0, 0xB6 (mean), 0xB7 (sub-range), 0xBF (both)
    std::uint8_t sample_size = 0;         // 0xB6, 0xBF: scans averaged (2..250)
    std::uint16_t first_beam = 0;         // 0xB7, 0xBF: 1-based index of the first value
    std::uint16_t last_beam = 0;          // 0xB7, 0xBF: 1-based index of the last value
    std::vector<std::uint16_t> values;    // N raw words, angular order right -> left
    core::RangeUnits units = core::RangeUnits::kMillimetre;  // header bits 14-15
    std::uint8_t partial_index = 0;            // header bits 11-12: offset index * 0.25 deg
    bool partial = false;                      // header bit 13
    std::vector<std::uint8_t> realtime_index;  // 0-2 bytes after the values (1 when on)
    std::uint8_t status = kStatusOk;
    bool operator==(const MeasuredValues&) const = default;
};

// ---------------------------------------------------------------------------------------------
// Host request builders. All at address 0x00.

[[nodiscard]] Telegram MakeModeRequest(std::uint8_t mode_byte);
/// 0x20 0x00 + 8-byte password (default "SICK_LMS"). Throws InputError if not 8 characters.
[[nodiscard]] Telegram MakeInstallationRequest(std::string_view password = "SICK_LMS");
/// 0x20 0x40/0x41/0x42/0x48. Throws InputError for rates the LMS 200 does not have.
[[nodiscard]] Telegram MakeBaudRequest(int baud);
[[nodiscard]] Telegram MakeStatusRequest();
[[nodiscard]] Telegram MakeErrorRequest();
[[nodiscard]] Telegram MakeTypeRequest();
[[nodiscard]] Telegram MakeVariantRequest(const Variant& variant);
[[nodiscard]] Telegram MakeReadConfigRequest();
[[nodiscard]] Telegram MakeWriteConfigRequest(const ConfigBlock& config);
[[nodiscard]] Telegram MakeScanRequest();  // 0x30 0x01
[[nodiscard]] Telegram MakeResetRequest();

// Scanner reply builders. All at address 0x80 | address with the given status byte.

[[nodiscard]] Telegram MakeModeReply(std::uint8_t result, std::uint8_t status = kStatusOk);
[[nodiscard]] Telegram MakeStatusReply(const DeviceStatus& device, std::uint8_t status = kStatusOk);
[[nodiscard]] Telegram MakeErrorReply(std::span<const std::pair<std::uint8_t, std::uint8_t>> errors,
                                      std::uint8_t status = kStatusOk);
/// Type string, padded or cut to 21 ASCII bytes (LEN 23), e.g. "LMS200;30106x;V02.10 ".
[[nodiscard]] Telegram MakeTypeReply(std::string_view type, std::uint8_t status = kStatusOk);
[[nodiscard]] Telegram MakeVariantReply(bool accepted,
                                        const Variant& variant,
                                        std::uint8_t status = kStatusOk);
[[nodiscard]] Telegram MakeConfigReply(const ConfigBlock& config, std::uint8_t status = kStatusOk);
[[nodiscard]] Telegram MakeWriteConfigReply(bool accepted,
                                            const ConfigBlock& config,
                                            std::uint8_t status = kStatusOk);
[[nodiscard]] Telegram MakeNotAcknowledged(std::uint8_t status = kStatusOk);
[[nodiscard]] Telegram MakeResetReply(std::uint8_t status = kStatusOk);
/// Unsolicited 0x90 after power-on or reset: 21 ASCII bytes (the type string) + status.
[[nodiscard]] Telegram MakePowerOnTelegram(std::string_view type, std::uint8_t status = kStatusOk);
/// 0xB0/0xB6/0xB7/0xBF (`values.command`) with the blocks before the header (sample size,
/// first/last beam) and the header (count, partial offset, partial flag, units). Throws
/// InputError for more than 1023 values, a partial index > 3, more than 2 real-time index
/// bytes or another command.
[[nodiscard]] Telegram MakeMeasuredValues(const MeasuredValues& values);
/// Same as MakeMeasuredValues, framed straight into `out` (the streaming hot path).
void AppendMeasuredValues(const MeasuredValues& values, std::vector<std::uint8_t>& out);

// Parsers. Each checks command code and exact length and throws InputError naming the
// telegram, the field and the rule ("LMS 200 telegram 0xB1: LEN = 12 (expected 154)").

[[nodiscard]] std::uint8_t ParseModeReply(const Telegram& t);  // result byte
[[nodiscard]] DeviceStatus ParseStatusReply(const Telegram& t);
[[nodiscard]] std::vector<std::pair<std::uint8_t, std::uint8_t>> ParseErrorReply(const Telegram& t);
[[nodiscard]] std::string ParseTypeReply(const Telegram& t);
struct VariantReply {
    bool accepted = false;
    Variant variant;
};
[[nodiscard]] VariantReply ParseVariantReply(const Telegram& t);
[[nodiscard]] ConfigBlock ParseConfigReply(const Telegram& t);
struct WriteConfigReply {
    bool accepted = false;
    ConfigBlock config;
};
[[nodiscard]] WriteConfigReply ParseWriteConfigReply(const Telegram& t);
/// 0xB0, 0xB6, 0xB7 or 0xBF. Bytes after the values (0-2) go to realtime_index.
[[nodiscard]] MeasuredValues ParseMeasuredValues(const Telegram& t);
[[nodiscard]] bool IsMeasuredValues(std::uint8_t command);

// Request parsers (the virtual scanner's side).
[[nodiscard]] Variant ParseVariantRequest(const Telegram& t);
[[nodiscard]] ConfigBlock ParseWriteConfigRequest(const Telegram& t);

/// "0xB0" style name of a command code for messages.
[[nodiscard]] std::string CommandName(std::uint8_t command);

}  // namespace casmap::drivers
