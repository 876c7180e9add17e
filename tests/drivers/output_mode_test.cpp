// Output modes 0x26/0x27/0x28/0x2A, their replies B6/B7/BF, and the checks beyond the CRC
// (issue #13 item 3), without a pty.
#include "casmap/drivers/output_mode.hpp"

#include <gtest/gtest.h>

#include <numbers>

#include "casmap/core/input_error.hpp"
#include "casmap/drivers/scan_codec.hpp"
#include "casmap/drivers/telegram_parser.hpp"
#include "test_source.hpp"

namespace casmap::drivers {
namespace {

std::vector<std::uint8_t> Bytes(const std::string& hex) {
    std::vector<std::uint8_t> out;
    for (std::size_t i = 0; i + 1 < hex.size(); i += 3) {
        out.push_back(static_cast<std::uint8_t>(std::stoul(hex.substr(i, 2), nullptr, 16)));
    }
    return out;
}

// Request telegrams of every streaming mode, reset and the remaining variants. The manual's
// (reference section 1) where it has them; the others computed with an independent Python
// implementation of the reference's CRC, which reproduces the manual's vectors.
TEST(OutputMode, GoldenRequestsEncodeByteForByte) {
    EXPECT_EQ(EncodeTelegram(MakeOutputModeRequest(OutputMode::Continuous())),
              Bytes("02 00 02 00 20 24 34 08"));
    EXPECT_EQ(EncodeTelegram(MakeOutputModeRequest(OutputMode::Mean(10))),
              Bytes("02 00 03 00 20 26 0A 76 3E"));
    EXPECT_EQ(EncodeTelegram(MakeOutputModeRequest(OutputMode::SubRange(10, 170))),
              Bytes("02 00 06 00 20 27 0A 00 AA 00 74 3A"));
    EXPECT_EQ(EncodeTelegram(MakeOutputModeRequest(OutputMode::MeanSubRange(5, 1, 181))),
              Bytes("02 00 07 00 20 28 05 01 00 B5 00 37 1A"));
    EXPECT_EQ(EncodeTelegram(MakeOutputModeRequest(OutputMode::Partial())),
              Bytes("02 00 02 00 20 2A 3A 08"));
    EXPECT_EQ(EncodeTelegram(MakeResetRequest()), Bytes("02 00 01 00 10 34 12"));
    EXPECT_EQ(EncodeTelegram(MakeResetReply()), Bytes("02 80 02 00 91 10 79 30"));
    EXPECT_EQ(EncodeTelegram(MakeVariantRequest({100, 100})),
              Bytes("02 00 05 00 3B 64 00 64 00 1D 0F"));
    EXPECT_EQ(EncodeTelegram(MakeVariantRequest({100, 50})),
              Bytes("02 00 05 00 3B 64 00 32 00 B1 59"));
    EXPECT_EQ(EncodeTelegram(MakeVariantRequest({100, 25})),
              Bytes("02 00 05 00 3B 64 00 19 00 E7 72"));
    // Each parses back to its mode.
    for (const OutputMode& m :
         {OutputMode::Continuous(), OutputMode::Mean(250), OutputMode::SubRange(1, 401),
          OutputMode::MeanSubRange(2, 7, 9), OutputMode::Partial()}) {
        EXPECT_EQ(ParseOutputModeRequest(MakeOutputModeRequest(m)), m) << m.ToString();
        EXPECT_EQ(ParseOutputMode(m.ToString(), "mode"), m);
    }
    EXPECT_FALSE(ParseOutputModeRequest(MakeModeRequest(mode::kRequest)).has_value());
}

TEST(OutputMode, ParametersAreValidatedAgainstTheVariant) {
    EXPECT_NO_THROW(OutputMode::Mean(2).Validate({180, 100}));
    EXPECT_THROW(OutputMode::Mean(1).Validate({180, 100}), InputError);
    EXPECT_THROW(OutputMode::Mean(251).Validate({180, 100}), InputError);
    EXPECT_NO_THROW(OutputMode::SubRange(1, 401).Validate({100, 25}));
    EXPECT_THROW(OutputMode::SubRange(1, 182).Validate({180, 100}), InputError);
    EXPECT_THROW(OutputMode::SubRange(0, 10).Validate({180, 100}), InputError);
    EXPECT_THROW(OutputMode::SubRange(20, 10).Validate({180, 100}), InputError);
    for (const char* bad :
         {"mean", "mean:x", "subrange:5", "subrange:1-", "fast", "mean-subrange:2"}) {
        try {
            (void)ParseOutputMode(bad, "mode");
            ADD_FAILURE() << bad << " accepted";
        } catch (const InputError& e) {
            EXPECT_EQ(std::string(e.what()).rfind("mode = ", 0), 0U) << e.what();  // no flag
        }
    }
}

// Block layout as sicktoolbox's _parseSickScanProfileB6/B7/BF read it.
TEST(OutputMode, ReplyBlocksSitWhereSicktoolboxReadsThem) {
    MeasuredValues v;
    v.command = cmd::kMeanSubRange;
    v.sample_size = 7;
    v.first_beam = 0x0102;
    v.last_beam = 0x0103;
    v.values = {0x1111, 0x2222};
    v.realtime_index = {0x55};
    const Telegram bf = MakeMeasuredValues(v);
    EXPECT_EQ(bf.command, 0xBF);
    EXPECT_EQ(bf.data, (std::vector<std::uint8_t>{7, 0x02, 0x01, 0x03, 0x01, 2, 0x40, 0x11, 0x11,
                                                  0x22, 0x22, 0x55}));
    EXPECT_EQ(ParseMeasuredValues(bf), v);
    v.command = cmd::kSubRange;
    v.sample_size = 0;
    const Telegram b7 = MakeMeasuredValues(v);
    EXPECT_EQ(b7.data[0], 0x02);  // start u16, stop u16, then the header
    EXPECT_EQ(b7.data[4], 2);
    EXPECT_EQ(ParseMeasuredValues(b7), v);
    v.command = cmd::kMeanValues;
    v.sample_size = 9;
    v.first_beam = v.last_beam = 0;
    const Telegram b6 = MakeMeasuredValues(v);
    EXPECT_EQ(b6.data[0], 9);  // sample size, then the header
    EXPECT_EQ(b6.data[1], 2);
    EXPECT_EQ(ParseMeasuredValues(b6), v);
    // Appending straight into a frame gives the same bytes.
    std::vector<std::uint8_t> framed;
    AppendMeasuredValues(v, framed);
    EXPECT_EQ(framed, EncodeTelegram(b6));
    // Reserved header bit 10 set: rejected.
    Telegram bad = MakeMeasuredValues(v);
    bad.data[2] |= 0x04;
    EXPECT_THROW((void)ParseMeasuredValues(bad), InputError);
}

MeasuredValues ScanValues(const Variant& variant) {
    MeasuredValues v;
    ValuesFromScan(testing::NumberedSource::Make(3, variant), core::Lms200Format{}, v);
    return v;
}

TEST(FrameChecks, EveryRuleBeyondTheCrcRejectsItsViolation) {
    FrameExpectation e;
    e.variant = {180, 50};
    MeasuredValues good = ScanValues(e.variant);
    EXPECT_NO_THROW(CheckMeasuredValues(good, e));
    const auto rejects = [&](MeasuredValues v, const std::string& field) {
        try {
            CheckMeasuredValues(v, e);
            ADD_FAILURE() << field << " accepted";
        } catch (const InputError& err) {
            EXPECT_NE(std::string(err.what()).find(field), std::string::npos) << err.what();
        }
    };
    MeasuredValues v = good;
    v.values.pop_back();
    rejects(v, "value count");  // a 180/1 length while 180/0.5 is configured
    v = good;
    v.realtime_index = {1};
    rejects(v, "bytes after the values");
    v = good;
    v.units = core::RangeUnits::kCentimetre;
    rejects(v, "units");
    v = good;
    v.values[5] = 0x2000 | 100;  // flag bit set, no field evaluation configured
    rejects(v, "value 5");
    v = good;
    v.values[6] = 0x1FF8;  // a reserved special code
    rejects(v, "value 6");
    v = good;
    v.partial = true;
    rejects(v, "partial");
    v = good;
    v.command = cmd::kMeanValues;
    rejects(v, "command");
    // Flags are accepted when the unit evaluates fields.
    e.value_flags = true;
    v = good;
    v.values[5] = 0x2000 | 100;
    EXPECT_NO_THROW(CheckMeasuredValues(v, e));
    // Mean and sub-range: sample size and bounds must be the configured ones.
    e.mode = OutputMode::MeanSubRange(4, 11, 20);
    v = good;
    v.command = cmd::kMeanSubRange;
    v.sample_size = 4;
    v.first_beam = 11;
    v.last_beam = 20;
    v.values.resize(10);
    EXPECT_NO_THROW(CheckMeasuredValues(v, e));
    v.sample_size = 5;
    rejects(v, "sample size");
    v.sample_size = 4;
    v.last_beam = 21;
    rejects(v, "sub-range");
    // Partial scans: 180 and 181 values for partial 1 and 0 at 0.5 deg; 0.25 deg offsets
    // are not multiples of 0.5 deg.
    e.mode = OutputMode::Partial();
    v = good;
    v.partial = true;
    v.partial_index = 2;  // 0.5 deg: partial 1
    v.values.resize(180);
    EXPECT_NO_THROW(CheckMeasuredValues(v, e));
    v.values.resize(181);
    rejects(v, "value count");
    v.partial_index = 1;
    rejects(v, "partial-scan index");
}

TEST(FrameChecks, ScansOfEveryModeCarryTheirBeamsGeometry) {
    constexpr double kDeg = std::numbers::pi / 180.0;
    FrameExpectation e;
    e.variant = {180, 50};
    MeasuredValues v = ScanValues(e.variant);
    e.mode = OutputMode::SubRange(11, 20);
    v.command = cmd::kSubRange;
    v.first_beam = 11;
    v.last_beam = 20;
    v.values.resize(10);
    const core::Scan sub = ScanFromFrame(v, e, 100.0);
    EXPECT_NEAR(sub.start_angle_rad, (-90.0 + 10 * 0.5) * kDeg, 1e-12);
    EXPECT_NEAR(sub.angle_step_rad, 0.5 * kDeg, 1e-12);
    // Beam 10 (first) is even: turn 0; beam 11 (second) odd: one turn later.
    EXPECT_NEAR(sub.stamp_s, 100.0 + 10 * 0.5 / 360.0 / 75.0, 1e-12);
    EXPECT_NEAR(sub.BeamTime(1) - sub.BeamTime(0), 1.0 / 75.0 + 0.5 / 360.0 / 75.0, 1e-12);
    e.mode = OutputMode::Partial();
    v = ScanValues(e.variant);
    v.command = cmd::kValues;
    v.partial = true;
    v.partial_index = 2;
    v.values.resize(180);
    const core::Scan part = ScanFromFrame(v, e, 50.0);
    EXPECT_NEAR(part.start_angle_rad, -89.5 * kDeg, 1e-12);
    EXPECT_NEAR(part.angle_step_rad, 1.0 * kDeg, 1e-12);
    EXPECT_NEAR(part.BeamTime(179) - part.BeamTime(0), 179.0 / 360.0 / 75.0, 1e-12);
}

/// The wire after frame `a` loses byte `drop`: its bytes, then frame `b`.
std::vector<std::uint8_t> DropThenNext(const std::vector<std::uint8_t>& a,
                                       std::size_t drop,
                                       const std::vector<std::uint8_t>& b) {
    std::vector<std::uint8_t> wire(a);
    wire.erase(wire.begin() + static_cast<std::ptrdiff_t>(drop));
    wire.insert(wire.end(), b.begin(), b.end());
    return wire;
}

// Issue #13 item 3: a single dropped byte whose frame keeps a valid CRC once the next
// telegram's STX completes it. Search sweeps and drop positions for one.
TEST(FrameChecks, CrcCollisionFromADroppedByteIsRejectedByTheFollowerCheck) {
    const Variant variant{180, 100};
    std::vector<std::uint8_t> a;
    std::vector<std::uint8_t> b;
    std::size_t drop = 0;
    std::uint64_t sweep = 0;
    for (; sweep < 2000 && drop == 0; ++sweep) {
        MeasuredValues v;
        ValuesFromScan(testing::NumberedSource::Make(sweep, variant), core::Lms200Format{}, v);
        a.clear();
        AppendMeasuredValues(v, a);
        for (std::size_t i = 7; i + 1 < a.size() && drop == 0; ++i) {
            const std::vector<std::uint8_t> wire = DropThenNext(a, i, {kStx});
            const std::size_t crc_at = a.size() - 2;
            if (Crc16(std::span(wire).first(crc_at)) == (wire[crc_at] | (wire[crc_at + 1] << 8))) {
                drop = i;
            }
        }
    }
    ASSERT_NE(drop, 0U) << "no colliding drop found";
    std::printf("collision: sweep %llu, byte %zu of %zu dropped\n",
                static_cast<unsigned long long>(sweep - 1), drop, a.size());
    MeasuredValues next;
    ValuesFromScan(testing::NumberedSource::Make(sweep, variant), core::Lms200Format{}, next);
    AppendMeasuredValues(next, b);
    const std::vector<std::uint8_t> wire = DropThenNext(a, drop, b);

    // Without the follower check the damaged frame passes as a good telegram.
    std::vector<std::uint16_t> firsts;
    TelegramParser lax(Sender::kScanner);
    lax.Feed(wire, [&](ParserEvent ev, const Telegram& t) {
        if (ev == ParserEvent::kTelegram) {
            firsts.push_back(ParseMeasuredValues(t).values.at(0));
        }
    });
    lax.Timeout([](ParserEvent, const Telegram&) {});
    EXPECT_EQ(firsts.size(), 1U);  // the damaged one; the next lost its STX
    // With it: the damaged frame is rejected, the next one is found.
    firsts.clear();
    TelegramParser strict(Sender::kScanner, 0, true);
    strict.Feed(wire, [&](ParserEvent ev, const Telegram& t) {
        if (ev == ParserEvent::kTelegram) {
            firsts.push_back(ParseMeasuredValues(t).values.at(0));
        }
    });
    strict.Idle([&](ParserEvent ev, const Telegram& t) {
        if (ev == ParserEvent::kTelegram) {
            firsts.push_back(ParseMeasuredValues(t).values.at(0));
        }
    });
    EXPECT_EQ(strict.counters().bad_followers, 1U);
    EXPECT_EQ(firsts, std::vector<std::uint16_t>{static_cast<std::uint16_t>(sweep % 8000)});
    EXPECT_EQ(strict.counters().telegrams + 0, 1U);
    const ParserCounters& sc = strict.counters();
    EXPECT_EQ(sc.bytes, b.size() + sc.acks + sc.naks + sc.dropped_bytes);  // every byte once
}

TEST(FrameChecks, FollowerCheckPassesStreamsAcksAndIdle) {
    MeasuredValues v;
    v.values.assign(181, 1000);
    std::vector<std::uint8_t> wire;
    AppendMeasuredValues(v, wire);
    AppendMeasuredValues(v, wire);
    wire.push_back(kAck);
    AppendMeasuredValues(v, wire);
    TelegramParser p(Sender::kScanner, 0, true);
    int telegrams = 0;
    const TelegramParser::Callback cb = [&](ParserEvent ev, const Telegram&) {
        telegrams += ev == ParserEvent::kTelegram ? 1 : 0;
    };
    p.Feed(wire, cb);
    EXPECT_EQ(telegrams, 2);  // the third waits for its follower
    EXPECT_TRUE(p.Pending());
    EXPECT_FALSE(p.InFrame());
    p.Idle(cb);
    EXPECT_EQ(telegrams, 3);
    EXPECT_EQ(p.counters().acks, 1U);
    EXPECT_EQ(p.counters().dropped_bytes, 0U);
}

}  // namespace
}  // namespace casmap::drivers
