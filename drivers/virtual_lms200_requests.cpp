#include <cmath>
#include <string>
#include <vector>

#include "casmap/core/input_error.hpp"
#include "casmap/drivers/scan_codec.hpp"
#include "casmap/drivers/virtual_lms200_impl.hpp"

// Request handling of the virtual LMS 200 (reference sections 2 and 6.5) and the choice of the
// sweep each measured-value telegram carries.

namespace casmap::drivers {
namespace {
using vlms::Chunk;
using vlms::Clock;
using vlms::Duration;
using vlms::Seconds;
}  // namespace

std::string VirtualLms200::Impl::TypeString() const {
    // "x" is 1 in mm and 3 in cm units on the unit MJ tested (reference section 2).
    return std::string("LMS200;30106") +
           (format.units == core::RangeUnits::kMillimetre ? '1' : '3') + ";V02.10 ";
}

DeviceStatus VirtualLms200::Impl::Status() const {
    DeviceStatus d;
    d.operating_mode = op_mode;
    d.measuring_mode = config.measuring_mode();
    d.variant = variant;
    d.baud_word = BaudWord(baud);
    d.units = config.units();
    return d;
}

void VirtualLms200::Impl::OnMode(const Telegram& t) {
    const std::uint8_t m = t.data.at(0);
    if (const std::optional<int> new_baud = BaudFromModeByte(m)) {
        if (t.data.size() != 1) {
            Reply(MakeNotAcknowledged());
            return;
        }
        Reply(MakeModeReply(0), *new_baud);  // answered at the old rate, then applied
        return;
    }
    if (m == mode::kInstallation) {
        const bool ok =
            t.data.size() == 9 && std::string(t.data.begin() + 1, t.data.end()) == "SICK_LMS";
        if (ok) {
            installation = true;
            op_mode = m;
        }
        Reply(MakeModeReply(ok ? 0 : 1));
        return;
    }
    std::optional<OutputMode> stream;
    try {
        stream = ParseOutputModeRequest(t);
        if (stream) {
            stream->Validate(variant);  // n 2..250, 1 <= first <= last <= beams
        }
    } catch (const InputError&) {
        Reply(MakeNotAcknowledged());  // parameters out of range: logically invalid
        return;
    }
    if (!stream && (t.data.size() != 1 || (m != mode::kDiagnostic && m != mode::kRequest))) {
        Reply(MakeNotAcknowledged());
        return;
    }
    if (stream && (m != op_mode || !(*stream == stream_mode))) {
        const std::int64_t turns = TurnsDone(Clock::now());
        if (!origin_turn) {
            origin_turn = turns;
        }
        // Only telegrams whose data completes from now on.
        last_sent_unit = (turns - *origin_turn) / UnitTurns(*stream) - 1;
        stream_mode = *stream;
    }
    installation = false;
    op_mode = m;
    Reply(MakeModeReply(0));
}

void VirtualLms200::Impl::OnRequest(const Telegram& t) {
    ++stats.requests;
    EnqueueRaw(kAck);
    try {
        switch (t.command) {
            case cmd::kMode:
                if (t.data.empty()) {
                    Reply(MakeNotAcknowledged());
                } else {
                    OnMode(t);
                }
                return;
            case cmd::kStatus:
                Reply(MakeStatusReply(Status()));
                return;
            case cmd::kErrors:
                Reply(MakeErrorReply({}));
                return;
            case cmd::kType:
                Reply(MakeTypeReply(TypeString()));
                return;
            case cmd::kReadConfig:
                Reply(MakeConfigReply(config));
                return;
            case cmd::kVariant: {
                const Variant v = ParseVariantRequest(t);
                const bool ok = v.IsValid() && source.Supports(v);
                if (ok) {
                    variant = v;
                }
                Reply(MakeVariantReply(ok, variant));
                return;
            }
            case cmd::kWriteConfig:
                OnWriteConfig(ParseWriteConfigRequest(t));
                return;
            case cmd::kScan:
                if (t.data.size() == 1 && t.data[0] == 0x01 && QueueNewestScan(true)) {
                    return;
                }
                break;
            case cmd::kReset: {
                // Answered, then the unit restarts (deaf for reset_s) at its power-on rate
                // and announces itself with 0x90.
                Reply(MakeResetReply(), 0, true);
                const Clock::time_point back = Clock::now() + Duration(cfg.reset_s);
                busy_until = back;
                SendPowerOn(back);
                return;
            }
            default:
                break;
        }
    } catch (const InputError&) {
        // wrong length for the command: logically invalid request
    }
    Reply(MakeNotAcknowledged());
}

void VirtualLms200::Impl::OnWriteConfig(const ConfigBlock& block) {
    bool ok = installation && block.bytes.size() == config.bytes.size();
    if (ok) {
        try {
            CheckConfigBlock(block, "0x77");
            format = FormatOf(block);
            config = block;
        } catch (const InputError&) {
            ok = false;
        }
    }
    if (ok && !cfg.eeprom_path.empty()) {
        try {
            WriteEepromFile(cfg.eeprom_path, config);
        } catch (const InputError&) {
            ok = false;  // the EEPROM failed: the unit reports the write as refused
        }
    }
    stats.config_writes += ok ? 1 : 0;
    // The F7 reply comes once the EEPROM is written: seconds (reference section 1).
    Chunk c;
    c.bytes = EncodeTelegram(MakeWriteConfigReply(ok, config));
    c.hold_until = Clock::now() + Duration(ok ? cfg.config_write_s : 0.0);
    EnqueueFrame(std::move(c));
}

int VirtualLms200::Impl::UnitTurns(const OutputMode& m) const {
    if (m.kind == OutputKind::kPartial) {
        return 1;
    }
    return variant.Turns() * (m.HasMean() ? m.mean_scans : 1);
}

namespace {

/// Mean of the range values of `samples` per beam (rounded to the unit); a beam without a
/// range in any sample keeps the last sample's special code.
void MeanOf(const std::vector<MeasuredValues>& samples,
            const core::Lms200Format& format,
            MeasuredValues& out) {
    out.values = samples.back().values;
    for (std::size_t i = 0; i < out.values.size(); ++i) {
        double sum_m = 0.0;
        int count = 0;
        for (const MeasuredValues& s : samples) {
            const core::Beam b = format.Decode(s.values[i]);
            if (b.status == core::BeamStatus::kOk) {
                sum_m += static_cast<double>(b.range_m);
                ++count;
            }
        }
        if (count > 0) {
            out.values[i] = format.EncodeRange(sum_m / count);
        }
    }
}

}  // namespace

bool VirtualLms200::Impl::BuildValues(const OutputMode& m, std::int64_t unit, Chunk& c) {
    const int k = variant.Turns();
    const auto sweep_of = [&](std::uint64_t index) -> bool {
        std::optional<core::Scan> scan = source.Sweep(index, variant);
        if (!scan) {
            stats.source_exhausted = true;
            return false;
        }
        if (scan->beams.size() != static_cast<std::size_t>(variant.BeamCount())) {
            throw MakeInputError("virtual LMS 200 scan source",
                                 "beams of sweep " + std::to_string(index),
                                 std::to_string(scan->beams.size()),
                                 "the variant has " + std::to_string(variant.BeamCount()));
        }
        ValuesFromScan(*scan, format, values);
        return true;
    };
    values.command = m.ReplyCommand();
    values.partial = false;
    values.partial_index = 0;
    values.sample_size = 0;
    values.first_beam = values.last_beam = 0;
    values.realtime_index.clear();
    const auto u = static_cast<std::uint64_t>(unit);
    if (m.HasMean()) {
        const auto n = static_cast<std::uint64_t>(m.mean_scans);
        std::vector<MeasuredValues> samples;
        for (std::uint64_t j = 0; j < n; ++j) {
            if (!sweep_of(u * n + j)) {
                return false;
            }
            samples.push_back(values);
        }
        MeanOf(samples, format, values);
        values.sample_size = static_cast<std::uint8_t>(n);
        c.scan_index = u * n + n - 1;
    } else {
        c.scan_index = m.kind == OutputKind::kPartial ? u / static_cast<std::uint64_t>(k) : u;
        if (!sweep_of(*c.scan_index)) {
            return false;
        }
    }
    if (m.HasSubRange()) {
        values.values.erase(values.values.begin() + m.last_beam, values.values.end());
        values.values.erase(values.values.begin(), values.values.begin() + (m.first_beam - 1));
        values.first_beam = static_cast<std::uint16_t>(m.first_beam);
        values.last_beam = static_cast<std::uint16_t>(m.last_beam);
    }
    if (m.kind == OutputKind::kPartial) {  // keep the beams of this turn: i mod k == p
        const int p = static_cast<int>(unit % k);
        std::size_t kept = 0;
        for (std::size_t i = static_cast<std::size_t>(p); i < values.values.size();
             i += static_cast<std::size_t>(k)) {
            values.values[kept++] = values.values[i];
        }
        values.values.resize(kept);
        values.partial = true;
        values.partial_index = static_cast<std::uint8_t>(p * variant.resolution_cdeg / 25);
        c.partial = p;
    }
    c.command = values.command;
    return true;
}

/// Queues the telegram of the newest completed unit (scan, n scans, or turn); false if none.
bool VirtualLms200::Impl::QueueNewestScan(bool on_request) {
    const std::int64_t turns = TurnsDone(Clock::now());
    if (!origin_turn) {
        origin_turn = turns;
    }
    const OutputMode m = on_request ? OutputMode::Continuous() : stream_mode;
    const int per_unit = UnitTurns(m);
    const std::int64_t newest = (turns - *origin_turn) / per_unit - 1;
    if (newest < 0 || (!on_request && last_sent_unit && newest <= *last_sent_unit)) {
        return false;
    }
    const auto completion = [&](std::int64_t u) {
        const std::int64_t end_turn = *origin_turn + (u + 1) * per_unit;
        return epoch + Duration(static_cast<double>(end_turn) * core::Lms200Timing::kTurnPeriodS);
    };
    std::int64_t unit = newest;
    std::optional<Clock::time_point> start;
    if (!on_request && last_sent_unit) {
        // A real-time scanner starts each telegram at max(line free, data complete) with
        // the newest data complete by then. Replay that schedule so this emulator's own
        // scheduling delays (up to 50 ms) neither drop telegrams nor change which are sent.
        const Clock::time_point line_free = next_byte;
        const std::int64_t first = *last_sent_unit + 1;
        if (Clock::now() - std::max(line_free, completion(first)) < Duration(0.05)) {
            unit = first;
            while (unit < newest && completion(unit + 1) <= line_free) {
                ++unit;
            }
            start = std::max(line_free, completion(unit));
        }
        stats.scans_skipped += static_cast<std::uint64_t>(unit - first);
    }
    Chunk c;
    if (!BuildValues(m, unit, c)) {
        return false;
    }
    if (!on_request) {
        last_sent_unit = unit;
    }
    const std::int64_t end_turn = *origin_turn + (unit + 1) * per_unit;
    if (config.realtime_indices()) {  // the turn at which the data was complete, mod 256
        values.realtime_index.assign(1, static_cast<std::uint8_t>(end_turn & 0xFF));
    }
    AppendMeasuredValues(values, c.bytes);
    // Beam 0 of the sweep c.scan_index: its last turn ends at end_turn (a partial scan's
    // sweep began p turns before this turn).
    const double turn_s = core::Lms200Timing::kTurnPeriodS;
    const double before_s = m.kind == OutputKind::kPartial
                                ? static_cast<double>(c.partial) * turn_s +
                                      static_cast<double>(variant.angle_deg) / 360.0 * turn_s
                                : SweepDurationS(variant);
    c.beam0_wall_s = epoch_wall_s + static_cast<double>(end_turn) * turn_s - before_s;
    EnqueueFrame(std::move(c), start);
    return true;
}

}  // namespace casmap::drivers
