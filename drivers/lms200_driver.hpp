#pragma once

// LMS 200 serial driver: power-on at 9600 baud, switch to the requested rate, read type, status
// and configuration, write configuration changes (installation mode + 0x77), set the variant,
// start the chosen output mode (0x24, 0x26, 0x27, 0x28, 0x2A), deliver core::Scans, and
// reconnect by itself when the line goes quiet or the device disappears (docs/drivers.md).

#include <chrono>
#include <cstdint>
#include <deque>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "casmap/core/lms200.hpp"
#include "casmap/core/scan.hpp"
#include "casmap/drivers/output_mode.hpp"
#include "casmap/drivers/scan_clock.hpp"
#include "casmap/drivers/serial_port.hpp"
#include "casmap/drivers/telegram.hpp"
#include "casmap/drivers/telegram_parser.hpp"

namespace casmap::drivers {

/// How scans are stamped (docs/drivers.md).
enum class StampMode {
    kScanClock,  // on the scanner's sweep grid t0 + k T, phase from the minimum latency
    kArrival,    // arrival - transmission - sweep per scan (jitters with the host's latency)
};

/// Configuration bytes to change (0x77) when the device's differ; unset = keep the device's.
struct ConfigChanges {
    std::optional<std::uint8_t> measuring_mode;  // byte D, 0x00-0x06
    std::optional<std::uint8_t> units;           // byte E, 0 cm, 1 mm
    std::optional<std::uint8_t> availability;    // byte C, bits 0-2 (bit 1: real-time indices)
    std::optional<std::uint8_t> sensitivity;     // byte B (peak threshold), 0-3
    [[nodiscard]] bool Empty() const {
        return !measuring_mode && !units && !availability && !sensitivity;
    }
    /// `config` with the set fields replaced.
    [[nodiscard]] ConfigBlock ApplyTo(ConfigBlock config) const;
};

struct DriverConfig {
    std::string device;                  // e.g. /dev/ttyUSB0 or the virtual scanner's link
    int baud = 38400;                    // rate the driver switches to (9600/19200/38400/500000)
    std::optional<Variant> variant;      // set with 0x3B when given; else the device's current
    OutputMode output;                   // streaming mode started by Connect (default 0x24)
    ConfigChanges config_changes;        // written (0x20 0x00 + 0x77) by Connect if they differ
    std::string password = "SICK_LMS";   // installation mode password (8 characters)
    int tries = 3;                       // per request (sicktoolbox: 3)
    double reply_timeout_s = 1.0;        // after the ACK, per try (sicktoolbox: 1 s)
    double mode_timeout_s = 3.0;         // after the ACK for 0x20, per try (TL: up to 3 s)
    double write_timeout_s = 15.0;       // after the ACK for 0x77 (EEPROM write; sicktoolbox 15 s)
    double reset_timeout_s = 5.0;        // 0x10: until the 0x90 power-on telegram
    double baud_settle_s = 0.05;         // pause after changing the host rate
    double quiet_timeout_s = 1.0;        // no scan for this long while streaming -> reconnect
    double inter_byte_timeout_s = 0.05;  // partial telegram dropped after this gap (LMS: 14 ms)
    double request_byte_gap_s = 0.0;     // gap between request bytes (sicktoolbox: 55 us)
    bool autodetect = true;              // probe 19200/38400/500000 with 0x32 if 9600 is silent
    StampMode stamps = StampMode::kScanClock;
    double sync_window_s = 2.0;  // scan clock: lower envelope over this many seconds of scans
    /// Checks beyond the CRC (issue #13 item 3): the byte after a telegram must start the next
    /// one (or be ACK/NAK) or the line must go idle for `idle_confirm_s`; every measured-value
    /// telegram must match the variant, mode and configuration (CheckMeasuredValues).
    bool strict_checks = true;
    double idle_confirm_s = 0.02;  // > a USB adaptor's 16 ms latency timer
    /// Accept field/dazzle/reflectivity flag bits in values (a unit with field evaluation
    /// configured); otherwise a value with them set is a damaged telegram.
    bool value_flags = false;
    /// Throws InputError naming the field (bad baud, empty device, non-positive timeouts).
    void Validate() const;
};

struct DriverCounters {
    std::uint64_t bytes = 0;           // bytes read from the line
    std::uint64_t telegrams = 0;       // good telegrams
    std::uint64_t scans = 0;           // scans delivered
    std::uint64_t crc_errors = 0;      // candidates rejected for their CRC
    std::uint64_t bad_headers = 0;     // candidates rejected for address or LEN
    std::uint64_t dropped_bytes = 0;   // bytes in no good telegram (garbage, damaged frames)
    std::uint64_t resyncs = 0;         // episodes of lost synchronisation
    std::uint64_t malformed = 0;       // good CRC but contents against the protocol (logged)
    std::uint64_t bad_followers = 0;   // good CRC but the next byte starts no telegram
    std::uint64_t realtime_scans = 0;  // scans stamped from their real-time index
    std::uint64_t naks = 0;            // 0x15 received
    std::uint64_t retries = 0;         // requests sent again
    std::uint64_t reconnects = 0;
    std::uint64_t sync_outliers = 0;  // scans the scan clock kept out of its envelope
};

/// What the scanner reported during initialisation.
struct DeviceInfo {
    std::string type;
    DeviceStatus status;
    ConfigBlock config;
    Variant variant;
    core::Lms200Format format;
    int baud = 0;
    OutputMode output;  // the streaming mode in force
};

class Lms200Driver {
public:
    /// Validates the config (InputError); does not touch the device.
    explicit Lms200Driver(DriverConfig config);
    ~Lms200Driver();
    Lms200Driver(const Lms200Driver&) = delete;
    Lms200Driver& operator=(const Lms200Driver&) = delete;

    /// Opens the device and initialises the scanner up to continuous output. Throws InputError
    /// for a missing device, a non-terminal or an unsupported configuration, SerialError if no
    /// LMS 200 answers.
    void Connect();
    /// The next scan, or nullopt if none arrived within `timeout_s`. Beam 0 is stamped on the
    /// system clock (s since the epoch): the telegram's arrival minus its transmission time at
    /// the line rate minus the sweep duration (scan_codec.hpp), then, with
    /// StampMode::kScanClock and a line that carries every sweep, put on the sweep grid by
    /// ScanClock (scan_clock.hpp). Reconnects by itself.
    [[nodiscard]] std::optional<core::Scan> NextScan(double timeout_s);
    /// Stops the output and returns the scanner to 9600 baud (best effort), closes the port.
    void Close();

    // Changes while connected. Each stops the output (0x20 0x25), makes the change, and starts
    // the output mode again; the scan clock restarts. Throw InputError when the scanner refuses
    // (naming what and why), SerialError when it does not answer.

    /// 0x3B: angle 100 or 180 deg, resolution 1, 0.5 or 0.25 deg (0.25 only with 100 deg).
    /// The output mode must fit the new variant (sub-range bounds).
    void SetVariant(const Variant& variant);
    /// 0x20 0x24/0x26/0x27/0x28/0x2A with its parameters (validated against the variant).
    void SetOutputMode(const OutputMode& mode);
    /// 0x74: the configuration block (also refreshes info().config and format).
    [[nodiscard]] ConfigBlock ReadConfig();
    /// 0x20 0x00 + password, then 0x77 (the scanner takes seconds to write its EEPROM), then
    /// 0x74 to confirm. Refused (F7 00 or a wrong password): InputError.
    void WriteConfig(const ConfigBlock& config);
    /// Reads, changes the set fields and writes the configuration if anything differs.
    void ApplyConfigChanges(const ConfigChanges& changes);
    /// 0x31 status (also refreshes info().status).
    [[nodiscard]] DeviceStatus ReadStatus();
    /// 0x10 software reset: 0x91, then the 0x90 power-on telegram at the power-on rate;
    /// then the whole initialisation again (the scanner is back at 9600 in request mode).
    /// Returns the power-on telegram's text.
    std::string Reset();

    [[nodiscard]] DriverCounters counters() const;
    [[nodiscard]] const DeviceInfo& info() const { return info_; }
    [[nodiscard]] bool connected() const { return port_ != nullptr; }
    /// True when scans are put on the sweep grid (StampMode::kScanClock and the line at
    /// info().baud carries a full scan telegram within one scan period).
    [[nodiscard]] bool synchronised() const { return sync_; }

private:
    using Clock = std::chrono::steady_clock;
    void Initialise();
    /// 0x20 0x25 if streaming; returns whether it was streaming.
    bool StopOutput();
    void StartOutput();
    void RestartClock();
    [[nodiscard]] FrameExpectation Expectation() const;
    /// Stamps and queues one measured-value telegram's scan.
    void OnValues(const MeasuredValues& v, double arrival_s, std::size_t frame_bytes);
    [[nodiscard]] bool MaybeAwaited(std::uint8_t command) const;
    /// Grid index from an 8-bit real-time index, nearest to what `latest_s` implies.
    [[nodiscard]] std::int64_t UnwrapIndex(std::uint8_t index, double latest_s) const;
    void RequireConnected(const char* what) const;
    bool FindScanner();
    /// Sends `request` and waits for the reply with command `reply_cmd`. nullopt after all tries.
    /// `reply_cmd` 0: the request code + 0x80.
    std::optional<Telegram> Transact(const Telegram& request,
                                     double timeout_s,
                                     int tries,
                                     std::uint8_t reply_cmd = 0);
    Telegram Require(const Telegram& request,
                     double timeout_s,
                     const char* what,
                     std::uint8_t reply_cmd = 0);
    /// Reads and parses what arrives within `timeout_s`; returns the number of bytes read.
    std::size_t ReadSome(double timeout_s);
    /// Hands the telegrams of one read (arrived_) to OnTelegram, in order, after bounding each
    /// measured-value telegram's arrival by the next one's (see ReadSome).
    void DeliverArrived();
    void OnTelegram(const Telegram& t, double arrival_s);
    bool TryReconnect(Clock::time_point deadline);

    DriverConfig config_;
    std::unique_ptr<SerialPort> port_;
    TelegramParser parser_;
    DeviceInfo info_;
    DriverCounters own_;
    bool streaming_ = false;
    std::deque<core::Scan> ready_;
    std::optional<Telegram> awaited_;  // reply captured during Transact
    std::uint8_t awaited_cmd_ = 0;
    bool saw_ack_ = false;
    bool saw_nak_ = false;
    bool saw_bad_crc_ = false;
    Clock::time_point last_scan_;
    std::vector<std::uint8_t> buffer_;
    ScanClock clock_;
    bool sync_ = false;
    /// The first scans after a (re)connection wait here until the scan clock has seen
    /// ScanClockConfig::warmup_scans of them, then all get that envelope's phase.
    struct HeldScan {
        core::Scan scan;
        std::int64_t k = 0;     // grid index
        double shift_s = 0.0;   // scan.stamp_s - grid stamp (sub-range / partial beam 0)
        double latest_s = 0.0;  // what the scan clock was given
    };
    std::vector<HeldScan> held_;
    /// Stamps the held scans with the envelope's phase (see OnValues).
    void ReleaseHeld(bool indexed);
    std::uint64_t sync_outliers_ = 0;  // of the clocks before the last reconnect
    double pending_arrival_s_ = 0.0;   // completion of the telegram waiting for its follower
    bool has_pending_arrival_ = false;
    std::int64_t last_turn_ = 0;  // unwrapped real-time index of the last scan
    bool have_turn_ = false;
    Clock::time_point last_byte_;
    bool starting_output_ = false;  // telegrams right after the mode's A0 are the stream's
    std::vector<std::pair<Telegram, double>> early_;
    std::vector<std::pair<Telegram, double>> arrived_;  // telegrams of the current read
};

}  // namespace casmap::drivers
