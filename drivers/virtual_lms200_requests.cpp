#include <cmath>
#include <string>

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
    if (t.data.size() != 1 || (m != mode::kDiagnostic && m != mode::kStreamAll &&
                               m != mode::kRequest && m != mode::kStreamPartial)) {
        Reply(MakeNotAcknowledged());
        return;
    }
    const bool streaming = m == mode::kStreamAll || m == mode::kStreamPartial;
    if (streaming && m != op_mode) {
        const std::int64_t turns = TurnsDone(Clock::now());
        if (!origin_turn) {
            origin_turn = turns;
        }
        last_sent_unit.reset();
        if (m == mode::kStreamAll) {  // only sweeps completing from now on
            last_sent_unit = (turns - *origin_turn) / variant.Turns() - 1;
        } else {
            last_sent_unit = turns - *origin_turn - 1;
        }
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
            case cmd::kReset:
                Reply(MakeResetReply(), 0, true);
                return;
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
            format = FormatOf(block);
            config = block;
        } catch (const InputError&) {
            ok = false;
        }
    }
    Reply(MakeWriteConfigReply(ok, config));
}

/// Queues the B0 of the newest completed sweep (0x24) or turn (0x2A); false if none.
bool VirtualLms200::Impl::QueueNewestScan(bool on_request) {
    const std::int64_t turns = TurnsDone(Clock::now());
    if (!origin_turn) {
        origin_turn = turns;
    }
    const bool partial = op_mode == mode::kStreamPartial && !on_request;
    const int k = variant.Turns();
    const std::int64_t newest = partial ? turns - *origin_turn - 1 : (turns - *origin_turn) / k - 1;
    if (newest < 0 || (!on_request && last_sent_unit && newest <= *last_sent_unit)) {
        return false;
    }
    const auto completion = [&](std::int64_t u) {
        const std::int64_t end_turn = *origin_turn + (partial ? u + 1 : (u + 1) * k);
        return epoch + Duration(static_cast<double>(end_turn) * core::Lms200Timing::kTurnPeriodS);
    };
    std::int64_t unit = newest;
    std::optional<Clock::time_point> start;
    if (!on_request && last_sent_unit) {
        // A real-time scanner starts each telegram at max(line free, sweep complete) with
        // the newest sweep complete by then. Replay that schedule so this emulator's own
        // scheduling delays (up to 50 ms) neither drop sweeps nor change which are sent.
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
    const std::uint64_t index = static_cast<std::uint64_t>(partial ? unit / k : unit);
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
    if (!on_request) {
        last_sent_unit = unit;
    }
    ValuesFromScan(*scan, format, values);
    values.partial = partial;
    values.partial_index = 0;
    if (partial) {  // keep the beams of this turn: i mod k == p, offset p * res
        const int p = static_cast<int>(unit % k);
        std::size_t out = 0;
        for (std::size_t i = static_cast<std::size_t>(p); i < values.values.size();
             i += static_cast<std::size_t>(k)) {
            values.values[out++] = values.values[i];
        }
        values.values.resize(out);
        values.partial_index = static_cast<std::uint8_t>(p * variant.resolution_cdeg / 25);
    }
    Chunk c;
    AppendMeasuredValues(values, c.bytes);
    c.scan_index = index;
    // Completed at the end of turn origin + (unit + 1) * turns (one turn per partial).
    const std::int64_t end_turn = *origin_turn + (partial ? unit + 1 : (unit + 1) * k);
    const double sweep_s =
        partial ? static_cast<double>(variant.angle_deg) / 360.0 * core::Lms200Timing::kTurnPeriodS
                : SweepDurationS(variant);
    c.beam0_wall_s =
        epoch_wall_s + static_cast<double>(end_turn) * core::Lms200Timing::kTurnPeriodS - sweep_s;
    EnqueueFrame(std::move(c), start);
    return true;
}

}  // namespace casmap::drivers
