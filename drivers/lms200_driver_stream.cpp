// The reading half of the LMS 200 driver: bytes -> telegrams (with the follower check) ->
// measured values checked against the configuration -> stamped core::Scans (docs/drivers.md).
#include <algorithm>
#include <chrono>
#include <cmath>

#include "casmap/core/input_error.hpp"
#include "casmap/drivers/lms200_driver.hpp"
#include "casmap/drivers/scan_codec.hpp"

namespace casmap::drivers {
namespace {

double Seconds(std::chrono::steady_clock::duration d) {
    return std::chrono::duration<double>(d).count();
}

double WallNowS() {
    return std::chrono::duration<double>(std::chrono::system_clock::now().time_since_epoch())
        .count();
}

}  // namespace

bool Lms200Driver::MaybeAwaited(std::uint8_t command) const {
    // A damaged candidate that may have been the awaited reply (or whose command byte was
    // lost) ends the try at once; a damaged stream telegram (e.g. 0xB0 while a 0x20 reply is
    // awaited) does not: under heavy damage the stream would otherwise abort every try.
    return awaited_cmd_ != 0 &&
           (command == 0 || command == awaited_cmd_ || command == cmd::kNotAcknowledged);
}

std::size_t Lms200Driver::ReadSome(double timeout_s) {
    double wait_s = timeout_s;
    if (parser_.Pending()) {  // a complete telegram waits for the next byte or for idle
        wait_s = std::min(
            wait_s, std::max(0.0, config_.idle_confirm_s - Seconds(Clock::now() - last_byte_)));
    }
    std::size_t n = 0;
    std::optional<SerialError> hung_up;
    try {
        n = port_->Read(buffer_, wait_s);
    } catch (const SerialError& e) {
        hung_up = e;  // the line went dead: a telegram completed before stands
    }
    const double arrival_s = WallNowS();
    // When this read returned, every byte of it had arrived; a byte followed by m more in the
    // same read arrived at least m byte times earlier (a serial line carries them one after
    // the other). So a telegram that ends inside the read is stamped that much earlier: after
    // a stall of this process the backlog of telegrams no longer looks late by the stall,
    // which would put them into later sweep slots (ServeRecord.AStalledScanner...).
    const double byte_s = ByteTimeS(port_->baud());
    const std::uint64_t fed_before = parser_.counters().bytes;
    const TelegramParser::Callback cb = [&](ParserEvent e, const Telegram& t) {
        switch (e) {
            case ParserEvent::kTelegram: {
                const std::uint64_t after = n - (parser_.counters().bytes - fed_before);
                arrived_.emplace_back(t, has_pending_arrival_
                                             ? pending_arrival_s_
                                             : arrival_s - static_cast<double>(after) * byte_s);
                has_pending_arrival_ = false;
                break;
            }
            case ParserEvent::kAckByte:
                saw_ack_ = saw_ack_ || parser_.InSync();  // an ACK inside noise means nothing
                break;
            case ParserEvent::kNakByte:
                saw_nak_ = saw_nak_ || (parser_.InSync() && awaited_cmd_ != 0);
                break;
            case ParserEvent::kBadCrc:
                saw_bad_crc_ = saw_bad_crc_ || MaybeAwaited(parser_.last_rejected_command());
                break;
            case ParserEvent::kBadFollower:
                has_pending_arrival_ = false;
                saw_bad_crc_ = saw_bad_crc_ || MaybeAwaited(parser_.last_rejected_command());
                break;
        }
    };
    if (hung_up) {
        parser_.Idle(cb);
        DeliverArrived();
        throw *hung_up;
    }
    if (n == 0) {
        const double quiet_s = Seconds(Clock::now() - last_byte_);
        if (parser_.Pending() && quiet_s >= config_.idle_confirm_s) {
            parser_.Idle(cb);  // the line went idle after the telegram: it stands
        }
        if (parser_.InFrame() && quiet_s >= config_.inter_byte_timeout_s) {
            parser_.Timeout(cb);  // a telegram stopped short: damaged
            saw_bad_crc_ = saw_bad_crc_ || MaybeAwaited(parser_.last_rejected_command());
        }
        DeliverArrived();
        return 0;
    }
    last_byte_ = Clock::now();
    const std::uint64_t bad_headers = parser_.counters().bad_headers;
    parser_.Feed(std::span(buffer_.data(), n), cb);
    DeliverArrived();
    if (parser_.counters().bad_headers != bad_headers) {  // e.g. a reply that lost a LEN byte
        saw_bad_crc_ = saw_bad_crc_ || MaybeAwaited(parser_.last_rejected_command());
    }
    if (parser_.Pending() && !has_pending_arrival_) {
        pending_arrival_s_ = arrival_s;
        has_pending_arrival_ = true;
    }
    return n;
}

void Lms200Driver::DeliverArrived() {
    // The scanner sends one measured-value telegram per telegram period (BoundArrivalsInRead).
    // (Bytes before a telegram that delay it, e.g. line noise, could make the bound early by
    // their transmission time.)
    if ((streaming_ || starting_output_) && arrived_.size() > 1) {
        std::vector<ReadTelegram> read(arrived_.size());
        for (std::size_t i = 0; i < arrived_.size(); ++i) {
            read[i] = {arrived_[i].second, IsMeasuredValues(arrived_[i].first.command)};
        }
        BoundArrivalsInRead(read, TelegramPeriodS(info_.output, info_.variant));
        for (std::size_t i = 0; i < arrived_.size(); ++i) {
            arrived_[i].second = read[i].arrival_s;
        }
    }
    for (const auto& [t, arrival_s] : arrived_) {
        OnTelegram(t, arrival_s);
    }
    arrived_.clear();
}

void Lms200Driver::OnTelegram(const Telegram& t, double arrival_s) {
    if (awaited_cmd_ != 0 && (t.command == awaited_cmd_ || t.command == cmd::kNotAcknowledged)) {
        awaited_ = t;
        return;
    }
    if (IsMeasuredValues(t.command) && starting_output_ && awaited_) {
        early_.emplace_back(t, arrival_s);  // the stream began right after the A0 reply
        return;
    }
    if (!IsMeasuredValues(t.command) || !streaming_) {
        return;  // e.g. a late reply or the 0x90 power-on telegram
    }
    try {
        OnValues(ParseMeasuredValues(t), arrival_s, t.Len() + kFrameOverhead);
    } catch (const InputError&) {
        ++own_.malformed;
    }
}

std::int64_t Lms200Driver::UnwrapIndex(std::uint8_t index, double latest_s) const {
    if (!have_turn_) {
        return index;
    }
    const double period_s = clock_.period_s();
    const auto estimate =
        static_cast<std::int64_t>(std::llround((latest_s - clock_.phase_s()) / period_s));
    std::int64_t d = (static_cast<std::int64_t>(index) - estimate) % 256;
    if (d < -128) {
        d += 256;
    } else if (d >= 128) {
        d -= 256;
    }
    return std::max(estimate + d, last_turn_ + 1);
}

void Lms200Driver::OnValues(const MeasuredValues& v, double arrival_s, std::size_t frame_bytes) {
    const FrameExpectation e = Expectation();
    if (config_.strict_checks) {
        CheckMeasuredValues(v, e);
    } else if (v.command != info_.output.ReplyCommand()) {
        throw MakeInputError("LMS 200 telegram " + CommandName(v.command), "command",
                             CommandName(v.command), "not the output mode's");
    }
    const double latest_s = arrival_s - TransmissionTimeS(frame_bytes, port_->baud()) -
                            TelegramSweepS(info_.output, info_.variant);
    const bool indexed = e.realtime_indices && v.realtime_index.size() == 1;
    core::Scan scan = ScanFromFrame(v, e, latest_s);
    const double shift_s = scan.stamp_s - latest_s;
    ++own_.scans;
    last_scan_ = Clock::now();
    if (!sync_) {
        ready_.push_back(std::move(scan));
        return;
    }
    double grid_s = 0.0;
    if (indexed) {
        const std::int64_t k = UnwrapIndex(v.realtime_index[0], latest_s);
        grid_s = clock_.StampIndexed(latest_s, k);
        last_turn_ = k;
        have_turn_ = true;
        ++own_.realtime_scans;
    } else {
        grid_s = clock_.Stamp(latest_s);
    }
    scan.stamp_s = grid_s + shift_s;
    const auto hold = static_cast<std::uint64_t>(ScanClockConfig{}.warmup_scans);
    if (clock_.scans() > hold) {
        ready_.push_back(std::move(scan));
        return;
    }
    held_.push_back({std::move(scan), clock_.last_index(), shift_s, latest_s});
    if (clock_.scans() == hold) {  // re-stamp the first scans with the better phase
        ReleaseHeld(indexed);
    }
}

void Lms200Driver::ReleaseHeld(bool indexed) {
    const double phase_s = clock_.phase_s();
    if (!indexed) {  // a late scan may have pushed the clock's first slots (ReslotHeldScans)
        std::vector<std::int64_t> k;
        std::vector<double> latest_s;
        for (const HeldScan& h : held_) {
            k.push_back(h.k);
            latest_s.push_back(h.latest_s);
        }
        ScanClockConfig config;
        config.period_s = clock_.period_s();
        ReslotHeldScans(k, latest_s, phase_s, config);
        for (std::size_t i = 0; i < held_.size(); ++i) {
            held_[i].k = k[i];
        }
    }
    for (HeldScan& h : held_) {
        h.scan.stamp_s = phase_s + static_cast<double>(h.k) * clock_.period_s() + h.shift_s;
        ready_.push_back(std::move(h.scan));
    }
    held_.clear();
}

}  // namespace casmap::drivers
