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
#include "casmap/drivers/output_mode.hpp"
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
            case 0xB0:
            case 0xB6:
            case 0xB7:
            case 0xBF: {
                const MeasuredValues v = ParseMeasuredValues(t);
                Check(MakeMeasuredValues(v) == t);
                FrameExpectation e;
                e.mode.kind = t.command == 0xB6   ? OutputKind::kMeanValues
                              : t.command == 0xB7 ? OutputKind::kSubRange
                              : t.command == 0xBF ? OutputKind::kMeanSubRange
                              : v.partial         ? OutputKind::kPartial
                                                  : OutputKind::kContinuous;
                e.mode.mean_scans = v.sample_size;
                e.mode.first_beam = v.first_beam;
                e.mode.last_beam = v.last_beam;
                e.variant = Variant{180, 50};
                e.realtime_indices = v.realtime_index.size() == 1;
                e.format.units = v.units;
                CheckMeasuredValues(v, e);  // throws InputError unless fully consistent
                (void)ScanFromFrame(v, e, 0.0);
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

void RunParser(Sender sender,
               std::span<const std::uint8_t> data,
               std::size_t chunk,
               bool check_follower) {
    TelegramParser parser(sender, 0, check_follower);
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
    RunParser(Sender::kScanner, all.subspan(1), chunk, (data[0] & 0x40U) != 0);
    RunParser(Sender::kHost, all.subspan(1), 1, false);
    if (const std::optional<Telegram> t = DecodeTelegram(all)) {
        Check(EncodeTelegram(*t) == std::vector<std::uint8_t>(all.begin(), all.end()));
        ExerciseParsers(*t);
    }
    return 0;
}
