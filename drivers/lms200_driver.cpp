#include "casmap/drivers/lms200_driver.hpp"

#include <algorithm>
#include <thread>

#include "casmap/core/input_error.hpp"
#include "casmap/drivers/scan_codec.hpp"

namespace casmap::drivers {
namespace {

double Seconds(std::chrono::steady_clock::duration d) {
    return std::chrono::duration<double>(d).count();
}

std::chrono::steady_clock::duration Duration(double s) {
    return std::chrono::duration_cast<std::chrono::steady_clock::duration>(
        std::chrono::duration<double>(s));
}

double WallNowS() {
    return std::chrono::duration<double>(std::chrono::system_clock::now().time_since_epoch())
        .count();
}

constexpr double kSilentLineS = 0.15;  // no ACK and no byte for this long: give up the try

void Sleep(double s) { std::this_thread::sleep_for(std::chrono::duration<double>(s)); }

void CheckPositive(double v, const char* field) {
    if (!(v > 0.0)) {
        throw MakeInputError("LMS 200 driver", field, std::to_string(v), "must be > 0");
    }
}

}  // namespace

void DriverConfig::Validate() const {
    if (device.empty()) {
        throw MakeInputError("LMS 200 driver", "--device", "", "a serial device path is required");
    }
    CheckLmsBaud(baud, "--baud");
    if (variant && !variant->IsValid()) {
        throw MakeInputError(
            "LMS 200 driver", "variant",
            std::to_string(variant->angle_deg) + "," + std::to_string(variant->resolution_cdeg),
            "180,100 180,50 100,100 100,50 or 100,25 (deg, 1/100 deg)");
    }
    if (tries < 1) {
        throw MakeInputError("LMS 200 driver", "tries", std::to_string(tries), ">= 1");
    }
    CheckPositive(reply_timeout_s, "reply_timeout_s");
    CheckPositive(mode_timeout_s, "mode_timeout_s");
    CheckPositive(quiet_timeout_s, "quiet_timeout_s");
    CheckPositive(inter_byte_timeout_s, "inter_byte_timeout_s");
    CheckPositive(sync_window_s, "sync_window_s");
}

Lms200Driver::Lms200Driver(DriverConfig config) : config_(std::move(config)) {
    config_.Validate();
    buffer_.resize(4096);
}

Lms200Driver::~Lms200Driver() {
    try {
        Close();
    } catch (...) {  // NOLINT(bugprone-empty-catch): best effort on destruction
    }
}

void Lms200Driver::Connect() {
    port_ = std::make_unique<SerialPort>(config_.device, 9600);
    try {
        Initialise();
    } catch (...) {
        port_.reset();
        throw;
    }
}

bool Lms200Driver::FindScanner() {
    // The power-on rate first; a scanner left at another rate answers the 0x32 probe there
    // (sicktoolbox's autodetection order).
    port_->SetBaud(9600);
    if (Transact(MakeBaudRequest(config_.baud), config_.mode_timeout_s, config_.tries)) {
        port_->SetBaud(config_.baud);
        Sleep(config_.baud_settle_s);
        return true;
    }
    if (!config_.autodetect) {
        return false;
    }
    for (const int rate : {19200, 38400, 500000}) {
        port_->SetBaud(rate);
        if (!Transact(MakeErrorRequest(), config_.reply_timeout_s, 1)) {
            continue;
        }
        if (rate != config_.baud) {
            if (!Transact(MakeBaudRequest(config_.baud), config_.mode_timeout_s, config_.tries)) {
                return false;
            }
            port_->SetBaud(config_.baud);
            Sleep(config_.baud_settle_s);
        }
        return true;
    }
    return false;
}

Telegram Lms200Driver::Require(const Telegram& request, double timeout_s, const char* what) {
    std::optional<Telegram> reply = Transact(request, timeout_s, config_.tries);
    if (!reply) {
        throw SerialError(config_.device + ": no reply to " + what);
    }
    if (reply->command == cmd::kNotAcknowledged) {
        throw MakeInputError(config_.device, what, "", "refused by the scanner (reply 0x92)");
    }
    return *reply;
}

void Lms200Driver::Initialise() {
    parser_.Reset();
    streaming_ = false;
    ready_.clear();
    if (!FindScanner()) {
        throw SerialError(config_.device +
                          ": no LMS 200 answers at 9600, 19200, 38400 or 500000 baud");
    }
    if (ParseModeReply(Require(MakeModeRequest(mode::kRequest), config_.mode_timeout_s,
                               "request mode 0x20 0x25")) != 0) {
        throw SerialError(config_.device + ": scanner refused request mode 0x25");
    }
    info_.type = ParseTypeReply(Require(MakeTypeRequest(), config_.reply_timeout_s, "type 0x3A"));
    info_.status =
        ParseStatusReply(Require(MakeStatusRequest(), config_.reply_timeout_s, "status 0x31"));
    info_.config = ParseConfigReply(
        Require(MakeReadConfigRequest(), config_.reply_timeout_s, "configuration 0x74"));
    info_.format = FormatOf(info_.config);
    info_.variant = info_.status.variant;
    if (config_.variant && *config_.variant != info_.variant) {
        const VariantReply r = ParseVariantReply(
            Require(MakeVariantRequest(*config_.variant), config_.reply_timeout_s, "variant 0x3B"));
        if (!r.accepted) {
            throw MakeInputError(config_.device, "variant",
                                 std::to_string(config_.variant->angle_deg) + "," +
                                     std::to_string(config_.variant->resolution_cdeg),
                                 "refused by the scanner");
        }
        info_.variant = r.variant;
    }
    if (!info_.variant.IsValid()) {
        throw MakeInputError(config_.device, "status variant",
                             std::to_string(info_.variant.angle_deg) + "," +
                                 std::to_string(info_.variant.resolution_cdeg),
                             "not an LMS 200 variant");
    }
    if (ParseModeReply(Require(MakeModeRequest(mode::kStreamAll), config_.mode_timeout_s,
                               "continuous output 0x20 0x24")) != 0) {
        throw SerialError(config_.device + ": scanner refused continuous output 0x24");
    }
    info_.baud = port_->baud();
    // The scan clock restarts with every connection (the mirror may have restarted). It needs
    // a line that carries every sweep: when a telegram takes longer than a scan period, the
    // scanner sends the newest sweep whenever the line frees, at a phase unrelated to the
    // sweep grid, and the arrival times hold no information about it.
    const double period_s = ScanPeriodS(info_.variant);
    const std::size_t frame_bytes =
        kFrameOverhead + 4 + 2 * static_cast<std::size_t>(info_.variant.BeamCount());
    sync_ = config_.stamps == StampMode::kScanClock &&
            TransmissionTimeS(frame_bytes, info_.baud) < period_s;
    sync_outliers_ += clock_.outliers();
    ScanClockConfig cc;
    cc.period_s = period_s;
    cc.window_s = config_.sync_window_s;
    clock_ = ScanClock(cc);
    held_.clear();
    streaming_ = true;
    last_scan_ = Clock::now();
}

std::optional<Telegram> Lms200Driver::Transact(const Telegram& request,
                                               double timeout_s,
                                               int tries) {
    const std::vector<std::uint8_t> frame = EncodeTelegram(request);
    // The ACK comes within 60 ms, but only after a telegram already on the line.
    const double ack_window_s = 0.1 + TransmissionTimeS(kMaxFrameBytes, port_->baud());
    for (int attempt = 0; attempt < tries; ++attempt) {
        if (attempt > 0) {
            ++own_.retries;
        }
        port_->Flush();
        parser_.Reset();
        ready_.clear();
        awaited_.reset();
        awaited_cmd_ = static_cast<std::uint8_t>(request.command | cmd::kReplyBit);
        saw_ack_ = saw_nak_ = saw_bad_crc_ = false;
        if (config_.request_byte_gap_s > 0.0) {
            port_->WriteSlowly(frame, config_.request_byte_gap_s);
        } else {
            port_->Write(frame, 1.0);
        }
        Clock::time_point deadline = Clock::now() + Duration(ack_window_s);
        Clock::time_point last_byte = Clock::now();
        bool acked = false;
        while (Clock::now() < deadline) {
            if (ReadSome(std::min(config_.inter_byte_timeout_s,
                                  std::max(0.0, Seconds(deadline - Clock::now())))) > 0) {
                last_byte = Clock::now();
            }
            // Before the ACK, silence means no telegram is in flight either (the LMS leaves
            // at most 14 ms between bytes) and the ACK (due within 60 ms) is not coming.
            if (!acked && !saw_ack_ && Seconds(Clock::now() - last_byte) > kSilentLineS) {
                break;
            }
            if (awaited_) {
                awaited_cmd_ = 0;
                return awaited_;
            }
            if (saw_nak_) {
                Sleep(0.03);  // TL 4.3: wait at least 30 ms before sending again
                break;
            }
            if (saw_ack_ && !acked) {
                acked = true;
                deadline = Clock::now() + Duration(timeout_s);
            }
            if (acked && saw_bad_crc_) {
                break;  // the reply was damaged or cut short: ask again at once
            }
        }
    }
    awaited_cmd_ = 0;
    return std::nullopt;
}

std::size_t Lms200Driver::ReadSome(double timeout_s) {
    const std::size_t n = port_->Read(buffer_, timeout_s);
    const double arrival_s = WallNowS();
    const TelegramParser::Callback cb = [this, arrival_s](ParserEvent e, const Telegram& t) {
        switch (e) {
            case ParserEvent::kTelegram:
                OnTelegram(t, arrival_s);
                break;
            case ParserEvent::kAckByte:
                saw_ack_ = saw_ack_ || parser_.InSync();  // an ACK inside noise means nothing
                break;
            case ParserEvent::kNakByte:
                saw_nak_ = saw_nak_ || (parser_.InSync() && awaited_cmd_ != 0);
                break;
            case ParserEvent::kBadCrc:
                saw_bad_crc_ = true;
                break;
        }
    };
    if (n == 0) {
        if (parser_.InFrame()) {
            saw_bad_crc_ = true;  // a telegram stopped short: damaged
            parser_.Timeout(cb);
        }
        return 0;
    }
    parser_.Feed(std::span(buffer_.data(), n), cb);
    return n;
}

void Lms200Driver::OnTelegram(const Telegram& t, double arrival_s) {
    if (awaited_cmd_ != 0 && (t.command == awaited_cmd_ || t.command == cmd::kNotAcknowledged)) {
        awaited_ = t;
        return;
    }
    if (t.command != (cmd::kScan | cmd::kReplyBit) || !streaming_) {
        return;  // e.g. a late reply or the 0x90 power-on telegram
    }
    try {
        const MeasuredValues v = ParseMeasuredValues(t);
        if (v.partial) {
            throw MakeInputError("LMS 200 telegram 0xB0", "partial flag", "1", "0 in mode 0x24");
        }
        const double latest_s = arrival_s -
                                TransmissionTimeS(t.Len() + kFrameOverhead, port_->baud()) -
                                SweepDurationS(info_.variant);
        if (!sync_) {
            ready_.push_back(ScanFromValues(v, info_.format, info_.variant, latest_s));
        } else {
            const double stamp_s = clock_.Stamp(latest_s);
            core::Scan scan = ScanFromValues(v, info_.format, info_.variant, stamp_s);
            const auto hold = static_cast<std::uint64_t>(ScanClockConfig{}.warmup_scans);
            if (clock_.scans() > hold) {
                ready_.push_back(std::move(scan));
            } else {
                held_.emplace_back(std::move(scan), clock_.last_index());
                if (clock_.scans() == hold) {  // re-stamp the first scans with the better phase
                    const double period_s = ScanPeriodS(info_.variant);
                    for (auto& [held, k] : held_) {
                        held.stamp_s = clock_.phase_s() + static_cast<double>(k) * period_s;
                        ready_.push_back(std::move(held));
                    }
                    held_.clear();
                }
            }
        }
        ++own_.scans;
        last_scan_ = Clock::now();
    } catch (const InputError&) {
        ++own_.malformed;
    }
}

bool Lms200Driver::TryReconnect(Clock::time_point deadline) {
    while (Clock::now() < deadline) {
        try {
            port_ = std::make_unique<SerialPort>(config_.device, 9600);
            Initialise();
            return true;
        } catch (const std::exception&) {
            port_.reset();  // the device may still be away: try again
            Sleep(std::min(0.05, std::max(0.0, Seconds(deadline - Clock::now()))));
        }
    }
    return false;
}

std::optional<core::Scan> Lms200Driver::NextScan(double timeout_s) {
    const Clock::time_point deadline = Clock::now() + Duration(timeout_s);
    for (;;) {
        if (!ready_.empty()) {
            core::Scan scan = std::move(ready_.front());
            ready_.pop_front();
            return scan;
        }
        const Clock::time_point now = Clock::now();
        if (now >= deadline) {
            return std::nullopt;
        }
        if (!port_) {
            if (!TryReconnect(deadline)) {
                return std::nullopt;
            }
            continue;
        }
        try {
            ReadSome(std::min(config_.inter_byte_timeout_s, Seconds(deadline - now)));
        } catch (const SerialError&) {
            port_.reset();  // device gone: reconnect
            ++own_.reconnects;
            continue;
        }
        // Quiet line: at least twice the longest frame's transmission time.
        const double quiet_s = std::max(config_.quiet_timeout_s,
                                        2.0 * TransmissionTimeS(kMaxFrameBytes, port_->baud()));
        if (ready_.empty() && Seconds(Clock::now() - last_scan_) > quiet_s) {
            port_.reset();
            ++own_.reconnects;
        }
    }
}

void Lms200Driver::Close() {
    if (!port_) {
        return;
    }
    try {
        if (streaming_) {
            streaming_ = false;
            (void)Transact(MakeModeRequest(mode::kRequest), config_.mode_timeout_s, 1);
        }
        if (port_->baud() != 9600 && Transact(MakeBaudRequest(9600), config_.mode_timeout_s, 1)) {
            port_->SetBaud(9600);
        }
    } catch (const std::exception&) {  // NOLINT(bugprone-empty-catch): best effort
    }
    port_.reset();
}

DriverCounters Lms200Driver::counters() const {
    DriverCounters c = own_;
    const ParserCounters& p = parser_.counters();
    c.bytes = p.bytes;
    c.telegrams = p.telegrams;
    c.crc_errors = p.crc_errors;
    c.bad_headers = p.bad_headers;
    c.dropped_bytes = p.dropped_bytes;
    c.resyncs = p.resyncs;
    c.naks = p.naks;
    c.sync_outliers = sync_outliers_ + clock_.outliers();
    return c;
}

}  // namespace casmap::drivers
