#include "casmap/drivers/telegram_parser.hpp"

#include <gtest/gtest.h>

#include <random>

namespace casmap::drivers {
namespace {

struct Collected {
    std::vector<Telegram> telegrams;
    int acks = 0;
    int naks = 0;
    int bad_crc = 0;
    TelegramParser::Callback Sink() {
        return [this](ParserEvent e, const Telegram& t) {
            switch (e) {
                case ParserEvent::kTelegram:
                    telegrams.push_back(t);
                    break;
                case ParserEvent::kAckByte:
                    ++acks;
                    break;
                case ParserEvent::kNakByte:
                    ++naks;
                    break;
                case ParserEvent::kBadCrc:
                    ++bad_crc;
                    break;
            }
        };
    }
};

Telegram Scan(std::uint16_t first) {
    MeasuredValues v;
    v.values.assign(181, 1000);
    v.values[0] = first;
    return MakeMeasuredValues(v);
}

void Append(std::vector<std::uint8_t>& stream, const Telegram& t) {
    const std::vector<std::uint8_t> f = EncodeTelegram(t);
    stream.insert(stream.end(), f.begin(), f.end());
}

TEST(TelegramParser, AckThenReplyByteByByte) {
    std::vector<std::uint8_t> stream{kAck};
    Append(stream, MakeModeReply(0));
    TelegramParser parser(Sender::kScanner);
    Collected c;
    for (const std::uint8_t b : stream) {
        parser.Feed(std::span(&b, 1), c.Sink());
    }
    EXPECT_EQ(c.acks, 1);
    ASSERT_EQ(c.telegrams.size(), 1U);
    EXPECT_EQ(c.telegrams[0], MakeModeReply(0));
    EXPECT_EQ(parser.counters().dropped_bytes, 0U);
    EXPECT_EQ(parser.counters().resyncs, 0U);
}

TEST(TelegramParser, FalseStartInGarbageDoesNotSwallowTheNextTelegram) {
    // Garbage ending in a plausible header (02 80, LEN 700) right before a short reply: the
    // candidate eats the reply, fails its CRC, and the reply is found on the re-parse.
    std::vector<std::uint8_t> stream{0x55, 0x02, 0x80, 0xBC, 0x02};
    Append(stream, MakeModeReply(0));
    for (int i = 0; i < 5; ++i) {
        Append(stream, Scan(static_cast<std::uint16_t>(i)));
    }
    TelegramParser parser(Sender::kScanner);
    Collected c;
    parser.Feed(stream, c.Sink());
    ASSERT_EQ(c.telegrams.size(), 6U);
    EXPECT_EQ(c.telegrams[0].command, 0xA0);
    EXPECT_EQ(parser.counters().crc_errors, 1U);
    EXPECT_EQ(parser.counters().dropped_bytes, 5U);
    EXPECT_EQ(parser.counters().resyncs, 1U);
    EXPECT_EQ(parser.counters().bytes, stream.size());
}

TEST(TelegramParser, TimeoutReleasesATelegramHiddenBehindAnIncompleteCandidate) {
    std::vector<std::uint8_t> stream{0x02, 0x80, 0xBC, 0x02};
    Append(stream, MakeModeReply(0));
    TelegramParser parser(Sender::kScanner);
    Collected c;
    parser.Feed(stream, c.Sink());
    EXPECT_TRUE(c.telegrams.empty());
    EXPECT_TRUE(parser.InFrame());
    parser.Timeout(c.Sink());
    ASSERT_EQ(c.telegrams.size(), 1U);
    EXPECT_FALSE(parser.InFrame());
    EXPECT_EQ(parser.counters().timeouts, 1U);
}

TEST(TelegramParser, CorruptedTelegramsAreRejectedAndTheRestKept) {
    const unsigned seed = 20261122;
    SCOPED_TRACE("seed " + std::to_string(seed));
    std::mt19937 rng(seed);
    std::vector<std::uint8_t> stream;
    std::vector<std::uint16_t> expected;
    int corrupted = 0;
    std::uint64_t garbage = 0;
    for (std::uint16_t i = 0; i < 300; ++i) {
        std::vector<std::uint8_t> f = EncodeTelegram(Scan(i));
        const unsigned roll = rng() % 10;
        if (roll == 0) {  // flip one bit past the header
            f[5 + rng() % (f.size() - 5)] ^= static_cast<std::uint8_t>(1U << (rng() % 8));
            ++corrupted;
        } else if (roll == 1) {  // drop one byte
            f.erase(f.begin() + static_cast<std::ptrdiff_t>(rng() % f.size()));
            ++corrupted;
        } else {
            expected.push_back(i);
        }
        if (rng() % 10 == 0) {  // a burst of garbage before the telegram
            const unsigned n = 1 + rng() % 40;
            for (unsigned k = 0; k < n; ++k) {
                stream.push_back(static_cast<std::uint8_t>(rng() % 256 == 0 ? kStx : rng()));
            }
            garbage += n;
        }
        stream.insert(stream.end(), f.begin(), f.end());
    }
    TelegramParser parser(Sender::kScanner);
    Collected c;
    // Feed in random chunk sizes.
    std::size_t at = 0;
    while (at < stream.size()) {
        const std::size_t n = std::min<std::size_t>(1 + rng() % 700, stream.size() - at);
        parser.Feed(std::span(stream).subspan(at, n), c.Sink());
        at += n;
    }
    parser.Timeout(c.Sink());
    std::vector<std::uint16_t> got;
    for (const Telegram& t : c.telegrams) {
        if (t.command == 0xB0) {
            got.push_back(ParseMeasuredValues(t).values[0]);
        }
    }
    EXPECT_EQ(got, expected);
    const ParserCounters& k = parser.counters();
    EXPECT_GE(k.crc_errors + k.bad_headers + k.timeouts, static_cast<std::uint64_t>(corrupted));
    EXPECT_GE(k.dropped_bytes, garbage);
    EXPECT_EQ(k.bytes, stream.size());
    // Byte accounting: every byte is in an accepted telegram, an ACK/NAK, or dropped.
    std::uint64_t accepted = 0;
    for (const Telegram& t : c.telegrams) {
        accepted += t.Len() + kFrameOverhead;
    }
    EXPECT_EQ(accepted + k.acks + k.naks + k.dropped_bytes, k.bytes);
}

TEST(TelegramParser, HostSideAcceptsRequestsAndRejectsReplies) {
    std::vector<std::uint8_t> stream;
    Append(stream, MakeModeReply(0));  // a reply on the host side: not a request
    Append(stream, MakeStatusRequest());
    stream.push_back(kAck);  // stray on the host side
    Append(stream, MakeVariantRequest({180, 50}));
    TelegramParser parser(Sender::kHost);
    Collected c;
    parser.Feed(stream, c.Sink());
    ASSERT_EQ(c.telegrams.size(), 2U);
    EXPECT_EQ(c.telegrams[0], MakeStatusRequest());
    EXPECT_EQ(c.telegrams[1], MakeVariantRequest({180, 50}));
    EXPECT_EQ(c.acks, 0);
}

TEST(TelegramParser, NoiseOnlyIsCountedNeverAccepted) {
    const unsigned seed = 7;
    SCOPED_TRACE("seed " + std::to_string(seed));
    std::mt19937 rng(seed);
    std::vector<std::uint8_t> noise(100000);
    for (auto& b : noise) {
        b = static_cast<std::uint8_t>(rng());
    }
    TelegramParser parser(Sender::kScanner);
    Collected c;
    parser.Feed(noise, c.Sink());
    parser.Timeout(c.Sink());
    EXPECT_TRUE(c.telegrams.empty());
    EXPECT_EQ(parser.counters().dropped_bytes + parser.counters().acks + parser.counters().naks,
              noise.size());
}

}  // namespace
}  // namespace casmap::drivers
