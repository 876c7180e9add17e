#include "casmap/drivers/output_mode.hpp"

#include <cstdlib>

#include "casmap/core/check.hpp"
#include "casmap/core/input_error.hpp"
#include "casmap/drivers/telegram_detail.hpp"

namespace casmap::drivers {
namespace {

using detail::GetU16;
using detail::Hex;
using detail::PutU16;

constexpr const char* kModeRule =
    "continuous, mean:N, subrange:FIRST-LAST, mean-subrange:N:FIRST-LAST or partial";

InputError ValuesError(const MeasuredValues& v,
                       const std::string& field,
                       const std::string& value,
                       const std::string& rule) {
    return MakeInputError("LMS 200 telegram " + CommandName(v.command), field, value, rule);
}

/// Strict integer parse of `text` (digits only); nullopt otherwise.
std::optional<int> ParseCount(const std::string& text) {
    if (text.empty() || text.size() > 6 ||
        text.find_first_not_of("0123456789") != std::string::npos) {
        return std::nullopt;
    }
    return std::atoi(text.c_str());
}

/// "A-B" -> (A, B).
std::optional<std::pair<int, int>> ParseRange(const std::string& text) {
    const std::size_t dash = text.find('-');
    if (dash == std::string::npos) {
        return std::nullopt;
    }
    const std::optional<int> a = ParseCount(text.substr(0, dash));
    const std::optional<int> b = ParseCount(text.substr(dash + 1));
    if (!a || !b) {
        return std::nullopt;
    }
    return std::make_pair(*a, *b);
}

/// Upper value bits the measuring mode uses for flags (fields, dazzle, reflectivity).
std::uint16_t FlagMask(const core::Lms200Format& format) {
    return static_cast<std::uint16_t>(~format.ValueMask());
}

bool IsDocumentedSpecial(std::uint16_t value, const core::Lms200Format& format) {
    const std::uint16_t mask = format.ValueMask();
    const std::uint16_t low = static_cast<std::uint16_t>(value & 0x000FU);
    // 0x.FFF no return, FFE dazzle, FFD overflow, FFB S/N, FFA read error, FF7 > maximum.
    return (value | 0x000FU) == mask &&
           (low == 0xF || low == 0xE || low == 0xD || low == 0xB || low == 0xA || low == 0x7);
}

}  // namespace

std::uint8_t OutputMode::ReplyCommand() const {
    switch (kind) {
        case OutputKind::kMeanValues:
            return cmd::kMeanValues;
        case OutputKind::kSubRange:
            return cmd::kSubRange;
        case OutputKind::kMeanSubRange:
            return cmd::kMeanSubRange;
        case OutputKind::kContinuous:
        case OutputKind::kPartial:
            break;
    }
    return cmd::kValues;
}

void OutputMode::Validate(const Variant& variant) const {
    const core::Check check("LMS 200 output mode");
    check.That(!HasMean() || (mean_scans >= 2 && mean_scans <= 250), "mean scans", mean_scans,
               "2..250");
    if (HasSubRange()) {
        const int beams = variant.BeamCount();
        check.That(first_beam >= 1 && first_beam <= last_beam && last_beam <= beams, "sub-range",
                   std::to_string(first_beam) + "-" + std::to_string(last_beam),
                   "1 <= first <= last <= " + std::to_string(beams) + " (beams of the variant)");
    }
}

std::string OutputMode::ToString() const {
    const std::string range = std::to_string(first_beam) + "-" + std::to_string(last_beam);
    switch (kind) {
        case OutputKind::kContinuous:
            return "continuous";
        case OutputKind::kMeanValues:
            return "mean:" + std::to_string(mean_scans);
        case OutputKind::kSubRange:
            return "subrange:" + range;
        case OutputKind::kMeanSubRange:
            return "mean-subrange:" + std::to_string(mean_scans) + ":" + range;
        case OutputKind::kPartial:
            return "partial";
    }
    return "continuous";
}

OutputMode ParseOutputMode(const std::string& text, const std::string& field) {
    const std::string shown = text.substr(0, 40);
    if (text == "continuous") {
        return OutputMode::Continuous();
    }
    if (text == "partial") {
        return OutputMode::Partial();
    }
    const std::size_t colon = text.find(':');
    const std::string head = text.substr(0, colon);
    const std::string rest = colon == std::string::npos ? "" : text.substr(colon + 1);
    if (head == "mean") {
        if (const std::optional<int> n = ParseCount(rest)) {
            return OutputMode::Mean(*n);
        }
    } else if (head == "subrange") {
        if (const auto r = ParseRange(rest)) {
            return OutputMode::SubRange(r->first, r->second);
        }
    } else if (head == "mean-subrange") {
        const std::size_t c2 = rest.find(':');
        if (c2 != std::string::npos) {
            const std::optional<int> n = ParseCount(rest.substr(0, c2));
            const auto r = ParseRange(rest.substr(c2 + 1));
            if (n && r) {
                return OutputMode::MeanSubRange(*n, r->first, r->second);
            }
        }
    }
    throw MakeInputError("", field, shown, kModeRule);
}

Telegram MakeOutputModeRequest(const OutputMode& m) {
    Telegram t;
    t.address = kHostAddress;
    t.command = cmd::kMode;
    t.data.push_back(m.ModeByte());
    if (m.HasMean()) {
        t.data.push_back(static_cast<std::uint8_t>(m.mean_scans));
    }
    if (m.HasSubRange()) {
        PutU16(t.data, static_cast<std::uint16_t>(m.first_beam));
        PutU16(t.data, static_cast<std::uint16_t>(m.last_beam));
    }
    return t;
}

std::optional<OutputMode> ParseOutputModeRequest(const Telegram& t) {
    if (t.command != cmd::kMode || t.data.empty()) {
        return std::nullopt;
    }
    OutputMode m;
    std::size_t want = 1;
    switch (t.data[0]) {
        case mode::kStreamAll:
        case mode::kStreamPartial:
            break;
        case mode::kStreamMean:
            want = 2;
            break;
        case mode::kStreamSubRange:
            want = 5;
            break;
        case mode::kStreamMeanSubRange:
            want = 6;
            break;
        default:
            return std::nullopt;
    }
    m.kind = static_cast<OutputKind>(t.data[0]);
    if (t.data.size() != want) {
        throw MakeInputError("LMS 200 telegram 0x20 " + Hex(t.data[0]), "LEN",
                             std::to_string(t.Len()), "expected " + std::to_string(want + 1));
    }
    std::size_t at = 1;
    if (m.HasMean()) {
        m.mean_scans = t.data[at++];
    }
    if (m.HasSubRange()) {
        m.first_beam = GetU16(t.data, at);
        m.last_beam = GetU16(t.data, at + 2);
    }
    return m;
}

int ValueCount(const OutputMode& mode, const Variant& variant, int partial) {
    if (mode.HasSubRange()) {
        return mode.last_beam - mode.first_beam + 1;
    }
    if (mode.kind == OutputKind::kPartial) {
        const int turns = variant.Turns();
        return (variant.BeamCount() - partial + turns - 1) / turns;
    }
    return variant.BeamCount();
}

int PartialNumber(const MeasuredValues& v, const Variant& variant) {
    const int offset_cdeg = 25 * v.partial_index;
    if (offset_cdeg % variant.resolution_cdeg != 0 || offset_cdeg >= 100) {
        throw ValuesError(v, "partial-scan index", std::to_string(v.partial_index),
                          "a multiple of the resolution " +
                              std::to_string(variant.resolution_cdeg) + " cdeg, below 1 deg");
    }
    return offset_cdeg / variant.resolution_cdeg;
}

void CheckMeasuredValues(const MeasuredValues& v, const FrameExpectation& e) {
    const std::uint8_t want_cmd = e.mode.ReplyCommand();
    if (v.command != want_cmd) {
        throw ValuesError(v, "command", CommandName(v.command),
                          "expected " + CommandName(want_cmd) + " in mode " + e.mode.ToString());
    }
    if (e.mode.HasMean() && v.sample_size != e.mode.mean_scans) {
        throw ValuesError(v, "sample size", std::to_string(v.sample_size),
                          "expected " + std::to_string(e.mode.mean_scans));
    }
    if (e.mode.HasSubRange() &&
        (v.first_beam != e.mode.first_beam || v.last_beam != e.mode.last_beam)) {
        throw ValuesError(v, "sub-range",
                          std::to_string(v.first_beam) + "-" + std::to_string(v.last_beam),
                          "expected " + std::to_string(e.mode.first_beam) + "-" +
                              std::to_string(e.mode.last_beam));
    }
    const bool partial_mode = e.mode.kind == OutputKind::kPartial;
    if (v.partial != partial_mode || (!partial_mode && v.partial_index != 0)) {
        throw ValuesError(v, "partial-scan bits",
                          std::string(v.partial ? "flag 1" : "flag 0") + ", index " +
                              std::to_string(v.partial_index),
                          partial_mode ? "flag 1 in mode 0x2A" : "flag 0 and index 0");
    }
    const int partial = partial_mode ? PartialNumber(v, e.variant) : 0;
    const auto want_count = static_cast<std::size_t>(ValueCount(e.mode, e.variant, partial));
    if (v.values.size() != want_count) {
        throw ValuesError(v, "value count", std::to_string(v.values.size()),
                          "expected " + std::to_string(want_count) + " for " +
                              std::to_string(e.variant.angle_deg) + " deg / " +
                              std::to_string(e.variant.resolution_cdeg) + " cdeg in mode " +
                              e.mode.ToString());
    }
    const std::size_t want_index = e.realtime_indices ? 1 : 0;
    if (v.realtime_index.size() != want_index) {
        throw ValuesError(v, "bytes after the values", std::to_string(v.realtime_index.size()),
                          "expected " + std::to_string(want_index) +
                              " (real-time index, configuration availability bit 1)");
    }
    if (v.units != e.format.units) {
        throw ValuesError(v, "header units bits",
                          v.units == core::RangeUnits::kMillimetre ? "mm" : "cm",
                          "the configuration's units");
    }
    const std::uint16_t flags = FlagMask(e.format);
    const double max_units = e.format.MaxRangeM() / e.format.UnitM() + 0.5;
    for (std::size_t i = 0; i < v.values.size(); ++i) {
        const std::uint16_t raw = v.values[i];
        const std::uint16_t value = static_cast<std::uint16_t>(raw & e.format.ValueMask());
        if (!e.value_flags && (raw & flags) != 0) {
            throw ValuesError(v, "value " + std::to_string(i), Hex(raw, 4),
                              "flag bits above " + Hex(e.format.ValueMask(), 4) +
                                  " clear (no field evaluation configured)");
        }
        if (static_cast<double>(value) > max_units && !IsDocumentedSpecial(value, e.format)) {
            throw ValuesError(v, "value " + std::to_string(i), Hex(raw, 4),
                              "a range up to the measuring mode's maximum or a documented "
                              "special code");
        }
    }
}

}  // namespace casmap::drivers
