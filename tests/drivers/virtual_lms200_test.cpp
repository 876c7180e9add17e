// The virtual LMS 200 against the raw telegrams third-party drivers send (reference 6.2-6.5).
#include "casmap/drivers/virtual_lms200.hpp"

#include <gtest/gtest.h>
#include <unistd.h>

#include <chrono>
#include <thread>

#include "casmap/core/input_error.hpp"
#include "casmap/drivers/serial_port.hpp"
#include "casmap/drivers/telegram_parser.hpp"
#include "test_source.hpp"

namespace casmap::drivers {
namespace {

using testing::NumberedSource;
using Clock = std::chrono::steady_clock;

std::string LinkPath(const std::string& name) {
    return "/tmp/casmap_vlms_test_" + std::to_string(getpid()) + "_" + name;
}

std::vector<std::uint8_t> Bytes(const std::string& hex) {
    std::vector<std::uint8_t> out;
    for (std::size_t i = 0; i + 1 < hex.size(); i += 3) {
        out.push_back(static_cast<std::uint8_t>(std::stoul(hex.substr(i, 2), nullptr, 16)));
    }
    return out;
}

/// A minimal host: writes a request one byte at a time with 55 us gaps (sicktoolbox) and
/// returns the raw bytes that come back until `expect` bytes arrived or `timeout_s` passed.
std::vector<std::uint8_t> Exchange(SerialPort& port,
                                   const std::vector<std::uint8_t>& request,
                                   std::size_t expect,
                                   double timeout_s = 1.0) {
    port.WriteSlowly(request, 55e-6);
    std::vector<std::uint8_t> got;
    std::uint8_t buf[1024];
    const Clock::time_point end = Clock::now() + std::chrono::duration_cast<Clock::duration>(
                                                     std::chrono::duration<double>(timeout_s));
    while (got.size() < expect && Clock::now() < end) {
        const std::size_t n = port.Read(buf, 0.02);
        got.insert(got.end(), buf, buf + n);
    }
    return got;
}

/// ACK, then one reply telegram: returns the reply (fails the test otherwise).
Telegram AckedReply(const std::vector<std::uint8_t>& bytes) {
    EXPECT_FALSE(bytes.empty());
    if (bytes.empty()) {
        return {};
    }
    EXPECT_EQ(bytes[0], kAck);
    const auto t = DecodeTelegram(std::span(bytes).subspan(1));
    EXPECT_TRUE(t.has_value());
    return t.value_or(Telegram{});
}

TEST(VirtualLms200, SicktoolboxStartupSequenceGetsTheRepliesItChecks) {
    NumberedSource source;
    VirtualLms200Config vc;
    vc.link_path = LinkPath("stb");
    VirtualLms200 scanner(vc, source);
    scanner.Start();
    SerialPort port(vc.link_path, 9600);

    // 1: at 9600, switch to 38400: exactly ACK + 02 80 03 00 A0 00 10 16 0A.
    const auto r1 = Exchange(port, Bytes("02 00 02 00 20 40 50 08"), 10);
    std::vector<std::uint8_t> want{kAck};
    const auto a0 = Bytes("02 80 03 00 A0 00 10 16 0A");
    want.insert(want.end(), a0.begin(), a0.end());
    EXPECT_EQ(r1, want);
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
    EXPECT_EQ(scanner.stats().baud, 38400);  // applied after the reply
    port.SetBaud(38400);
    std::this_thread::sleep_for(std::chrono::milliseconds(50));

    // 2: request mode: A0 with payload[1] == 0.
    const Telegram r2 = AckedReply(Exchange(port, Bytes("02 00 02 00 20 25 35 08"), 10));
    EXPECT_EQ(r2.command, 0xA0);
    EXPECT_EQ(r2.data, std::vector<std::uint8_t>{0x00});
    EXPECT_EQ(r2.status, 0x10);
    EXPECT_EQ(r2.address, 0x80);

    // 3: type: BA, LEN 23, contains LMS200;30106.
    const Telegram r3 = AckedReply(Exchange(port, Bytes("02 00 01 00 3A 1E 12"), 30));
    EXPECT_EQ(r3.command, 0xBA);
    EXPECT_EQ(r3.Len(), 23U);
    EXPECT_NE(ParseTypeReply(r3).find("LMS200;30106"), std::string::npos);

    // 4: status: B1, LEN 154, [8] = 0x25, [9] = 0, angle 180, resolution 100.
    const Telegram r4 = AckedReply(Exchange(port, Bytes("02 00 01 00 31 15 12"), 161));
    EXPECT_EQ(r4.command, 0xB1);
    EXPECT_EQ(r4.Len(), 154U);
    EXPECT_EQ(r4.data[8 - 1], 0x25);
    EXPECT_EQ(r4.data[9 - 1], 0x00);
    EXPECT_EQ(r4.data[107 - 1] | (r4.data[108 - 1] << 8), 180);
    EXPECT_EQ(r4.data[109 - 1] | (r4.data[110 - 1] << 8), 100);
    EXPECT_EQ(r4.data[116 - 1], 0x19);  // 38400
    EXPECT_EQ(r4.data[122 - 1], 1);     // mm

    // 5: configuration: F4, LEN 36, config byte 5 = 0x00 measuring mode, byte 6 = 1 (mm).
    const Telegram r5 = AckedReply(Exchange(port, Bytes("02 00 01 00 74 50 12"), 43));
    EXPECT_EQ(r5.command, 0xF4);
    EXPECT_EQ(r5.Len(), 36U);
    EXPECT_EQ(r5.data[5], 0x00);
    EXPECT_EQ(r5.data[6], 0x01);

    // The autodetection probe 0x32 gets B2 + status.
    const Telegram r6 = AckedReply(Exchange(port, Bytes("02 00 01 00 32 16 12"), 9));
    EXPECT_EQ(r6.command, 0xB2);
    EXPECT_EQ(r6.Len(), 2U);

    // Variant 180/0.5: BB LEN 7, payload[1] = 1, then angle and resolution.
    const Telegram r7 = AckedReply(Exchange(port, Bytes("02 00 05 00 3B B4 00 32 00 3B 1F"), 14));
    EXPECT_EQ(r7.command, 0xBB);
    EXPECT_EQ(r7.Len(), 7U);
    EXPECT_EQ(r7.data, (std::vector<std::uint8_t>{1, 0xB4, 0, 0x32, 0}));

    // Start streaming: A0 00, then complete B0 telegrams of 361 values.
    const auto r8 = Exchange(port, Bytes("02 00 02 00 20 24 34 08"), 10 + 2 * 732, 1.0);
    ASSERT_GE(r8.size(), 10U);
    EXPECT_EQ(AckedReply(std::vector<std::uint8_t>(r8.begin(), r8.begin() + 10)).data,
              std::vector<std::uint8_t>{0x00});
    TelegramParser parser(Sender::kScanner);
    int scans = 0;
    parser.Feed(std::span(r8).subspan(10), [&](ParserEvent e, const Telegram& t) {
        if (e == ParserEvent::kTelegram && t.command == 0xB0) {
            EXPECT_EQ(ParseMeasuredValues(t).values.size(), 361U);
            ++scans;
        }
    });
    EXPECT_GE(scans, 2);
    EXPECT_EQ(parser.counters().dropped_bytes, 0U);

    // A request pauses the stream: stop with 20 25 and the line goes quiet after the A0.
    port.Flush();
    const auto r9 = Exchange(port, Bytes("02 00 02 00 20 25 35 08"), 2000, 0.3);
    TelegramParser p2(Sender::kScanner);
    int a0s = 0;
    int b0s_after = 0;
    p2.Feed(r9, [&](ParserEvent e, const Telegram& t) {
        if (e == ParserEvent::kTelegram && t.command == 0xA0) {
            ++a0s;
        } else if (e == ParserEvent::kTelegram && t.command == 0xB0 && a0s > 0) {
            ++b0s_after;
        }
    });
    EXPECT_EQ(a0s, 1);
    EXPECT_EQ(b0s_after, 0);
    EXPECT_EQ(scanner.stats().operating_mode, 0x25);
}

TEST(VirtualLms200, BadChecksumGetsNakAndInstallationModeGuardsConfigWrites) {
    NumberedSource source;
    VirtualLms200Config vc;
    vc.link_path = LinkPath("nak");
    vc.config_write_s = 0.1;  // the default 3 s EEPROM write is tested in protocol tests
    VirtualLms200 scanner(vc, source);
    scanner.Start();
    SerialPort port(vc.link_path, 9600);
    EXPECT_EQ(Exchange(port, Bytes("02 00 01 00 31 15 13"), 1, 0.3),
              std::vector<std::uint8_t>{kNak});
    // Config write without installation mode: refused (F7 00).
    ConfigBlock cm = ConfigBlock::Default();
    cm.set_units(0);
    const Telegram refused =
        AckedReply(Exchange(port, EncodeTelegram(MakeWriteConfigRequest(cm)), 44));
    EXPECT_FALSE(ParseWriteConfigReply(refused).accepted);
    // Wrong password: A0 01.
    EXPECT_EQ(ParseModeReply(AckedReply(
                  Exchange(port, EncodeTelegram(MakeInstallationRequest("SICK_XXX")), 10))),
              1);
    EXPECT_EQ(
        ParseModeReply(AckedReply(Exchange(port, EncodeTelegram(MakeInstallationRequest()), 10))),
        0);
    const WriteConfigReply ok = ParseWriteConfigReply(
        AckedReply(Exchange(port, EncodeTelegram(MakeWriteConfigRequest(cm)), 44)));
    EXPECT_TRUE(ok.accepted);
    EXPECT_EQ(ok.config, cm);
    // Unknown command: 0x92.
    Telegram unknown;
    unknown.command = 0x66;
    EXPECT_EQ(AckedReply(Exchange(port, EncodeTelegram(unknown), 9)).command, 0x92);
    // Variant 180/0.25 does not exist: BB 00 with the current variant.
    const VariantReply vr = ParseVariantReply(
        AckedReply(Exchange(port, EncodeTelegram(MakeVariantRequest({180, 25})), 14)));
    EXPECT_FALSE(vr.accepted);
    EXPECT_EQ(vr.variant, (Variant{180, 100}));
}

TEST(VirtualLms200, SurvivesTheClientClosingAndReopeningAndIgnoresAWrongBaud) {
    NumberedSource source;
    VirtualLms200Config vc;
    vc.link_path = LinkPath("reopen");
    VirtualLms200 scanner(vc, source);
    scanner.Start();
    for (int i = 0; i < 3; ++i) {
        SerialPort port(vc.link_path, 9600);
        EXPECT_EQ(AckedReply(Exchange(port, EncodeTelegram(MakeErrorRequest()), 9)).command, 0xB2)
            << "open " << i;
    }
    SerialPort port(vc.link_path, 19200);  // the scanner still runs at 9600
    EXPECT_TRUE(Exchange(port, EncodeTelegram(MakeErrorRequest()), 9, 0.2).empty());
    EXPECT_GT(scanner.stats().wrong_baud_bytes, 0U);
}

TEST(VirtualLms200, RejectsBadConfiguration) {
    NumberedSource source;
    VirtualLms200Config vc;
    vc.power_on_baud = 57600;
    EXPECT_THROW(VirtualLms200(vc, source), InputError);
    vc.power_on_baud = 9600;
    vc.variant = {180, 25};
    EXPECT_THROW(VirtualLms200(vc, source), InputError);
    EXPECT_THROW((void)ParseFaults("crc=2"), InputError);
    EXPECT_THROW((void)ParseFaults("bits=0.1"), InputError);
    EXPECT_THROW((void)ParseFaults("crc=abc"), InputError);
    const FaultConfig f = ParseFaults("drop=0.01,disconnect=5");
    EXPECT_DOUBLE_EQ(f.drop_rate, 0.01);
    EXPECT_DOUBLE_EQ(f.disconnect_period_s, 5.0);
}

}  // namespace
}  // namespace casmap::drivers
