// Golden telegrams from shared/reference/lms200_protocol.md section 1 (SICK manual examples
// quoted by manorajesh/sick-lidar and JeffreyYijiWang/Gepruft_Lidar) and one real capture.
#include "casmap/drivers/telegram.hpp"

#include <gtest/gtest.h>

#include <cstdio>
#include <fstream>
#include <numbers>
#include <sstream>
#include <string>

#include "casmap/core/input_error.hpp"
#include "casmap/drivers/scan_codec.hpp"

namespace casmap::drivers {
namespace {

std::vector<std::uint8_t> Bytes(const std::string& hex) {
    std::vector<std::uint8_t> out;
    std::istringstream in(hex);
    std::string token;
    while (in >> token) {
        out.push_back(static_cast<std::uint8_t>(std::stoul(token, nullptr, 16)));
    }
    return out;
}

std::vector<std::uint8_t> RealCapture() {
    std::ifstream in(std::string(CASMAP_SOURCE_DIR) + "/tests/data/drivers/b0_real_361_mm.hex");
    std::stringstream s;
    s << in.rdbuf();
    return Bytes(s.str());
}

struct Golden {
    const char* name;
    Telegram telegram;
    const char* hex;
};

std::vector<Golden> Goldens() {
    return {
        {"status", MakeStatusRequest(), "02 00 01 00 31 15 12"},
        {"type", MakeTypeRequest(), "02 00 01 00 3A 1E 12"},
        {"read_config", MakeReadConfigRequest(), "02 00 01 00 74 50 12"},
        {"errors", MakeErrorRequest(), "02 00 01 00 32 16 12"},
        {"installation", MakeInstallationRequest(),
         "02 00 0A 00 20 00 53 49 43 4B 5F 4C 4D 53 BE C5"},
        {"baud9600", MakeBaudRequest(9600), "02 00 02 00 20 42 52 08"},
        {"baud19200", MakeBaudRequest(19200), "02 00 02 00 20 41 51 08"},
        {"baud38400", MakeBaudRequest(38400), "02 00 02 00 20 40 50 08"},
        {"baud500k", MakeBaudRequest(500000), "02 00 02 00 20 48 58 08"},
        {"stream", MakeModeRequest(mode::kStreamAll), "02 00 02 00 20 24 34 08"},
        {"request_mode", MakeModeRequest(mode::kRequest), "02 00 02 00 20 25 35 08"},
        {"partial", MakeModeRequest(mode::kStreamPartial), "02 00 02 00 20 2A 3A 08"},
        {"scan", MakeScanRequest(), "02 00 02 00 30 01 31 18"},
        {"variant180_1", MakeVariantRequest({180, 100}), "02 00 05 00 3B B4 00 64 00 97 49"},
        {"variant180_05", MakeVariantRequest({180, 50}), "02 00 05 00 3B B4 00 32 00 3B 1F"},
        {"variant100_025", MakeVariantRequest({100, 25}), "02 00 05 00 3B 64 00 19 00 E7 72"},
        {"a0_ok", MakeModeReply(0), "02 80 03 00 A0 00 10 16 0A"},
        {"not_acknowledged", MakeNotAcknowledged(), "02 80 02 00 92 10 7F 33"},
    };
}

TEST(Telegram, GoldenTelegramsEncodeByteForByte) {
    for (const Golden& g : Goldens()) {
        EXPECT_EQ(EncodeTelegram(g.telegram), Bytes(g.hex)) << g.name;
    }
}

TEST(Telegram, GoldenTelegramsDecodeToTheSameTelegram) {
    for (const Golden& g : Goldens()) {
        FrameError error = FrameError::kShort;
        const auto decoded = DecodeTelegram(Bytes(g.hex), &error);
        ASSERT_TRUE(decoded.has_value()) << g.name;
        EXPECT_EQ(error, FrameError::kNone);
        EXPECT_EQ(*decoded, g.telegram) << g.name;
    }
}

TEST(Telegram, ReplyAtAddressOneMatchesManual) {
    Telegram t = MakeModeReply(0);
    t.address = 0x81;
    EXPECT_EQ(EncodeTelegram(t), Bytes("02 81 03 00 A0 00 10 36 1A"));
}

TEST(Telegram, EveryFlippedBitIsRejected) {
    const std::vector<std::uint8_t> good = Bytes("02 00 05 00 3B B4 00 64 00 97 49");
    for (std::size_t i = 0; i < good.size() * 8; ++i) {
        std::vector<std::uint8_t> bad = good;
        bad[i / 8] ^= static_cast<std::uint8_t>(1U << (i % 8));
        EXPECT_FALSE(DecodeTelegram(bad).has_value()) << "bit " << i;
    }
}

TEST(Telegram, RealCaptureDecodesAndReencodesByteForByte) {
    const std::vector<std::uint8_t> frame = RealCapture();
    ASSERT_EQ(frame.size(), 732U);
    EXPECT_EQ(Crc16(std::span(frame).first(730)), 0x4764);
    const auto t = DecodeTelegram(frame);
    ASSERT_TRUE(t.has_value());
    const MeasuredValues v = ParseMeasuredValues(*t);
    EXPECT_EQ(v.values.size(), 361U);
    EXPECT_EQ(v.units, core::RangeUnits::kMillimetre);
    EXPECT_FALSE(v.partial);
    EXPECT_EQ(v.status, 0x10);
    EXPECT_EQ(v.values.front(), 0x08CB);
    EXPECT_EQ(v.values.back(), 0x0518);
    EXPECT_EQ(EncodeTelegram(MakeMeasuredValues(v)), frame);
    std::vector<std::uint8_t> appended;
    AppendMeasuredValues(v, appended);
    EXPECT_EQ(appended, frame);
    const core::Scan scan = ScanFromValues(v, core::Lms200Format{}, Variant{180, 50}, 1.0);
    EXPECT_FLOAT_EQ(scan.beams.front().range_m, 2.251F);  // 0x08CB mm
    EXPECT_EQ(scan.beams.front().raw, 0x08CB);
    EXPECT_EQ(scan.beam_time_offset_s.size(), 361U);
}

TEST(Telegram, MeasuredValueHeaderBits) {
    MeasuredValues v;
    v.values.assign(181, 0x1FFF);
    v.units = core::RangeUnits::kCentimetre;
    v.partial = true;
    v.partial_index = 2;
    v.realtime_index = {7};
    const Telegram t = MakeMeasuredValues(v);
    EXPECT_EQ(t.data[0] | (t.data[1] << 8), 181 | (2 << 11) | (1 << 13));
    EXPECT_EQ(t.Len(), 1U + 2U + 362U + 1U + 1U);
    EXPECT_EQ(ParseMeasuredValues(t), v);
    v.units = core::RangeUnits::kMillimetre;
    EXPECT_EQ(MakeMeasuredValues(v).data[1] & 0xC0, 0x40);
}

TEST(Telegram, CountMismatchIsRejectedWithTheRule) {
    MeasuredValues v;
    v.values.assign(181, 100);
    Telegram t = MakeMeasuredValues(v);
    t.data.resize(t.data.size() - 10);
    try {
        (void)ParseMeasuredValues(t);
        FAIL() << "no exception";
    } catch (const InputError& e) {
        EXPECT_NE(std::string(e.what()).find("0xB0"), std::string::npos) << e.what();
        EXPECT_NE(std::string(e.what()).find("LEN"), std::string::npos) << e.what();
    }
}

TEST(Telegram, StatusReplyRoundTripsAndHasTheReferenceLayout) {
    DeviceStatus d;
    d.operating_mode = mode::kStreamAll;
    d.variant = {180, 50};
    d.baud_word = BaudWord(38400);
    d.units = 1;
    const Telegram t = MakeStatusReply(d);
    EXPECT_EQ(t.Len(), 154U);
    // Payload indices (CMD = 0) that sicktoolbox and RL read.
    EXPECT_EQ(t.data[8 - 1], 0x24);
    EXPECT_EQ(t.data[107 - 1], 180);
    EXPECT_EQ(t.data[109 - 1], 50);
    EXPECT_EQ(t.data[116 - 1], 0x19);
    EXPECT_EQ(t.data[117 - 1], 0x80);
    EXPECT_EQ(t.data[122 - 1], 1);
    EXPECT_EQ(ParseStatusReply(t), d);
}

TEST(Telegram, BaudWordsMatchReference) {
    EXPECT_EQ(BaudWord(9600), 0x8067);
    EXPECT_EQ(BaudWord(19200), 0x8033);
    EXPECT_EQ(BaudWord(38400), 0x8019);
    EXPECT_EQ(BaudWord(500000), 0x8001);
    EXPECT_THROW((void)MakeBaudRequest(57600), InputError);
    EXPECT_THROW(CheckLmsBaud(115200, "baud"), InputError);
}

TEST(Telegram, ReplyLengthsMatchTheChecklist) {
    EXPECT_EQ(MakeModeReply(0).Len(), 3U);
    EXPECT_EQ(MakeTypeReply("LMS200;30106x;V02.10 ").Len(), 23U);
    EXPECT_EQ(MakeVariantReply(true, {180, 100}).Len(), 7U);
    EXPECT_EQ(MakeConfigReply(ConfigBlock::Default()).Len(), 36U);
    EXPECT_EQ(MakeConfigReply(ConfigBlock::Default(32)).Len(), 34U);
    EXPECT_EQ(MakeWriteConfigRequest(ConfigBlock::Default()).Len(), 35U);
    EXPECT_EQ(MakeErrorReply({}).Len(), 2U);
}

TEST(Telegram, OtherRepliesRoundTrip) {
    EXPECT_EQ(ParseModeReply(MakeModeReply(1)), 1);
    EXPECT_EQ(ParseTypeReply(MakeTypeReply("LMS200;30106x;V02.10 ")), "LMS200;30106x;V02.10 ");
    const VariantReply vr = ParseVariantReply(MakeVariantReply(true, {100, 25}));
    EXPECT_TRUE(vr.accepted);
    EXPECT_EQ(vr.variant, (Variant{100, 25}));
    ConfigBlock c = ConfigBlock::Default();
    c.set_measuring_mode(0x04);
    c.set_units(0);
    EXPECT_EQ(ParseConfigReply(MakeConfigReply(c)), c);
    EXPECT_EQ(ParseWriteConfigRequest(MakeWriteConfigRequest(c)), c);
    const WriteConfigReply wr = ParseWriteConfigReply(MakeWriteConfigReply(true, c));
    EXPECT_TRUE(wr.accepted);
    EXPECT_EQ(wr.config, c);
    const std::pair<std::uint8_t, std::uint8_t> errors[] = {{3, 7}, {2, 1}};
    EXPECT_EQ(ParseErrorReply(MakeErrorReply(errors)).size(), 2U);
    EXPECT_EQ(ParseVariantRequest(MakeVariantRequest({180, 50})), (Variant{180, 50}));
    EXPECT_EQ(FormatOf(c).mode, core::RangeMode::k16m);
    EXPECT_EQ(FormatOf(c).units, core::RangeUnits::kCentimetre);
    c.set_measuring_mode(0x0F);
    EXPECT_THROW((void)FormatOf(c), InputError);
}

TEST(Telegram, WrongCommandIsRejected) {
    EXPECT_THROW((void)ParseStatusReply(MakeModeReply(0)), InputError);
    EXPECT_THROW((void)ParseModeReply(MakeStatusReply(DeviceStatus{})), InputError);
}

TEST(ScanCodec, EncodeBeamKeepsConsistentRawAndEncodesTheRest) {
    const core::Lms200Format mm{};
    core::Beam b = mm.Decode(0x2000 | 1234);  // field A flag set
    EXPECT_EQ(EncodeBeam(b, mm), 0x2000 | 1234);
    b.raw = 0;
    EXPECT_EQ(EncodeBeam(b, mm), 1234);
    core::Beam dazzle;
    dazzle.status = core::BeamStatus::kDazzle;
    EXPECT_EQ(EncodeBeam(dazzle, mm), 8190);
    core::Lms200Format cm{};
    cm.units = core::RangeUnits::kCentimetre;
    core::Beam far = mm.Decode(1234);
    EXPECT_EQ(EncodeBeam(far, cm), 123);  // raw does not decode to the same range in cm
}

TEST(ScanCodec, TimingOfTheVariants) {
    EXPECT_NEAR(SweepDurationS({180, 100}), 0.5 / 75.0, 1e-12);
    EXPECT_NEAR(SweepDurationS({180, 50}), 1.5 / 75.0, 1e-12);
    EXPECT_NEAR(ScanPeriodS({100, 25}), 4.0 / 75.0, 1e-12);
    EXPECT_NEAR(TransmissionTimeS(372, 38400), 0.096875, 1e-12);
    MeasuredValues v;
    v.values.assign(101, 5);
    const core::Scan s = ScanFromValues(v, {}, {100, 100}, 0.0);
    EXPECT_NEAR(s.start_angle_rad, -50.0 * std::numbers::pi / 180.0, 1e-12);
}

}  // namespace
}  // namespace casmap::drivers
