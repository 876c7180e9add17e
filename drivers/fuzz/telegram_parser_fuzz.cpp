// libFuzzer target: arbitrary bytes through the streaming parser (both directions, in chunks
// chosen by the input), every telegram parser, and the frame decoder. Checks that nothing
// crashes, that accepted telegrams re-encode to frames that decode to themselves, and that
// every byte is accounted for (in a telegram, an ACK/NAK, or dropped).
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <span>

#include "casmap/core/input_error.hpp"
#include "casmap/core/lms200.hpp"
#include "casmap/drivers/scan_codec.hpp"
#include "casmap/drivers/telegram.hpp"
#include "casmap/drivers/telegram_parser.hpp"

namespace {

using namespace casmap::drivers;

void Check(bool ok) {
    if (!ok) {
        std::abort();
    }
}

void ExerciseParsers(const Telegram& t) {
    try {
        switch (t.command) {
            case 0xA0:
                (void)ParseModeReply(t);
                break;
            case 0xB0: {
                const MeasuredValues v = ParseMeasuredValues(t);
                Check(MakeMeasuredValues(v) == t);
                const Variant variant{180, 100};
                if (v.values.size() == static_cast<std::size_t>(variant.BeamCount())) {
                    (void)ScanFromValues(v, casmap::core::Lms200Format{}, variant, 0.0);
                }
                break;
            }
            case 0xB1:
                (void)ParseStatusReply(t);
                break;
            case 0xB2:
                (void)ParseErrorReply(t);
                break;
            case 0xBA:
                (void)ParseTypeReply(t);
                break;
            case 0xBB:
                (void)ParseVariantReply(t);
                break;
            case 0xF4:
                (void)FormatOf(ParseConfigReply(t));
                break;
            case 0xF7:
                (void)ParseWriteConfigReply(t);
                break;
            case 0x3B:
                (void)ParseVariantRequest(t);
                break;
            case 0x77:
                (void)ParseWriteConfigRequest(t);
                break;
            default:
                break;
        }
    } catch (const casmap::InputError&) {
        // a rejected telegram is an expected outcome
    }
}

void RunParser(Sender sender, std::span<const std::uint8_t> data, std::size_t chunk) {
    TelegramParser parser(sender);
    std::uint64_t in_telegrams = 0;
    const TelegramParser::Callback cb = [&](ParserEvent e, const Telegram& t) {
        if (e != ParserEvent::kTelegram) {
            return;
        }
        in_telegrams += t.Len() + kFrameOverhead;
        const std::vector<std::uint8_t> frame = EncodeTelegram(t);
        const std::optional<Telegram> again = DecodeTelegram(frame);
        Check(again.has_value() && *again == t);
        ExerciseParsers(t);
    };
    for (std::size_t at = 0; at < data.size(); at += chunk) {
        parser.Feed(data.subspan(at, std::min(chunk, data.size() - at)), cb);
    }
    parser.Timeout(cb);
    const ParserCounters& c = parser.counters();
    Check(c.bytes == data.size());
    Check(in_telegrams + c.acks + c.naks + c.dropped_bytes == c.bytes);
    Check(!parser.InFrame());
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    if (size == 0) {
        return 0;
    }
    const std::span<const std::uint8_t> all(data, size);
    const std::size_t chunk = 1 + data[0] % 64;
    RunParser(Sender::kScanner, all.subspan(1), chunk);
    RunParser(Sender::kHost, all.subspan(1), 1);
    if (const std::optional<Telegram> t = DecodeTelegram(all)) {
        Check(EncodeTelegram(*t) == std::vector<std::uint8_t>(all.begin(), all.end()));
        ExerciseParsers(*t);
    }
    return 0;
}
