#include "casmap/drivers/lms200_driver.hpp"

#include <algorithm>
#include <cmath>
#include <thread>

#include "casmap/core/check.hpp"
#include "casmap/core/input_error.hpp"
#include "casmap/core/text.hpp"
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

constexpr double kSilentLineS = 0.15;  // no ACK and no byte for this long: give up the try

void Sleep(double s) { std::this_thread::sleep_for(std::chrono::duration<double>(s)); }

}  // namespace

void DriverConfig::Validate() const {
    const core::Check check("LMS 200 driver");
    check.That(!device.empty(), "device", "", "a serial device path is required");
    CheckLmsBaud(baud, "baud");
    if (variant) {
        check.That(
            variant->IsValid(), "variant",
            std::to_string(variant->angle_deg) + "," + std::to_string(variant->resolution_cdeg),
            "180,100 180,50 100,100 100,50 or 100,25 (deg, 1/100 deg)");
    }
    check.That(tries >= 1, "tries", tries, ">= 1");
    // A NaN timeout would wait forever: every timeout must be a number > 0 (infinity allowed).
    const auto positive = [&check](const char* field, double v) {
        check.That(v > 0.0, field, v, "must be > 0");
    };
    positive("reply_timeout_s", reply_timeout_s);
    positive("mode_timeout_s", mode_timeout_s);
    positive("quiet_timeout_s", quiet_timeout_s);
    positive("inter_byte_timeout_s", inter_byte_timeout_s);
    positive("sync_window_s", sync_window_s);
    positive("write_timeout_s", write_timeout_s);
    positive("reset_timeout_s", reset_timeout_s);
    positive("idle_confirm_s", idle_confirm_s);
    check.That(password.size() == 8, "password",
               "(" + std::to_string(password.size()) + " characters)", "exactly 8 characters");
    if (variant) {
        output.Validate(*variant);
    } else {  // the sub-range is checked against the device's variant at Connect
        OutputMode m = output;
        if (m.HasSubRange()) {
            m.first_beam = m.last_beam = 1;
        }
        m.Validate(Variant{});
    }
    CheckConfigBlock(config_changes.ApplyTo(ConfigBlock::Default()),
                     "LMS 200 driver configuration changes");
}

ConfigBlock ConfigChanges::ApplyTo(ConfigBlock config) const {
    if (measuring_mode) {
        config.set_measuring_mode(*measuring_mode);
    }
    if (units) {
        config.set_units(*units);
    }
    if (availability) {
        config.set_availability(*availability);
    }
    if (sensitivity) {
        config.set_sensitivity(*sensitivity);
    }
    return config;
}

Lms200Driver::Lms200Driver(DriverConfig config)
    : config_(std::move(config)), parser_(Sender::kScanner, 0, config_.strict_checks) {
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

Telegram Lms200Driver::Require(const Telegram& request,
                               double timeout_s,
                               const char* what,
                               std::uint8_t reply_cmd) {
    std::optional<Telegram> reply = Transact(request, timeout_s, config_.tries, reply_cmd);
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
    has_pending_arrival_ = false;
    streaming_ = false;
    ready_.clear();
    if (!FindScanner()) {
        throw SerialError(config_.device +
                          ": no LMS 200 answers at 9600, 19200, 38400 or 500000 baud");
    }
    info_.baud = port_->baud();
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
    if (!config_.config_changes.Empty()) {
        const ConfigBlock wanted = config_.config_changes.ApplyTo(info_.config);
        if (wanted != info_.config) {
            WriteConfig(wanted);
        }
    }
    if (config_.variant && *config_.variant != info_.variant) {
        SetVariant(*config_.variant);
    }
    if (!info_.variant.IsValid()) {
        throw MakeInputError(config_.device, "status variant",
                             std::to_string(info_.variant.angle_deg) + "," +
                                 std::to_string(info_.variant.resolution_cdeg),
                             "not an LMS 200 variant");
    }
    config_.output.Validate(info_.variant);
    info_.output = config_.output;
    StartOutput();
}

void Lms200Driver::StartOutput() {
    early_.clear();
    starting_output_ = true;
    std::uint8_t result = 0;
    try {
        result = ParseModeReply(Require(MakeOutputModeRequest(info_.output), config_.mode_timeout_s,
                                        "output mode 0x20"));
    } catch (...) {
        starting_output_ = false;
        throw;
    }
    starting_output_ = false;
    if (result != 0) {
        throw MakeInputError(config_.device, "output mode", info_.output.ToString(),
                             "refused by the scanner (A0 result " + std::to_string(result) + ")");
    }
    RestartClock();
    streaming_ = true;
    last_scan_ = Clock::now();
    for (const auto& [t, arrival_s] : early_) {
        OnTelegram(t, arrival_s);
    }
    early_.clear();
}

bool Lms200Driver::StopOutput() {
    const bool was = streaming_;
    if (streaming_) {
        streaming_ = false;
        if (ParseModeReply(Require(MakeModeRequest(mode::kRequest), config_.mode_timeout_s,
                                   "request mode 0x20 0x25")) != 0) {
            throw SerialError(config_.device + ": scanner refused request mode 0x25");
        }
    }
    ready_.clear();
    return was;
}

void Lms200Driver::RestartClock() {
    // The scan clock restarts with every connection and mode change (the mirror may have
    // restarted). Without real-time indices it needs a line that carries every telegram: when
    // one takes longer than the telegram period, the scanner sends the newest data whenever
    // the line frees, at a phase unrelated to the sweep grid, and the arrival times alone
    // cannot tell which sweep a telegram carries. With the indices they can.
    const bool indexed = info_.config.realtime_indices();
    const double period_s = TelegramPeriodS(info_.output, info_.variant);
    const std::size_t frame_bytes =
        kFrameOverhead + 10 + 2 * static_cast<std::size_t>(ValueCount(info_.output, info_.variant));
    sync_ = config_.stamps == StampMode::kScanClock &&
            (indexed || TransmissionTimeS(frame_bytes, info_.baud) < period_s);
    sync_outliers_ += clock_.outliers();
    ScanClockConfig cc;
    cc.period_s = indexed ? core::Lms200Timing::kTurnPeriodS : period_s;
    cc.window_s = config_.sync_window_s;
    clock_ = ScanClock(cc);
    held_.clear();
    have_turn_ = false;
}

FrameExpectation Lms200Driver::Expectation() const {
    FrameExpectation e;
    e.variant = info_.variant;
    e.mode = info_.output;
    e.format = info_.format;
    e.realtime_indices = info_.config.realtime_indices();
    e.value_flags = config_.value_flags;
    return e;
}

void Lms200Driver::RequireConnected(const char* what) const {
    if (!port_) {
        throw SerialError(config_.device + ": " + what + " needs a connected scanner");
    }
}

std::optional<Telegram> Lms200Driver::Transact(const Telegram& request,
                                               double timeout_s,
                                               int tries,
                                               std::uint8_t reply_cmd) {
    const std::vector<std::uint8_t> frame = EncodeTelegram(request);
    // The ACK comes within 60 ms, but only after a telegram already on the line.
    const double ack_window_s = 0.1 + TransmissionTimeS(kMaxFrameBytes, port_->baud());
    for (int attempt = 0; attempt < tries; ++attempt) {
        if (attempt > 0) {
            ++own_.retries;
        }
        port_->Flush();
        parser_.Reset();
        has_pending_arrival_ = false;
        ready_.clear();
        awaited_.reset();
        awaited_cmd_ = reply_cmd != 0 ? reply_cmd
                                      : static_cast<std::uint8_t>(request.command | cmd::kReplyBit);
        saw_ack_ = saw_nak_ = saw_bad_crc_ = false;
        if (config_.request_byte_gap_s > 0.0) {
            port_->WriteSlowly(frame, config_.request_byte_gap_s);
        } else {
            port_->Write(frame, 1.0);
        }
        Clock::time_point deadline = Clock::now() + Duration(ack_window_s);
        last_byte_ = Clock::now();
        bool acked = false;
        while (Clock::now() < deadline) {
            (void)ReadSome(std::min(config_.inter_byte_timeout_s,
                                    std::max(0.0, Seconds(deadline - Clock::now()))));
            // Before the ACK, silence means no telegram is in flight either (the LMS leaves
            // at most 14 ms between bytes) and the ACK (due within 60 ms) is not coming.
            if (!acked && !saw_ack_ && Seconds(Clock::now() - last_byte_) > kSilentLineS) {
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
        // Quiet line: at least twice the longest frame's transmission time, and twice the
        // telegram period (mean values of 250 scans come every 6.7 s at 0.5 deg).
        const double quiet_s = std::max({config_.quiet_timeout_s,
                                         2.0 * TransmissionTimeS(kMaxFrameBytes, port_->baud()),
                                         2.0 * TelegramPeriodS(info_.output, info_.variant)});
        // Bytes still coming (e.g. the backlog after this process stalled) get three times as
        // long to yield a scan before the line counts as dead.
        const double since_scan_s = Seconds(Clock::now() - last_scan_);
        const bool line_quiet = Seconds(Clock::now() - last_byte_) > 0.5 * quiet_s;
        if (ready_.empty() && since_scan_s > quiet_s &&
            (line_quiet || since_scan_s > 3 * quiet_s)) {
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
    c.bad_followers = p.bad_followers;
    c.sync_outliers = sync_outliers_ + clock_.outliers();
    return c;
}

}  // namespace casmap::drivers
