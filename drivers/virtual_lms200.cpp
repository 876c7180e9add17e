#include "casmap/drivers/virtual_lms200.hpp"

#include <poll.h>
#ifdef __linux__
#include <sys/prctl.h>
#endif
#include <sys/ioctl.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <cmath>
#include <thread>

#include "casmap/core/input_error.hpp"
#include "casmap/drivers/scan_codec.hpp"
#include "casmap/drivers/virtual_lms200_impl.hpp"

// The line, the pacing, faults, disconnects and the serving loop of the virtual LMS 200; the
// request handling is in virtual_lms200_requests.cpp.

namespace casmap::drivers {
namespace {
using vlms::Chunk;
using vlms::Clock;
using vlms::Duration;
using vlms::kMaxWaitS;
using vlms::kMinWaitS;
using vlms::kRequestGapTimeoutS;
using vlms::Seconds;
}  // namespace

void VirtualLms200::Impl::PowerOn() {
    baud = cfg.power_on_baud;
    op_mode = mode::kRequest;
    stream_mode = OutputMode::Continuous();
    installation = false;
}

void VirtualLms200::Impl::SendPowerOn(Clock::time_point at) {
    Chunk c;
    c.bytes = EncodeTelegram(MakePowerOnTelegram(TypeString()));
    c.hold_until = at;
    EnqueueFrame(std::move(c));
}

bool VirtualLms200::Impl::Streaming() const {
    return op_mode == mode::kStreamAll || op_mode == mode::kStreamPartial ||
           op_mode == mode::kStreamMean || op_mode == mode::kStreamSubRange ||
           op_mode == mode::kStreamMeanSubRange;
}

void VirtualLms200::Impl::Open() {
    variant = cfg.variant;
    config = cfg.config;
    if (!cfg.eeprom_path.empty() && access(cfg.eeprom_path.c_str(), F_OK) == 0) {
        config = ReadEepromFile(cfg.eeprom_path);  // what the last 0x77 stored
    }
    format = FormatOf(config);
    PowerOn();
    // No 0x90 here: the unit was powered before any host opened the line (a pty opened by a
    // client flushes whatever came before anyway). Resets and power cycles send it.
    pty.Open(cfg.link_path, baud);
    const Clock::time_point now = Clock::now();
    epoch = now;
    epoch_wall_s =
        std::chrono::duration<double>(std::chrono::system_clock::now().time_since_epoch()).count();
    next_byte = now;
    last_rx = now;
    next_disconnect = now + Duration(cfg.faults.disconnect_period_s);
    std::lock_guard lock(mutex);
    slave_path = pty.slave_path();
}

bool VirtualLms200::Impl::Roll(double p) {
    return p > 0.0 && std::uniform_real_distribution<double>(0.0, 1.0)(rng) < p;
}

void VirtualLms200::Impl::EnqueueRaw(std::uint8_t byte) {
    if (tx.empty()) {
        next_byte = std::max(next_byte, Clock::now());
    }
    Chunk c;
    c.bytes = {byte};
    tx.push_back(std::move(c));
}

/// Queues a telegram (with faults). `start`: when the line starts sending it, if the
/// line is idle (default: now).
void VirtualLms200::Impl::EnqueueFrame(Chunk c, std::optional<Clock::time_point> start) {
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
    if (c.scan_index && c.intact && Roll(f.collide_rate)) {
        ApplyCollision(c);
    }
    ++stats.telegrams_sent;
    tx.push_back(std::move(c));
}

void VirtualLms200::Impl::Reply(const Telegram& t, int baud_after, bool power_on_after) {
    Chunk c;
    c.bytes = EncodeTelegram(t);
    c.baud_after = baud_after;
    c.power_on_after = power_on_after;
    EnqueueFrame(std::move(c));
}

std::int64_t VirtualLms200::Impl::TurnsDone(Clock::time_point now) const {
    return static_cast<std::int64_t>(
        std::floor(Seconds(now - epoch) / core::Lms200Timing::kTurnPeriodS));
}

/// Queues the next B0 telegram if the line is free; true if one was queued.
void VirtualLms200::Impl::ApplyCollision(Chunk& c) {
    // Dropping byte i shifts the rest left; the receiver then takes the next telegram's STX
    // as the last CRC byte. Look for the i (after the header) where the CRC still matches.
    std::vector<std::uint8_t>& b = c.bytes;
    const std::size_t n = b.size();
    std::vector<std::uint8_t> cand(n);
    for (std::size_t i = 5; i + 1 < n; ++i) {
        std::copy(b.begin(), b.begin() + static_cast<std::ptrdiff_t>(i), cand.begin());
        std::copy(b.begin() + static_cast<std::ptrdiff_t>(i + 1), b.end(),
                  cand.begin() + static_cast<std::ptrdiff_t>(i));
        cand[n - 1] = kStx;
        const std::uint16_t crc = static_cast<std::uint16_t>(cand[n - 2] | (cand[n - 1] << 8U));
        if (Crc16(std::span(cand).first(n - 2)) == crc) {
            b.erase(b.begin() + static_cast<std::ptrdiff_t>(i));
            c.intact = false;
            ++stats.collision_faults;
            return;
        }
    }
}

bool VirtualLms200::Impl::Produce() {
    if (!Streaming() || !tx.empty() || parser.InFrame() || stats.source_exhausted) {
        return false;  // a request arriving pauses the stream; one frame at a time
    }
    return QueueNewestScan(false);
}

void VirtualLms200::Impl::OnParserEvent(ParserEvent e, const Telegram& t) {
    if (e == ParserEvent::kTelegram) {
        OnRequest(t);
    } else if (e == ParserEvent::kBadCrc) {
        ++stats.naks_sent;
        EnqueueRaw(kNak);
    }
}

void VirtualLms200::Impl::Receive(Clock::time_point now) {
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
        if (now < busy_until) {  // resetting: nothing is heard
            parser.Reset();
            continue;
        }
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

void VirtualLms200::Impl::Finish(Chunk& c) {
    if (c.scan_index) {
        if (c.intact) {
            ++stats.scans_sent;
        }
        if (observer) {
            observer(SentScan{*c.scan_index, c.intact, c.beam0_wall_s, c.partial, c.command,
                              stats.disconnects});
        }
    }
    if (c.baud_after != 0) {
        baud = c.baud_after;
    }
    if (c.power_on_after) {
        PowerOn();
    }
}

void VirtualLms200::Impl::Transmit(Clock::time_point now) {
    const double byte_s = ByteTimeS(baud);
    while (!tx.empty()) {
        Chunk& c = tx.front();
        if (c.pos == 0 && c.hold_until > next_byte) {
            next_byte = c.hold_until;  // e.g. the EEPROM write before the F7 reply
        }
        if (next_byte > now) {
            break;
        }
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

void VirtualLms200::Impl::Disconnect(const std::atomic<bool>& stop) {
    for (Chunk& c : tx) {
        if (c.scan_index && observer) {
            observer(SentScan{*c.scan_index, false, c.beam0_wall_s, c.partial, c.command,
                              stats.disconnects});
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
    SendPowerOn(Clock::now());
    slave_path = pty.slave_path();
    const Clock::time_point now = Clock::now();
    next_byte = now;
    last_rx = now;
    next_disconnect = now + Duration(cfg.faults.disconnect_period_s);
}

double VirtualLms200::Impl::WaitS(Clock::time_point now) const {
    double wait = kMaxWaitS;
    if (!tx.empty()) {
        const Clock::time_point start = std::max(next_byte, tx.front().hold_until);
        wait = std::max(kMinWaitS, Seconds(start - now));
        // The telegram's last byte goes out on time, not at the next ~1 ms burst: the host's
        // arrival time (and so its scan clock, scan_clock.hpp) sees the real line timing.
        const Chunk& c = tx.front();
        const double last_byte_s =
            Seconds(start - now) +
            static_cast<double>(c.bytes.size() - c.pos - 1) * ByteTimeS(baud);
        if (last_byte_s > 0.0) {
            wait = std::min(wait, last_byte_s);
        }
    } else if (Streaming()) {
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

void VirtualLms200::Impl::Loop(const std::atomic<bool>& stop, bool stop_when_exhausted) {
#ifdef __linux__
    // Wake on time: the default 50 us timer slack would make every telegram end late by up
    // to that (a real scanner's UART has no slack). Affects this thread only.
    prctl(PR_SET_TIMERSLACK, 1UL, 0UL, 0UL, 0UL);
#endif
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
