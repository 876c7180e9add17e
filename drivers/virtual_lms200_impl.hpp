#pragma once

// Private to the virtual LMS 200 (virtual_lms200.cpp, virtual_lms200_requests.cpp): the state
// of the emulated scanner, its line and its mirror.

#include <atomic>
#include <chrono>
#include <cstdint>
#include <deque>
#include <functional>
#include <mutex>
#include <optional>
#include <random>
#include <string>
#include <vector>

#include "casmap/drivers/output_mode.hpp"
#include "casmap/drivers/pseudo_terminal.hpp"
#include "casmap/drivers/telegram_parser.hpp"
#include "casmap/drivers/virtual_lms200.hpp"

namespace casmap::drivers {
namespace vlms {

using Clock = std::chrono::steady_clock;

inline double Seconds(Clock::duration d) { return std::chrono::duration<double>(d).count(); }
inline Clock::duration Duration(double s) {
    return std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(s));
}

/// One item on the emulated line: a raw byte (ACK/NAK), garbage, or a telegram.
struct Chunk {
    std::vector<std::uint8_t> bytes;
    std::size_t pos = 0;
    int baud_after = 0;           // a baud switch takes effect once this chunk is sent
    bool power_on_after = false;  // software reset
    std::optional<std::uint64_t> scan_index;
    bool intact = true;
    double beam0_wall_s = 0.0;
    int partial = -1;
    std::uint8_t command = 0xB0;
    Clock::time_point hold_until{};  // not sent before (EEPROM write, reset)
};

inline constexpr double kRequestGapTimeoutS = 0.1;  // a request's bytes come within 6 ms (TL 4.3)
inline constexpr double kMaxWaitS = 0.05;
inline constexpr double kMinWaitS = 0.001;  // pacing granularity: bytes go out in ~1 ms bursts

}  // namespace vlms

struct VirtualLms200::Impl {
    using Clock = vlms::Clock;
    using Chunk = vlms::Chunk;

    Impl(VirtualLms200Config c, ScanSource& s)
        : cfg(std::move(c)), source(s), rng(cfg.faults.seed) {}

    VirtualLms200Config cfg;
    ScanSource& source;
    PseudoTerminal pty;
    TelegramParser parser{Sender::kHost};
    std::mt19937_64 rng;
    mutable std::mutex mutex;
    VirtualLms200Stats stats;
    std::string slave_path;
    std::function<void(const SentScan&)> observer;

    // Emulated device.
    int baud = 9600;
    std::uint8_t op_mode = mode::kRequest;
    OutputMode stream_mode;  // parameters of the streaming mode in force
    bool installation = false;
    Clock::time_point busy_until{};  // requests are not heard before (reset)
    Variant variant;
    ConfigBlock config;
    core::Lms200Format format;

    // Line and mirror.
    std::deque<Chunk> tx;
    Clock::time_point next_byte;
    Clock::time_point epoch;    // mirror turn 0
    double epoch_wall_s = 0.0;  // the same instant on the system clock
    std::optional<std::int64_t> origin_turn;
    std::optional<std::int64_t> last_sent_unit;  // telegram unit last queued (UnitTurns)
    Clock::time_point last_rx;
    Clock::time_point next_disconnect;
    MeasuredValues values;

    void PowerOn();
    void SendPowerOn(Clock::time_point at);
    [[nodiscard]] bool Streaming() const;
    /// Mirror turns per telegram of `m`: the scan's turns; n x that for mean values; 1 for
    /// partial scans.
    [[nodiscard]] int UnitTurns(const OutputMode& m) const;
    /// The values of telegram `unit` of mode `m` into `values` (false: source exhausted).
    bool BuildValues(const OutputMode& m, std::int64_t unit, Chunk& c);
    void ApplyCollision(Chunk& c);
    void Open();
    bool Roll(double p);
    void EnqueueRaw(std::uint8_t byte);
    /// Queues a telegram (with faults). `start`: when the line starts sending it, if the
    /// line is idle (default: now).
    void EnqueueFrame(Chunk c, std::optional<Clock::time_point> start = std::nullopt);
    void Reply(const Telegram& t, int baud_after = 0, bool power_on_after = false);
    [[nodiscard]] std::int64_t TurnsDone(Clock::time_point now) const;
    [[nodiscard]] std::string TypeString() const;
    [[nodiscard]] DeviceStatus Status() const;
    void OnMode(const Telegram& t);
    void OnRequest(const Telegram& t);
    void OnWriteConfig(const ConfigBlock& block);
    /// Queues the B0 telegram a real-time scanner sends next: 0x24 the newest sweep complete
    /// when the line became free, 0x2A one partial scan per turn, 0x30 the newest sweep.
    /// False if there is none yet (or the source is exhausted).
    bool QueueNewestScan(bool on_request);
    /// Queues the next B0 telegram if the line is free; true if one was queued.
    bool Produce();
    void OnParserEvent(ParserEvent e, const Telegram& t);
    void Receive(Clock::time_point now);
    void Finish(Chunk& c);
    void Transmit(Clock::time_point now);
    void Disconnect(const std::atomic<bool>& stop);
    [[nodiscard]] double WaitS(Clock::time_point now) const;
    void Loop(const std::atomic<bool>& stop, bool stop_when_exhausted);
};

}  // namespace casmap::drivers
