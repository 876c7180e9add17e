// Telegram parser and B0 encoder throughput (bytes/s). The line carries at most 50 kB/s at
// 500000 baud, so the parser needs only a small fraction of a core.
#include <benchmark/benchmark.h>

#include <random>

#include "casmap/drivers/scan_codec.hpp"
#include "casmap/drivers/telegram.hpp"
#include "casmap/drivers/telegram_parser.hpp"

namespace casmap::drivers {
namespace {

std::vector<std::uint8_t> Stream(int telegrams, double garbage_rate) {
    std::mt19937 rng(1);
    std::vector<std::uint8_t> out;
    MeasuredValues v;
    v.values.resize(181);
    for (int t = 0; t < telegrams; ++t) {
        for (auto& x : v.values) {
            x = static_cast<std::uint16_t>(rng() % 8000);
        }
        if (std::uniform_real_distribution<double>(0, 1)(rng) < garbage_rate) {
            for (int k = 0; k < 20; ++k) {
                out.push_back(static_cast<std::uint8_t>(rng()));
            }
        }
        AppendMeasuredValues(v, out);
    }
    return out;
}

void BM_ParseStream(benchmark::State& state) {
    const std::vector<std::uint8_t> stream = Stream(200, static_cast<double>(state.range(0)) / 100);
    std::uint64_t telegrams = 0;
    const TelegramParser::Callback cb = [&](ParserEvent e, const Telegram&) {
        telegrams += e == ParserEvent::kTelegram ? 1 : 0;
    };
    TelegramParser parser(Sender::kScanner);
    for (auto _ : state) {
        parser.Feed(stream, cb);
    }
    benchmark::DoNotOptimize(telegrams);
    state.SetBytesProcessed(static_cast<std::int64_t>(state.iterations() * stream.size()));
    state.SetItemsProcessed(static_cast<std::int64_t>(telegrams));
}
BENCHMARK(BM_ParseStream)->Arg(0)->Arg(10);  // percent of telegrams preceded by garbage

void BM_EncodeMeasuredValues(benchmark::State& state) {
    MeasuredValues v;
    v.values.assign(static_cast<std::size_t>(state.range(0)), 1234);
    std::vector<std::uint8_t> out;
    out.reserve(kMaxFrameBytes);
    for (auto _ : state) {
        out.clear();
        AppendMeasuredValues(v, out);
        benchmark::DoNotOptimize(out.data());
    }
    state.SetItemsProcessed(state.iterations());
    state.SetBytesProcessed(static_cast<std::int64_t>(state.iterations() * out.size()));
}
BENCHMARK(BM_EncodeMeasuredValues)->Arg(181)->Arg(361);

void BM_DecodeToScan(benchmark::State& state) {
    MeasuredValues v;
    v.values.assign(181, 1234);
    const Telegram t = MakeMeasuredValues(v);
    for (auto _ : state) {
        const core::Scan s = ScanFromValues(ParseMeasuredValues(t), {}, {180, 100}, 0.0);
        benchmark::DoNotOptimize(s.beams.data());
    }
    state.SetItemsProcessed(state.iterations());
}
BENCHMARK(BM_DecodeToScan);

}  // namespace
}  // namespace casmap::drivers

BENCHMARK_MAIN();
