#pragma once

#include <cstddef>
#include <cstdint>
#include <functional>
#include <span>
#include <vector>

#include "casmap/drivers/telegram.hpp"

namespace casmap::drivers {

/// Which side's telegrams a parser reads.
enum class Sender : std::uint8_t {
    kScanner,  // replies: STX 0x80|address, ACK/NAK bytes between telegrams
    kHost,     // requests: STX address < 0x80
};

enum class ParserEvent : std::uint8_t {
    kTelegram,  // a complete telegram with a good CRC
    kAckByte,   // a lone 0x06 between telegrams (scanner side only)
    kNakByte,   // a lone 0x15 between telegrams (scanner side only)
    kBadCrc,    // a candidate frame whose CRC failed (already counted and rejected)
    /// A telegram with a good CRC rejected because the byte after it starts no telegram, ACK
    /// or NAK (follower check on): a damaged frame whose CRC matched by chance.
    kBadFollower,
};

/// What a parser saw. Every byte is counted once in `bytes` and ends up either in an accepted
/// telegram, an ACK/NAK, or `dropped_bytes`.
struct ParserCounters {
    std::uint64_t bytes = 0;
    std::uint64_t telegrams = 0;
    std::uint64_t acks = 0;
    std::uint64_t naks = 0;
    std::uint64_t dropped_bytes = 0;
    std::uint64_t crc_errors = 0;     // candidates with a plausible header and a bad CRC
    std::uint64_t bad_headers = 0;    // candidates abandoned for address or LEN
    std::uint64_t timeouts = 0;       // candidates abandoned because the line went quiet
    std::uint64_t bad_followers = 0;  // good-CRC candidates rejected by the follower check
    /// Episodes of lost synchronisation: a stray byte or an abandoned candidate starts one,
    /// the next good telegram ends it.
    std::uint64_t resyncs = 0;
};

/// Streaming telegram parser. Looks for STX + address, checks LEN (1..kMaxLen) and the CRC.
/// When a candidate fails, only its first byte is dropped and the rest is parsed again, so a
/// good telegram hidden behind garbage or a damaged telegram is never lost.
/// Allocation-free after the first frames (buffers keep their capacity).
class TelegramParser {
public:
    using Callback = std::function<void(ParserEvent event, const Telegram& telegram)>;

    /// `address`: the scanner address whose replies are accepted (0x80 | address on the wire);
    /// for kHost, requests to 0x00 (broadcast) and to `address` are accepted.
    /// `check_follower` (scanner side): a telegram with a good CRC is only delivered once the
    /// next byte starts a telegram (STX) or is an ACK/NAK, or the line goes idle (Idle() or
    /// Timeout()); any other next byte rejects it (kBadFollower) and its bytes after the STX
    /// are parsed again. A frame that lost a byte takes the next telegram's STX as its last
    /// CRC byte; when the CRC matches by chance, the byte after it (the next address) gives
    /// it away (issue #13 item 3).
    explicit TelegramParser(Sender sender, std::uint8_t address = 0, bool check_follower = false);

    /// Parses `bytes`; calls `callback` for each event in order. The Telegram reference is
    /// valid only during the call.
    void Feed(std::span<const std::uint8_t> bytes, const Callback& callback);
    /// The line went quiet: delivers a telegram waiting for its follower, then abandons the
    /// partial candidate (re-parsing what follows its STX).
    void Timeout(const Callback& callback);
    /// The line went idle after a complete telegram: delivers the telegram waiting for its
    /// follower (if any). Does not touch a partial candidate.
    void Idle(const Callback& callback);
    /// True while a candidate frame is being collected (not counting a complete telegram that
    /// waits for its follower).
    [[nodiscard]] bool InFrame() const { return !frame_.empty() && !pending_; }
    /// True while a complete telegram with a good CRC waits for its follower.
    [[nodiscard]] bool Pending() const { return pending_; }
    /// Command byte of the last rejected candidate (bad CRC, bad follower, timeout), 0 if it
    /// was too short to have one: tells a damaged reply from a damaged stream telegram.
    [[nodiscard]] std::uint8_t last_rejected_command() const { return last_rejected_command_; }
    /// False from a stray byte or abandoned candidate until the next good telegram (or Reset).
    [[nodiscard]] bool InSync() const { return !out_of_sync_; }
    /// Drops any partial frame without counting and starts in sync (after a port flush).
    void Reset();
    [[nodiscard]] const ParserCounters& counters() const { return counters_; }

private:
    void Step(std::uint8_t byte, const Callback& callback);
    void Deliver(const Callback& callback);
    void Abandon();
    void Drain(const Callback& callback);
    void LoseSync();
    [[nodiscard]] bool AddressOk(std::uint8_t address) const;

    Sender sender_;
    std::uint8_t address_;
    std::vector<std::uint8_t> frame_;   // current candidate, starts with STX
    std::vector<std::uint8_t> replay_;  // bytes to parse (again)
    std::size_t replay_pos_ = 0;
    std::size_t expected_size_ = 0;
    bool out_of_sync_ = false;
    bool check_follower_ = false;
    bool pending_ = false;
    std::uint8_t last_rejected_command_ = 0;
    Telegram telegram_;
    ParserCounters counters_;
};

}  // namespace casmap::drivers
