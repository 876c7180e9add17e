// Simulator throughput (issue 3): full LMS 200 scans with the default sensor model on obstacle
// course 4, the sensor moving as in test T, against the same sub-rays traced one rtcIntersect1
// call each. Both count traced rays as items; BM_SimulateScan also reports realtime_factor
// (simulated scanner seconds per wall-clock second). One thread.
#include <benchmark/benchmark.h>

#include <filesystem>
#include <string>
#include <vector>

#include "casmap/core/pose.hpp"
#include "casmap/core/scene.hpp"
#include "casmap/core/trajectory.hpp"
#include "casmap/io/scene_file.hpp"
#include "casmap/sensor_models/lms200_model.hpp"
#include "casmap/sim/simulator.hpp"
#include "casmap/sim/world.hpp"

namespace {

using casmap::core::Pose;
using casmap::sensor_models::Lms200Config;
using casmap::sensor_models::Lms200Model;

constexpr double kDeg = 3.14159265358979323846 / 180.0;
// Test T: linear motion along +x at 1 m/s for 5 s (375 scans at 75 Hz) with the rig's default
// mount (rig/table.hpp: sensor 1.0 m above the floor, 40 deg nose down).
constexpr double kSpeed = 1.0;
constexpr double kDuration = 5.0;
constexpr double kHeight = 1.0;
constexpr double kPitchDeg = 40.0;

casmap::core::Scene Course4() {
    const std::filesystem::path file =
        std::filesystem::path(CASMAP_SOURCE_DIR) / "scenes/courses/course04.yaml";
    return casmap::io::LoadScene(file.string());
}

casmap::core::Trajectory TestT() {
    std::vector<casmap::core::TimedPose> poses;
    for (int k = 0; k <= 50; ++k) {
        const double t = kDuration * k / 50.0;
        poses.push_back({t, casmap::core::PoseFromXyzRpy({kSpeed * t, 0.0, kHeight},
                                                         {0.0, kPitchDeg * kDeg, 0.0})});
    }
    return casmap::core::Trajectory(std::move(poses));
}

struct Fixture {
    casmap::sim::World world{Course4()};
    Lms200Model model{Lms200Config{}, 1};
    casmap::core::Trajectory trajectory = TestT();
    std::size_t scans = static_cast<std::size_t>(kDuration / model.ScanPeriodS()) - 1;
};

Fixture& Shared() {
    static Fixture f;
    return f;
}

void BM_SimulateScan(benchmark::State& state) {
    Fixture& f = Shared();
    std::size_t k = 0;
    std::int64_t rays = 0;
    for (auto _ : state) {
        const double stamp = static_cast<double>(k) * f.model.ScanPeriodS();
        auto r = casmap::sim::CastScan(f.world, f.model, f.trajectory, stamp, k);
        benchmark::DoNotOptimize(r);
        rays += static_cast<std::int64_t>(f.model.BeamCount() * f.model.SubrayCount());
        k = (k + 1) % f.scans;
    }
    state.SetItemsProcessed(rays);
    state.counters["realtime_factor"] =
        benchmark::Counter(static_cast<double>(state.iterations()) * f.model.ScanPeriodS(),
                           benchmark::Counter::kIsRate);
}
BENCHMARK(BM_SimulateScan)->Unit(benchmark::kMicrosecond);

// The same sub-rays (same poses, same per-pulse pattern rotations), one CastOne each.
void BM_EmbreeRaw(benchmark::State& state) {
    Fixture& f = Shared();
    std::vector<casmap::sim::Ray> rays;
    std::vector<casmap::sensor_models::Subray> sub(f.model.SubrayCount());
    for (std::size_t k = 0; k < f.scans; ++k) {
        const casmap::core::Scan scan =
            f.model.MakeScan(static_cast<double>(k) * f.model.ScanPeriodS());
        for (std::size_t i = 0; i < f.model.BeamCount(); ++i) {
            const Pose pose = *f.trajectory.PoseAt(scan.BeamTime(i));
            f.model.PulseSubrays(k, i, sub);
            for (const auto& s : sub) {
                casmap::sim::Ray ray;
                ray.origin = (pose * s.origin).cast<float>();
                ray.direction = (pose.rotation * s.direction).cast<float>();
                ray.tmax_m = static_cast<float>(f.model.TraceRangeM());
                rays.push_back(ray);
            }
        }
    }
    const std::size_t per_scan = f.model.BeamCount() * f.model.SubrayCount();
    std::size_t k = 0;
    std::int64_t traced = 0;
    for (auto _ : state) {
        for (std::size_t j = k * per_scan; j < (k + 1) * per_scan; ++j) {
            benchmark::DoNotOptimize(f.world.CastOne(rays[j]));
        }
        traced += static_cast<std::int64_t>(per_scan);
        k = (k + 1) % f.scans;
    }
    state.SetItemsProcessed(traced);
}
BENCHMARK(BM_EmbreeRaw)->Unit(benchmark::kMicrosecond);

}  // namespace

BENCHMARK_MAIN();
