#pragma once

// LMS 200 serial driver: power-on at 9600 baud, switch to the requested rate, read type, status
// and configuration, set the variant, start continuous 0x24 output, deliver core::Scans, and
// reconnect by itself when the line goes quiet or the device disappears.

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

struct DriverConfig {
    std::string device;                  // e.g. /dev/ttyUSB0 or the virtual scanner's link
    int baud = 38400;                    // rate the driver switches to (9600/19200/38400/500000)
    std::optional<Variant> variant;      // set with 0x3B when given; else the device's current
    int tries = 3;                       // per request (sicktoolbox: 3)
    double reply_timeout_s = 1.0;        // after the ACK, per try (sicktoolbox: 1 s)
    double mode_timeout_s = 3.0;         // after the ACK for 0x20, per try (TL: up to 3 s)
    double baud_settle_s = 0.05;         // pause after changing the host rate
    double quiet_timeout_s = 1.0;        // no scan for this long while streaming -> reconnect
    double inter_byte_timeout_s = 0.05;  // partial telegram dropped after this gap (LMS: 14 ms)
    double request_byte_gap_s = 0.0;     // gap between request bytes (sicktoolbox: 55 us)
    bool autodetect = true;              // probe 19200/38400/500000 with 0x32 if 9600 is silent
    StampMode stamps = StampMode::kScanClock;
    double sync_window_s = 2.0;  // scan clock: lower envelope over this many seconds of scans
    /// Throws InputError naming the field (bad baud, empty device, non-positive timeouts).
    void Validate() const;
};

struct DriverCounters {
    std::uint64_t bytes = 0;          // bytes read from the line
    std::uint64_t telegrams = 0;      // good telegrams
    std::uint64_t scans = 0;          // scans delivered
    std::uint64_t crc_errors = 0;     // candidates rejected for their CRC
    std::uint64_t bad_headers = 0;    // candidates rejected for address or LEN
    std::uint64_t dropped_bytes = 0;  // bytes in no good telegram (garbage, damaged frames)
    std::uint64_t resyncs = 0;        // episodes of lost synchronisation
    std::uint64_t malformed = 0;      // good CRC but contents against the protocol (logged)
    std::uint64_t naks = 0;           // 0x15 received
    std::uint64_t retries = 0;        // requests sent again
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

    [[nodiscard]] DriverCounters counters() const;
    [[nodiscard]] const DeviceInfo& info() const { return info_; }
    [[nodiscard]] bool connected() const { return port_ != nullptr; }
    /// True when scans are put on the sweep grid (StampMode::kScanClock and the line at
    /// info().baud carries a full scan telegram within one scan period).
    [[nodiscard]] bool synchronised() const { return sync_; }

private:
    using Clock = std::chrono::steady_clock;
    void Initialise();
    bool FindScanner();
    /// Sends `request` and waits for the reply with command `reply_cmd`. nullopt after all tries.
    std::optional<Telegram> Transact(const Telegram& request, double timeout_s, int tries);
    Telegram Require(const Telegram& request, double timeout_s, const char* what);
    /// Reads and parses what arrives within `timeout_s`; returns the number of bytes read.
    std::size_t ReadSome(double timeout_s);
    void OnTelegram(const Telegram& t, double arrival_s);
    bool TryReconnect(Clock::time_point deadline);

    DriverConfig config_;
    std::unique_ptr<SerialPort> port_;
    TelegramParser parser_{Sender::kScanner};
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
    std::vector<std::pair<core::Scan, std::int64_t>> held_;
    std::uint64_t sync_outliers_ = 0;  // of the clocks before the last reconnect
};

}  // namespace casmap::drivers
