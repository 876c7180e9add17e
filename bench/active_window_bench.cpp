// BM_ActiveWindowScan (DESIGN.md budget: p99 per scan <= 200 us on one core): one LMS 200 scan
// into the live active window (Eq. 1-6 on rows R-m..R-1, then the CAS filter of every row that
// reached R-m and its registration into the obstacle map), timed scan by scan. The scans are
// analytic (mapper/synthetic_scans.hpp): the paper's vehicle geometry (0.6 m, 11 deg down) at
// 1 m/s past boxes, 181 beams at 75 Hz. Counters p50_us / p99_us / max_us: thread CPU time per
// scan (the cost on one core); wall_p99_us: wall time, which adds other processes' share.
// The *Stages cases time what `casmap live` does per scan with each mapper mode and pre-filter:
// the scan with its own slice of poses (as the session hands it over), consensus cell heights
// (ActiveWindowConfig::consensus) and/or the sweep_jump stream (push, label the scan before,
// map it with its keep labels).
#include <benchmark/benchmark.h>

#include <algorithm>
#include <chrono>
#include <ctime>
#include <memory>
#include <vector>

#include "casmap/mapper/active_window.hpp"
#include "casmap/mapper/sweep_jump_stream.hpp"
#include "casmap/mapper/synthetic_scans.hpp"

namespace {

using namespace casmap;

mapper::SyntheticRun Run(double yaw_rate_rad_s) {
    mapper::SyntheticDrive d;
    d.duration_s = 20.0;
    d.yaw_rate_rad_s = yaw_rate_rad_s;
    for (int i = 0; i < 20; ++i) {
        const double x = 3.0 + 0.9 * i;
        d.boxes.push_back({x, x + 0.3, -1.5 + 0.1 * i, -1.2 + 0.1 * i, 0.05 + 0.01 * i});
    }
    d.spike_every = 37;
    return mapper::BuildSyntheticRun(d);
}

double ThreadCpuUs() {
    timespec t{};
    clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
    return static_cast<double>(t.tv_sec) * 1e6 + static_cast<double>(t.tv_nsec) * 1e-3;
}

double At(const std::vector<double>& v, double q) {
    return v[std::min(v.size() - 1, static_cast<std::size_t>(q * static_cast<double>(v.size())))];
}

void Report(benchmark::State& state, std::vector<double>& us, std::vector<double>& wall_us) {
    std::sort(us.begin(), us.end());
    std::sort(wall_us.begin(), wall_us.end());
    state.counters["p50_us"] = At(us, 0.50);
    state.counters["p99_us"] = At(us, 0.99);
    state.counters["max_us"] = us.back();
    state.counters["wall_p99_us"] = At(wall_us, 0.99);
    state.SetItemsProcessed(state.iterations());
}

void ScanLoop(benchmark::State& state, const mapper::SyntheticRun& run) {
    std::unique_ptr<mapper::ActiveWindow> w;
    std::size_t next = run.scans.size();
    std::vector<double> us;       // thread CPU time per scan: the cost on one core
    std::vector<double> wall_us;  // wall time: adds whatever else the machine runs
    us.reserve(1 << 16);
    wall_us.reserve(1 << 16);
    for (auto _ : state) {
        if (next == run.scans.size()) {  // start the drive again with a fresh window
            state.PauseTiming();
            w = std::make_unique<mapper::ActiveWindow>(mapper::ActiveWindowConfig{});
            next = 0;
            state.ResumeTiming();
        }
        const double c0 = ThreadCpuUs();
        const auto t0 = std::chrono::steady_clock::now();
        const auto rows = w->AddScan(run.scans[next++], run.poses);
        const auto t1 = std::chrono::steady_clock::now();
        const double c1 = ThreadCpuUs();
        benchmark::DoNotOptimize(rows.data());
        us.push_back(c1 - c0);
        wall_us.push_back(std::chrono::duration<double, std::micro>(t1 - t0).count());
    }
    Report(state, us, wall_us);
}

// Each scan's poses as the live session hands them over: from one scan period before beam 0 to
// the first sample at or after the last beam.
std::vector<core::Trajectory> Slices(const mapper::SyntheticRun& run) {
    const std::vector<core::TimedPose>& p = run.poses.samples();
    const auto by_stamp = [](const core::TimedPose& a, double t) { return a.stamp_s < t; };
    std::vector<core::Trajectory> out;
    for (const core::Scan& s : run.scans) {
        auto first = std::lower_bound(p.begin(), p.end(), s.stamp_s - 1.0 / 75.0, by_stamp);
        first = first == p.begin() ? first : first - 1;
        auto last = std::lower_bound(p.begin(), p.end(), s.BeamTime(s.beams.size() - 1), by_stamp);
        last = last == p.end() ? last : last + 1;
        out.emplace_back(std::vector<core::TimedPose>(first, last));
    }
    return out;
}

// One live scan: consensus and/or sweep_jump (range(0), range(1): 0 off, 1 on).
void BM_ActiveWindowScanStages(benchmark::State& state) {
    static const mapper::SyntheticRun run = Run(0.0);
    static const std::vector<core::Trajectory> slices = Slices(run);
    const bool consensus = state.range(0) != 0;
    const bool sweep_jump = state.range(1) != 0;
    mapper::ActiveWindowConfig config;
    if (consensus) {
        config.consensus = mapper::ConsensusConfig{};
    }
    std::unique_ptr<mapper::ActiveWindow> w;
    std::unique_ptr<mapper::SweepJumpStream> stream;
    std::size_t next = run.scans.size();
    std::vector<double> us;
    std::vector<double> wall_us;
    us.reserve(1 << 16);
    wall_us.reserve(1 << 16);
    for (auto _ : state) {
        if (next == run.scans.size()) {
            state.PauseTiming();
            w = std::make_unique<mapper::ActiveWindow>(config);
            stream = std::make_unique<mapper::SweepJumpStream>(mapper::SweepJumpConfig{});
            next = 0;
            state.ResumeTiming();
        }
        const double c0 = ThreadCpuUs();
        const auto t0 = std::chrono::steady_clock::now();
        if (sweep_jump) {
            stream->Push(run.scans[next], slices[next]);
            while (const auto l = stream->Pop()) {
                benchmark::DoNotOptimize(w->AddScan(l->scan, l->poses, l->keep).data());
            }
        } else {
            benchmark::DoNotOptimize(w->AddScan(run.scans[next], slices[next]).data());
        }
        ++next;
        const auto t1 = std::chrono::steady_clock::now();
        const double c1 = ThreadCpuUs();
        us.push_back(c1 - c0);
        wall_us.push_back(std::chrono::duration<double, std::micro>(t1 - t0).count());
    }
    Report(state, us, wall_us);
}
BENCHMARK(BM_ActiveWindowScanStages)
    ->ArgNames({"consensus", "sweep_jump"})
    ->Args({0, 0})
    ->Args({1, 0})
    ->Args({0, 1})
    ->Args({1, 1})
    ->Unit(benchmark::kMicrosecond)
    ->Iterations(20000);

void BM_ActiveWindowScan(benchmark::State& state) {
    static const mapper::SyntheticRun run = Run(0.0);
    ScanLoop(state, run);
}
BENCHMARK(BM_ActiveWindowScan)->Unit(benchmark::kMicrosecond)->Iterations(20000);

// Turning at 10 deg/s: the window re-anchors (resamples) every 0.5 s.
void BM_ActiveWindowScanTurning(benchmark::State& state) {
    static const mapper::SyntheticRun run = Run(0.1745);
    ScanLoop(state, run);
}
BENCHMARK(BM_ActiveWindowScanTurning)->Unit(benchmark::kMicrosecond)->Iterations(20000);

}  // namespace

BENCHMARK_MAIN();
