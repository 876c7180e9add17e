#pragma once

// The LMS 200's streaming output modes (request 0x20 with mode 0x24, 0x26, 0x27, 0x28, 0x2A;
// reference section 2) and the checks a measured-value telegram must pass beyond its CRC
// (issue #13 item 3): command, length and blocks as the configured variant and mode imply,
// reserved header bits clear, values inside the measuring mode's range.

#include <cstdint>
#include <string>

#include "casmap/core/lms200.hpp"
#include "casmap/drivers/telegram.hpp"

namespace casmap::drivers {

enum class OutputKind : std::uint8_t {
    kContinuous = mode::kStreamAll,             // 0x24 -> B0, every complete scan
    kMeanValues = mode::kStreamMean,            // 0x26 -> B6, mean of n scans
    kSubRange = mode::kStreamSubRange,          // 0x27 -> B7, beams first..last
    kMeanSubRange = mode::kStreamMeanSubRange,  // 0x28 -> BF, mean of n scans of first..last
    kPartial = mode::kStreamPartial,            // 0x2A -> B0 per mirror turn (partial scans)
};

/// One streaming output mode with its parameters.
struct OutputMode {
    OutputKind kind = OutputKind::kContinuous;
    int mean_scans = 0;  // kMeanValues, kMeanSubRange: scans averaged, 2..250 (sicktoolbox)
    int first_beam = 0;  // kSubRange, kMeanSubRange: 1-based, 1 <= first <= last <= beams
    int last_beam = 0;

    [[nodiscard]] static OutputMode Continuous() { return {}; }
    [[nodiscard]] static OutputMode Mean(int scans) { return {OutputKind::kMeanValues, scans}; }
    [[nodiscard]] static OutputMode SubRange(int first, int last) {
        return {OutputKind::kSubRange, 0, first, last};
    }
    [[nodiscard]] static OutputMode MeanSubRange(int scans, int first, int last) {
        return {OutputKind::kMeanSubRange, scans, first, last};
    }
    [[nodiscard]] static OutputMode Partial() { return {OutputKind::kPartial}; }

    [[nodiscard]] bool HasMean() const {
        return kind == OutputKind::kMeanValues || kind == OutputKind::kMeanSubRange;
    }
    [[nodiscard]] bool HasSubRange() const {
        return kind == OutputKind::kSubRange || kind == OutputKind::kMeanSubRange;
    }
    /// The 0x20 mode byte (0x24, 0x26, 0x27, 0x28, 0x2A).
    [[nodiscard]] std::uint8_t ModeByte() const { return static_cast<std::uint8_t>(kind); }
    /// The reply command its telegrams carry (0xB0, 0xB6, 0xB7, 0xBF).
    [[nodiscard]] std::uint8_t ReplyCommand() const;
    /// Throws InputError naming the field when a parameter is outside its range for `variant`
    /// (mean scans 2..250, 1 <= first <= last <= variant.BeamCount()).
    void Validate(const Variant& variant) const;
    /// "continuous", "mean:N", "subrange:A-B", "mean-subrange:N:A-B", "partial".
    [[nodiscard]] std::string ToString() const;
    bool operator==(const OutputMode&) const = default;
};

/// Parses OutputMode::ToString()'s forms. Throws InputError naming `field`.
[[nodiscard]] OutputMode ParseOutputMode(const std::string& text, const std::string& field);

/// 0x20 with the mode byte and its parameters (n; first, last as u16 LE).
[[nodiscard]] Telegram MakeOutputModeRequest(const OutputMode& mode);
/// The streaming mode of a 0x20 request, or nullopt when it is another 0x20 request. Throws
/// InputError when the parameter bytes have the wrong length (ranges are not checked).
[[nodiscard]] std::optional<OutputMode> ParseOutputModeRequest(const Telegram& t);

/// Values in one telegram of `mode`: all beams of the variant, the sub-range, or (kPartial)
/// the beams of partial scan `partial` (0..turns-1): ceil((beams - partial) / turns).
[[nodiscard]] int ValueCount(const OutputMode& mode, const Variant& variant, int partial = 0);

/// What the driver expects of every measured-value telegram.
struct FrameExpectation {
    Variant variant;
    OutputMode mode;
    core::Lms200Format format;      // measuring mode (value range) and units (header bits)
    bool realtime_indices = false;  // config availability bit 1: one index byte follows
    bool value_flags = false;       // accept flag bits above the range bits (field evaluation)
};

/// Throws InputError naming the field when `v` is not a telegram the scanner sends in the
/// expected configuration: command, sample size and sub-range, value count, index bytes,
/// partial flag and index, units bits, reserved header bit 10, and every value: within the
/// measuring mode's bits (flag bits only where the mode has flags) and either a range or one
/// of the documented special codes (reserved codes 0x.FF8, 0x.FF9, 0x.FFC rejected).
void CheckMeasuredValues(const MeasuredValues& v, const FrameExpectation& expect);

/// Partial scan number (0..turns-1) of a partial B0 from its offset index (0.25 deg units).
/// Throws InputError if the offset is not a multiple of the variant's resolution.
[[nodiscard]] int PartialNumber(const MeasuredValues& v, const Variant& variant);

}  // namespace casmap::drivers
