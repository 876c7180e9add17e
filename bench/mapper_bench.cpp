// Mapper benchmarks (DESIGN.md budgets): the mapper at >= 25 million beams/s per core, the same
// on a 6 s and a 60 s run (cost per beam independent of the run's length); the CAS filter at
// <= 0.25 x OpenCV's 5x5 median on the same realistic 200 x 200 map pair, one thread.
#include <benchmark/benchmark.h>

#include <cmath>
#include <numbers>
#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>
#include <vector>

#include "casmap/mapper/filters.hpp"
#include "casmap/mapper/sweep_jump.hpp"
#include "casmap/mapper/synthetic_map.hpp"
#include "casmap/mapper/terrain_mapper.hpp"

namespace {

using namespace casmap;

constexpr double kDeg = std::numbers::pi / 180.0;

// The paper's table: 1 m/s along x, pitch 30 deg down with a 37.5 deg/s roll oscillation,
// 1 kHz pose samples for `seconds`; LMS 200 scans of 181 beams at 75 Hz. The table runs back
// and forth over the same 6 m (as repeated passes do), so a long run maps onto the grid too.
core::Trajectory TableTrajectory(int seconds) {
    std::vector<core::TimedPose> samples;
    for (int n = 0; n <= 1000 * seconds; ++n) {
        const double t = n * 1e-3;
        const double roll = 15 * kDeg * std::sin(2.5 * t);
        const double lap = std::fmod(t, 12.0);
        const double x = lap < 6.0 ? lap : 12.0 - lap;
        samples.push_back({t, core::PoseFromXyzRpy(Eigen::Vector3d(x, 0.0, 1.0),
                                                   Eigen::Vector3d(roll, 30 * kDeg, 0.0))});
    }
    return core::Trajectory(samples);
}

std::vector<core::Scan> TableScans(int count) {
    std::vector<core::Scan> scans;
    for (int n = 0; n < count; ++n) {
        core::Scan s;
        s.stamp_s = 0.05 + n / 75.0;
        s.start_angle_rad = -90 * kDeg;
        s.angle_step_rad = kDeg;
        s.beam_period_s = (1.0 / 75.0) / 360.0;
        s.beams.resize(181);
        for (std::size_t i = 0; i < s.beams.size(); ++i) {
            const double a = s.BeamAngle(i);
            // Roughly the floor range of a 1 m high sensor pitched 30 deg, clipped at 4 m.
            const double r = std::min(4.0, 2.0 / std::max(0.2, std::cos(a)));
            s.beams[i] = core::Beam{
                static_cast<float>(r + 0.01 * std::sin(0.7 * n + static_cast<double>(i))),
                i % 23 == 0 ? core::BeamStatus::kNoReturn : core::BeamStatus::kOk, 0};
        }
        scans.push_back(std::move(s));
    }
    return scans;
}

// Maps every scan of a run of state.range(0) seconds (75 scans/s from t = 0.05 s to the end):
// beams/s must not depend on the length. With `consensus`, the consensus cell height
// (mapper/consensus.hpp) beside the paper's Eq. 6.
void MapperIngest(benchmark::State& state, bool consensus) {
    const auto seconds = static_cast<int>(state.range(0));
    const core::Trajectory trajectory = TableTrajectory(seconds);
    const std::vector<core::Scan> scans = TableScans(75 * seconds - 5);
    mapper::TerrainMapperConfig cfg;
    cfg.grid = core::GridGeometry{-1.0, -4.0, 0.025, 400, 320};
    if (consensus) {
        cfg.consensus = mapper::ConsensusConfig{};
    }
    mapper::TerrainMapper m(cfg);
    std::int64_t beams = 0;
    for (auto _ : state) {
        for (const core::Scan& s : scans) {
            m.AddScan(s, trajectory);
            beams += static_cast<std::int64_t>(s.beams.size());
        }
        benchmark::DoNotOptimize(m.elevation().data.data());
    }
    state.SetItemsProcessed(beams);
    state.counters["time_per_beam"] = benchmark::Counter(
        static_cast<double>(beams), benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
}
void BM_MapperIngest(benchmark::State& state) { MapperIngest(state, false); }
BENCHMARK(BM_MapperIngest)->Arg(6)->Arg(60)->Unit(benchmark::kMillisecond);

void BM_MapperIngestConsensus(benchmark::State& state) { MapperIngest(state, true); }
BENCHMARK(BM_MapperIngestConsensus)->Arg(6)->Arg(60)->Unit(benchmark::kMillisecond);

// The sweep-jump pre-filter's labels for the same runs (every beam to world coordinates once,
// then three scans compared): its cost per beam beside the mapper's.
void BM_SweepJumpLabels(benchmark::State& state) {
    const auto seconds = static_cast<int>(state.range(0));
    const core::Trajectory trajectory = TableTrajectory(seconds);
    const std::vector<core::Scan> scans = TableScans(75 * seconds - 5);
    std::int64_t beams = 0;
    for (auto _ : state) {
        const auto labels = mapper::SweepJumpLabels(scans, trajectory, {});
        benchmark::DoNotOptimize(labels.data());
        beams += static_cast<std::int64_t>(scans.size() * scans[0].beams.size());
    }
    state.SetItemsProcessed(beams);
    state.counters["time_per_beam"] = benchmark::Counter(
        static_cast<double>(beams), benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
}
BENCHMARK(BM_SweepJumpLabels)->Arg(6)->Arg(60)->Unit(benchmark::kMillisecond);

const mapper::SyntheticMap& Map() {
    static const mapper::SyntheticMap map = mapper::BuildSyntheticMap({});
    return map;
}

void BM_CasFilter(benchmark::State& state) {
    cv::setNumThreads(1);
    const mapper::SyntheticMap& m = Map();
    const mapper::CasParams params;
    mapper::FilterResult r;  // reused, as cv::medianBlur below reuses its dst
    for (auto _ : state) {
        mapper::CasFilterInto(m.elevation, m.certainty, params, r);
        benchmark::DoNotOptimize(r.elevation.data.data());
    }
    state.SetItemsProcessed(state.iterations() * static_cast<std::int64_t>(m.truth.data.size()));
}
BENCHMARK(BM_CasFilter)->Unit(benchmark::kMicrosecond);

void BM_OpenCvMedian5(benchmark::State& state) {
    cv::setNumThreads(1);
    const mapper::SyntheticMap& m = Map();
    const cv::Mat src(m.elevation.rows, m.elevation.cols, CV_32F,
                      const_cast<float*>(m.elevation.data.data()));
    cv::Mat dst;
    for (auto _ : state) {
        cv::medianBlur(src, dst, 5);
        benchmark::DoNotOptimize(dst.data);
    }
    state.SetItemsProcessed(state.iterations() * static_cast<std::int64_t>(src.total()));
}
BENCHMARK(BM_OpenCvMedian5)->Unit(benchmark::kMicrosecond);

}  // namespace

BENCHMARK_MAIN();
