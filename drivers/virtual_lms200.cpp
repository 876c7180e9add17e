#include "drivers/virtual_lms200.hpp"

#include <poll.h>
#include <sys/ioctl.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <cmath>
#include <deque>
#include <random>

#include "core/input_error.hpp"
#include "drivers/pseudo_terminal.hpp"
#include "drivers/scan_codec.hpp"
#include "drivers/telegram_parser.hpp"

namespace casmap::drivers {
namespace {

using Clock = std::chrono::steady_clock;

double Seconds(Clock::duration d) { return std::chrono::duration<double>(d).count(); }
Clock::duration Duration(double s) {
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
};

constexpr double kRequestGapTimeoutS = 0.1;  // a request's bytes come within 6 ms (TL 4.3)
constexpr double kMaxWaitS = 0.05;
constexpr double kMinWaitS = 0.001;  // pacing granularity: bytes go out in ~1 ms bursts

}  // namespace

struct VirtualLms200::Impl {
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
    bool installation = false;
    Variant variant;
    ConfigBlock config;
    core::Lms200Format format;

    // Line and mirror.
    std::deque<Chunk> tx;
    Clock::time_point next_byte;
    Clock::time_point epoch;    // mirror turn 0
    double epoch_wall_s = 0.0;  // the same instant on the system clock
    std::optional<std::int64_t> origin_turn;
    std::optional<std::int64_t> last_sent_unit;  // scan (0x24) or turn (0x2A) last queued
    Clock::time_point last_rx;
    Clock::time_point next_disconnect;
    MeasuredValues values;

    void PowerOn() {
        baud = cfg.power_on_baud;
        op_mode = mode::kRequest;
        installation = false;
    }

    void Open() {
        variant = cfg.variant;
        config = cfg.config;
        format = FormatOf(config);
        PowerOn();
        pty.Open(cfg.link_path, baud);
        const Clock::time_point now = Clock::now();
        epoch = now;
        epoch_wall_s =
            std::chrono::duration<double>(std::chrono::system_clock::now().time_since_epoch())
                .count();
        next_byte = now;
        last_rx = now;
        next_disconnect = now + Duration(cfg.faults.disconnect_period_s);
        std::lock_guard lock(mutex);
        slave_path = pty.slave_path();
    }

    bool Roll(double p) {
        return p > 0.0 && std::uniform_real_distribution<double>(0.0, 1.0)(rng) < p;
    }

    void EnqueueRaw(std::uint8_t byte) {
        if (tx.empty()) {
            next_byte = std::max(next_byte, Clock::now());
        }
        Chunk c;
        c.bytes = {byte};
        tx.push_back(std::move(c));
    }

    /// Queues a telegram (with faults). `start`: when the line starts sending it, if the
    /// line is idle (default: now).
    void EnqueueFrame(Chunk c, std::optional<Clock::time_point> start = std::nullopt) {
        if (tx.empty()) {
            next_byte = start ? *start : std::max(next_byte, Clock::now());
        }
        const FaultConfig& f = cfg.faults;
        if (Roll(f.garbage_rate)) {
            Chunk g;
            g.bytes.resize(1 + rng() % 32);
            for (auto& b : g.bytes) {
                b = static_cast<std::uint8_t>(rng());
            }
            ++stats.garbage_faults;
            stats.garbage_bytes += g.bytes.size();
            tx.push_back(std::move(g));
        }
        if (Roll(f.crc_rate)) {  // one bit after the header: a pure checksum failure
            const std::size_t at = 5 + rng() % (c.bytes.size() - 5);
            c.bytes[at] ^= static_cast<std::uint8_t>(1U << (rng() % 8));
            c.intact = false;
            ++stats.crc_faults;
        }
        if (Roll(f.drop_rate)) {
            c.bytes.erase(c.bytes.begin() + static_cast<std::ptrdiff_t>(rng() % c.bytes.size()));
            c.intact = false;
            ++stats.drop_faults;
        }
        ++stats.telegrams_sent;
        tx.push_back(std::move(c));
    }

    void Reply(const Telegram& t, int baud_after = 0, bool power_on_after = false) {
        Chunk c;
        c.bytes = EncodeTelegram(t);
        c.baud_after = baud_after;
        c.power_on_after = power_on_after;
        EnqueueFrame(std::move(c));
    }

    [[nodiscard]] std::int64_t TurnsDone(Clock::time_point now) const {
        return static_cast<std::int64_t>(
            std::floor(Seconds(now - epoch) / core::Lms200Timing::kTurnPeriodS));
    }

    [[nodiscard]] std::string TypeString() const {
        // "x" is 1 in mm and 3 in cm units on the unit MJ tested (reference section 2).
        return std::string("LMS200;30106") +
               (format.units == core::RangeUnits::kMillimetre ? '1' : '3') + ";V02.10 ";
    }

    [[nodiscard]] DeviceStatus Status() const {
        DeviceStatus d;
        d.operating_mode = op_mode;
        d.measuring_mode = config.measuring_mode();
        d.variant = variant;
        d.baud_word = BaudWord(baud);
        d.units = config.units();
        return d;
    }

    void OnMode(const Telegram& t) {
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

    void OnRequest(const Telegram& t) {
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

    void OnWriteConfig(const ConfigBlock& block) {
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
    bool QueueNewestScan(bool on_request) {
        const std::int64_t turns = TurnsDone(Clock::now());
        if (!origin_turn) {
            origin_turn = turns;
        }
        const bool partial = op_mode == mode::kStreamPartial && !on_request;
        const int k = variant.Turns();
        const std::int64_t newest =
            partial ? turns - *origin_turn - 1 : (turns - *origin_turn) / k - 1;
        if (newest < 0 || (!on_request && last_sent_unit && newest <= *last_sent_unit)) {
            return false;
        }
        const auto completion = [&](std::int64_t u) {
            const std::int64_t end_turn = *origin_turn + (partial ? u + 1 : (u + 1) * k);
            return epoch +
                   Duration(static_cast<double>(end_turn) * core::Lms200Timing::kTurnPeriodS);
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
        const double sweep_s = partial ? static_cast<double>(variant.angle_deg) / 360.0 *
                                             core::Lms200Timing::kTurnPeriodS
                                       : SweepDurationS(variant);
        c.beam0_wall_s = epoch_wall_s +
                         static_cast<double>(end_turn) * core::Lms200Timing::kTurnPeriodS - sweep_s;
        EnqueueFrame(std::move(c), start);
        return true;
    }

    /// Queues the next B0 telegram if the line is free; true if one was queued.
    bool Produce() {
        const bool streaming = op_mode == mode::kStreamAll || op_mode == mode::kStreamPartial;
        if (!streaming || !tx.empty() || parser.InFrame() || stats.source_exhausted) {
            return false;  // a request arriving pauses the stream; one frame at a time
        }
        return QueueNewestScan(false);
    }

    void OnParserEvent(ParserEvent e, const Telegram& t) {
        if (e == ParserEvent::kTelegram) {
            OnRequest(t);
        } else if (e == ParserEvent::kBadCrc) {
            ++stats.naks_sent;
            EnqueueRaw(kNak);
        }
    }

    void Receive(Clock::time_point now) {
        std::uint8_t buf[512];
        const TelegramParser::Callback cb = [this](ParserEvent e, const Telegram& t) {
            OnParserEvent(e, t);
        };
        for (;;) {
            const ssize_t n = read(pty.master_fd(), buf, sizeof(buf));
            if (n <= 0) {
                break;
            }
            last_rx = now;
            if (cfg.check_host_baud && pty.ClientBaud() != baud) {
                stats.wrong_baud_bytes += static_cast<std::uint64_t>(n);
                parser.Reset();  // at the wrong rate the bytes are garbled beyond use
                continue;
            }
            parser.Feed(std::span(buf, static_cast<std::size_t>(n)), cb);
        }
        if (parser.InFrame() && Seconds(now - last_rx) > kRequestGapTimeoutS) {
            parser.Timeout(cb);
        }
    }

    void Finish(Chunk& c) {
        if (c.scan_index) {
            if (c.intact) {
                ++stats.scans_sent;
            }
            if (observer) {
                observer(SentScan{*c.scan_index, c.intact, c.beam0_wall_s});
            }
        }
        if (c.baud_after != 0) {
            baud = c.baud_after;
        }
        if (c.power_on_after) {
            PowerOn();
        }
    }

    void Transmit(Clock::time_point now) {
        const double byte_s = ByteTimeS(baud);
        while (!tx.empty() && next_byte <= now) {
            Chunk& c = tx.front();
            const auto due = static_cast<std::size_t>(Seconds(now - next_byte) / byte_s) + 1;
            const std::size_t n = std::min(due, c.bytes.size() - c.pos);
            std::span<std::uint8_t> out(c.bytes.data() + c.pos, n);
            if (cfg.check_host_baud && pty.ClientBaud() != baud) {
                for (auto& b : out) {  // heard at the wrong rate: noise
                    b = static_cast<std::uint8_t>(rng());
                }
                c.intact = false;
            }
            const ssize_t w = write(pty.master_fd(), out.data(), out.size());
            const std::size_t written = w > 0 ? static_cast<std::size_t>(w) : 0;
            if (written < n) {  // nobody reads and the pty buffer is full: lost on the line
                stats.bytes_lost += n - written;
                c.intact = false;
            }
            stats.bytes_sent += n;
            c.pos += n;
            next_byte += Duration(static_cast<double>(n) * byte_s);
            if (c.pos == c.bytes.size()) {
                Finish(c);
                tx.pop_front();
            }
        }
    }

    void Disconnect(const std::atomic<bool>& stop) {
        for (Chunk& c : tx) {
            if (c.scan_index && observer) {
                observer(SentScan{*c.scan_index, false, c.beam0_wall_s});
            }
        }
        tx.clear();
        parser.Reset();
        // Bytes already on the wire reach the client: wait (briefly) until it has read them.
        const Clock::time_point drain_until = Clock::now() + Duration(0.1);
        while (pty.Unread() > 0 && Clock::now() < drain_until) {
            std::this_thread::sleep_for(std::chrono::milliseconds(1));
        }
        pty.Close();
        ++stats.disconnects;
        const Clock::time_point back = Clock::now() + Duration(cfg.faults.offline_s);
        mutex.unlock();
        while (!stop && Clock::now() < back) {
            std::this_thread::sleep_for(std::chrono::milliseconds(5));
        }
        mutex.lock();
        PowerOn();
        pty.Open(cfg.link_path, baud);
        slave_path = pty.slave_path();
        const Clock::time_point now = Clock::now();
        next_byte = now;
        last_rx = now;
        next_disconnect = now + Duration(cfg.faults.disconnect_period_s);
    }

    [[nodiscard]] double WaitS(Clock::time_point now) const {
        double wait = kMaxWaitS;
        if (!tx.empty()) {
            wait = std::max(kMinWaitS, Seconds(next_byte - now));
        } else if (op_mode == mode::kStreamAll || op_mode == mode::kStreamPartial) {
            // Wake just after the next mirror turn ends: a completed sweep goes out at once.
            const double turn_s = core::Lms200Timing::kTurnPeriodS;
            const double next_turn_s = static_cast<double>(TurnsDone(now) + 1) * turn_s;
            wait = std::min(wait, next_turn_s - Seconds(now - epoch) + 1e-4);
        }
        if (cfg.faults.disconnect_period_s > 0.0) {
            wait = std::min(wait, std::max(0.0, Seconds(next_disconnect - now)));
        }
        return std::min(wait, kMaxWaitS);
    }

    void Loop(const std::atomic<bool>& stop, bool stop_when_exhausted) {
        std::unique_lock lock(mutex);
        while (!stop) {
            Clock::time_point now = Clock::now();
            if (cfg.faults.disconnect_period_s > 0.0 && now >= next_disconnect) {
                Disconnect(stop);
                continue;
            }
            Receive(now);
            // Behind schedule (the thread was delayed), several telegrams may be due at once:
            // send them all now rather than one per wake-up, so the delay does not last.
            for (int i = 0; i < 8 && Produce(); ++i) {
                Transmit(Clock::now());
                if (!tx.empty()) {
                    break;
                }
            }
            Transmit(Clock::now());
            stats.baud = baud;
            stats.operating_mode = op_mode;
            if (stop_when_exhausted && stats.source_exhausted && tx.empty()) {
                break;
            }
            const double wait = WaitS(Clock::now());
            lock.unlock();
            pollfd p{pty.master_fd(), POLLIN, 0};
            const auto ns = static_cast<long>(wait * 1e9);
            const timespec ts{ns / 1000000000L, ns % 1000000000L};
            ppoll(&p, 1, &ts, nullptr);
            lock.lock();
        }
    }
};

VirtualLms200::VirtualLms200(VirtualLms200Config config, ScanSource& source) {
    config.Validate();
    impl_ = std::make_unique<Impl>(std::move(config), source);
}

VirtualLms200::~VirtualLms200() { Stop(); }

void VirtualLms200::Start() {
    Stop();
    impl_->Open();
    stop_ = false;
    thread_ = std::thread([this] { impl_->Loop(stop_, false); });
}

void VirtualLms200::Stop() {
    stop_ = true;
    if (thread_.joinable()) {
        thread_.join();
    }
    std::lock_guard lock(impl_->mutex);
    impl_->pty.Close();
}

void VirtualLms200::Open() {
    if (!impl_->pty.IsOpen()) {
        impl_->Open();
    }
}

void VirtualLms200::Run(const std::atomic<bool>& stop, bool stop_when_exhausted) {
    Open();
    impl_->Loop(stop, stop_when_exhausted);
    std::lock_guard lock(impl_->mutex);
    const Clock::time_point until = Clock::now() + std::chrono::seconds(1);
    while (!stop && impl_->pty.Unread() > 0 && Clock::now() < until) {
        std::this_thread::sleep_for(std::chrono::milliseconds(5));
    }
    impl_->pty.Close();
}

std::string VirtualLms200::SlavePath() const {
    std::lock_guard lock(impl_->mutex);
    return impl_->slave_path;
}

VirtualLms200Stats VirtualLms200::stats() const {
    std::lock_guard lock(impl_->mutex);
    return impl_->stats;
}

void VirtualLms200::SetScanObserver(std::function<void(const SentScan&)> observer) {
    std::lock_guard lock(impl_->mutex);
    impl_->observer = std::move(observer);
}

}  // namespace casmap::drivers
