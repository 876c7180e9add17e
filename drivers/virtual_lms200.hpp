#pragma once

// A virtual LMS 200 on a pseudo-terminal: speaks the telegram protocol of
// shared/reference/lms200_protocol.md (checklist of section 6.5, pty caveats of section 7),
// paces its output at the emulated baud rate and streams scans from a ScanSource.

#include <atomic>
#include <cstdint>
#include <functional>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <string_view>
#include <thread>

#include "casmap/core/lms200.hpp"
#include "casmap/core/scan.hpp"
#include "casmap/drivers/telegram.hpp"

namespace casmap::drivers {

/// Where the virtual scanner's scans come from (the simulator live, or a run file).
class ScanSource {
public:
    virtual ~ScanSource() = default;
    /// The complete scan of mirror sweep `index` (0 = the first scan served after streaming
    /// started; sweeps follow each other at the variant's scan period). nullopt when the source
    /// is exhausted. Called from the scanner's thread.
    virtual std::optional<core::Scan> Sweep(std::uint64_t index, const Variant& variant) = 0;
    /// Whether Sweep() can deliver scans of `variant` (decides the 0x3B reply).
    [[nodiscard]] virtual bool Supports(const Variant& variant) const = 0;
};

/// Faults injected into the scanner's telegrams (never into the raw ACK/NAK bytes).
/// Rates are probabilities per telegram.
struct FaultConfig {
    double crc_rate = 0.0;      // one bit flipped after the header (bad CRC)
    double garbage_rate = 0.0;  // 1..32 random bytes sent before the telegram
    double drop_rate = 0.0;     // one byte of the telegram never sent
    /// A measured-value telegram loses the one byte whose loss keeps the CRC valid when the
    /// next telegram's STX completes it (a CRC collision, issue #13 item 3); telegrams with
    /// no such byte (about 99 %) go out intact.
    double collide_rate = 0.0;
    double disconnect_period_s = 0.0;  // 0 = never; else the device vanishes every S seconds
    double offline_s = 0.3;            // how long it stays away (then powers on at 9600)
    std::uint64_t seed = 1;
    /// Throws InputError naming the field when a rate is outside [0, 1] or a period negative.
    void Validate() const;
};
/// Reads an EEPROM file written by the virtual scanner. Throws InputError naming the file,
/// the field and the rule.
[[nodiscard]] ConfigBlock ReadEepromFile(const std::string& path);
/// Writes it (temporary file + rename). Throws InputError if the file cannot be written.
void WriteEepromFile(const std::string& path, const ConfigBlock& config);

/// Parses "crc=P,garbage=P,drop=P,collide=P,disconnect=S" (any subset, any order). Throws
/// InputError.
[[nodiscard]] FaultConfig ParseFaults(std::string_view spec);

struct VirtualLms200Config {
    std::string link_path;     // stable symlink to the current slave device ("" = none)
    int power_on_baud = 9600;  // as the real unit unless a permanent rate was stored
    Variant variant;           // 180 deg, 1 deg
    ConfigBlock config = ConfigBlock::Default();  // 34 bytes (V02.x); 32 for the old profile
    /// The EEPROM: when set, the configuration is read from this file at start (if it exists;
    /// it then replaces `config`) and written to it (atomically) by every accepted 0x77.
    std::string eeprom_path;
    double config_write_s = 3.0;  // 0x77: the EEPROM write before the F7 reply (TL: seconds)
    double reset_s = 1.0;         // 0x10: from the 0x91 reply to the 0x90 power-on telegram
    /// Ignore requests (and garble output) while the host's terminal speed, read from the
    /// master side, differs from the emulated rate: "wrong baud => no answer".
    bool check_host_baud = true;
    FaultConfig faults;
    void Validate() const;  // throws InputError
};

struct VirtualLms200Stats {
    std::uint64_t requests = 0;        // valid request telegrams
    std::uint64_t naks_sent = 0;       // raw 0x15 for bad request checksums
    std::uint64_t telegrams_sent = 0;  // reply + B0 telegrams queued
    std::uint64_t scans_sent = 0;      // B0 telegrams fully written
    std::uint64_t scans_skipped = 0;   // completed sweeps that did not fit on the line
    std::uint64_t bytes_sent = 0;
    std::uint64_t bytes_lost = 0;  // written while nobody read and the pty buffer was full
    std::uint64_t wrong_baud_bytes = 0;
    std::uint64_t crc_faults = 0;
    std::uint64_t drop_faults = 0;
    std::uint64_t garbage_faults = 0;
    std::uint64_t garbage_bytes = 0;
    std::uint64_t collision_faults = 0;  // telegrams sent with a CRC-preserving byte drop
    std::uint64_t config_writes = 0;     // accepted 0x77 (EEPROM writes)
    std::uint64_t disconnects = 0;
    bool source_exhausted = false;
    int baud = 9600;
    std::uint8_t operating_mode = mode::kRequest;
};

/// Reported once per measured-value telegram when its last byte was written (or it was cut
/// off).
struct SentScan {
    std::uint64_t index = 0;  // ScanSource sweep index (the last one for mean values)
    bool intact = false;      // every byte written unchanged
    /// When beam 0 of this sweep was measured by the emulated mirror (system clock, s since
    /// the epoch): the driver's latency-corrected stamp estimates this.
    double beam0_wall_s = 0.0;
    int partial = -1;             // partial scan number in mode 0x2A, else -1
    std::uint8_t command = 0xB0;  // B0, B6, B7 or BF
    /// Disconnects before it was sent: a telegram the client had not read when the device
    /// next vanished is lost with it (however many the pty buffered).
    std::uint64_t connection = 0;
};

class VirtualLms200 {
public:
    /// `source` must outlive the scanner. Validates the config (InputError).
    VirtualLms200(VirtualLms200Config config, ScanSource& source);
    ~VirtualLms200();
    VirtualLms200(const VirtualLms200&) = delete;
    VirtualLms200& operator=(const VirtualLms200&) = delete;

    /// Creates the pseudo-terminal (and link) and serves it on a background thread.
    /// Throws std::system_error / InputError if the pty or link cannot be made.
    void Start();
    /// Stops the thread, closes the pty and removes the link.
    void Stop();
    /// Creates the pseudo-terminal (and link) without serving it yet (SlavePath() is then
    /// known). Throws like Start().
    void Open();
    /// Serves on the calling thread (opening the pty first if needed) until `stop` becomes
    /// true, or, with `stop_when_exhausted`, the source is exhausted and the client has read
    /// the last telegram (waiting at most 1 s for that).
    void Run(const std::atomic<bool>& stop, bool stop_when_exhausted = false);

    /// Current slave device path (changes after each disconnect).
    [[nodiscard]] std::string SlavePath() const;
    [[nodiscard]] VirtualLms200Stats stats() const;
    /// Called from the scanner's thread for each B0 telegram.
    void SetScanObserver(std::function<void(const SentScan&)> observer);

private:
    struct Impl;
    std::unique_ptr<Impl> impl_;
    std::atomic<bool> stop_{false};
    std::thread thread_;
};

}  // namespace casmap::drivers
