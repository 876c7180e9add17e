// End-to-end simulator throughput (issue 11, "Speed"): the `casmap simulate` path as library
// calls, one core: scene load + Embree BVH, the Bullet table at 1 kHz (pipeline::RigTrajectory),
// ray casting + sensor model (pipeline::SimulateRun without truth), the ground truth, the HDF5
// run file. Counters:
//   realtime_factor  simulated seconds / process CPU seconds of the whole path (per core)
//   sim_s            simulated seconds (trajectory span)
//   <stage>_pct      share of the CPU time per stage: setup (scene + BVH), rig, cast (sub-ray
//                    tracing + sensor model), truth, write (HDF5 + zlib)
//   trace_pct        share of the same pulses traced without the sensor model (measured
//                    separately, not part of the total): cast_pct - trace_pct ~ sensor model
//   cast_rt          real-time factor of the cast stage alone
// Arguments: motion (0 = T, 1 = TRP), speed (mm/s: 1000 -> 6 s run, 100 -> 51 s, 25 -> 201 s),
// scene variant (0 = course 4; 1/2/3 = course 4 on a heightfield floor of 10/5/2.5 cm cells;
// 4/5 = course 4 plus 40/160 extra boxes and poles in the course region).
#include <benchmark/benchmark.h>
#include <unistd.h>

#include <ctime>
#include <filesystem>
#include <span>
#include <string>
#include <utility>
#include <vector>

#include "casmap/core/scene.hpp"
#include "casmap/core/trajectory.hpp"
#include "casmap/io/run_file.hpp"
#include "casmap/io/scene_file.hpp"
#include "casmap/pipeline/sim_pipeline.hpp"
#include "casmap/scenegen/heightfield.hpp"
#include "casmap/scenegen/random.hpp"
#include "casmap/sensor_models/lms200_model.hpp"
#include "casmap/sim/ground_truth.hpp"
#include "casmap/sim/simulator.hpp"
#include "casmap/sim/world.hpp"

namespace {

namespace fs = std::filesystem;
using casmap::core::Scene;

double CpuSeconds() {
    timespec ts{};
    clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts);
    return static_cast<double>(ts.tv_sec) + 1e-9 * static_cast<double>(ts.tv_nsec);
}

std::string Course4Path() {
    return (fs::path(CASMAP_SOURCE_DIR) / "scenes/courses/course04.yaml").string();
}

// Course 4 with its floor box replaced by a heightfield mesh (gentle noise) of `cell_m`.
void AddTerrainFloor(Scene& scene, double cell_m) {
    casmap::scenegen::Heightfield field = casmap::scenegen::Heightfield::Flat(
        Eigen::Vector2d(-4.0, -4.0), Eigen::Vector2d(10.0, 4.0), cell_m);
    casmap::scenegen::Rng rng(7);
    casmap::scenegen::AddFractalNoise(field, 0.01, 1.0, 3, rng);
    casmap::core::SceneObject floor;
    floor.name = "terrain";
    floor.shape = casmap::scenegen::ToMesh(field);
    floor.reflectivity = 0.3;
    floor.terrain = true;
    scene.objects[0] = std::move(floor);  // course 4's object 0 is its floor box
}

// `count` extra objects (alternately boxes and poles) on a grid over the course region.
void AddClutter(Scene& scene, int count) {
    casmap::scenegen::Rng rng(11);
    const int cols = 8;
    const int rows = (count + cols - 1) / cols;
    for (int k = 0; k < count; ++k) {
        const double x = 1.2 + 4.6 * (static_cast<double>(k / cols) + 0.5) / rows;
        const double y = -0.9 + 1.8 * (static_cast<double>(k % cols) + 0.5) / cols;
        casmap::core::SceneObject o;
        o.name = "clutter" + std::to_string(k);
        const double h = rng.Draw({0.05, 0.3});
        if (k % 2 == 0) {
            o.shape = casmap::core::BoxShape{Eigen::Vector3d(0.04, 0.04, h)};
        } else {
            o.shape = casmap::core::CylinderShape{rng.Draw({0.003, 0.02}), h};
        }
        o.world_T_object = casmap::core::PoseFromXyzRpy({x, y, 0.5 * h}, {0.0, 0.0, 0.0});
        o.reflectivity = rng.Draw({0.05, 0.9});
        scene.objects.push_back(std::move(o));
    }
}

Scene LoadVariant(int variant) {
    Scene scene = casmap::io::LoadScene(Course4Path());
    switch (variant) {
        case 1:
            AddTerrainFloor(scene, 0.10);
            break;
        case 2:
            AddTerrainFloor(scene, 0.05);
            break;
        case 3:
            AddTerrainFloor(scene, 0.025);
            break;
        case 4:
            AddClutter(scene, 40);
            break;
        case 5:
            AddClutter(scene, 160);
            break;
        default:
            break;
    }
    return scene;
}

std::size_t Triangles(const Scene& scene) {
    std::size_t n = 0;
    for (const auto& o : scene.objects) {
        if (const auto* m = std::get_if<casmap::core::MeshShape>(&o.shape)) {
            n += m->triangles.size();
        } else if (std::holds_alternative<casmap::core::BoxShape>(o.shape)) {
            n += 12;
        }
    }
    return n;
}

// Traces every pulse of every scan the run casts as the simulator does (one ray batch per
// scan), without the sensor model.
void TraceOnly(const casmap::sim::World& world,
               const casmap::sensor_models::Lms200Model& model,
               const casmap::core::Trajectory& poses,
               std::size_t scans) {
    const std::size_t n = model.BeamCount();
    const std::size_t m = model.SubrayCount();
    casmap::sim::RayBatch rays;
    casmap::sim::HitBatch hits;
    rays.tmax_m = static_cast<float>(model.TraceRangeM());
    for (std::size_t k = 0; k < scans; ++k) {
        const casmap::core::Scan scan =
            model.MakeScan(poses.StartTime() + static_cast<double>(k) * model.ScanPeriodS());
        rays.Resize(n * m);
        for (std::size_t i = 0; i < n; ++i) {
            const auto frame = model.PulseBasis(k, i, *poses.PoseAt(scan.BeamTime(i)));
            model.ForEachSubray(
                frame, [&](std::size_t j, const Eigen::Vector3d& o, const Eigen::Vector3d& d) {
                    rays.Set(i * m + j, o.cast<float>(), d.cast<float>());
                });
        }
        world.CastBatch(rays, hits);
        benchmark::DoNotOptimize(hits.distance_m.data());
    }
}

void BM_SimulateEndToEnd(benchmark::State& state) {
    const bool trp = state.range(0) == 1;
    const double speed_m_s = static_cast<double>(state.range(1)) / 1000.0;
    const auto variant = static_cast<int>(state.range(2));
    casmap::pipeline::SimFlags flags;
    flags.scene_path = Course4Path();
    flags.motion = trp ? "TRP" : "T";
    flags.speed_m_s = speed_m_s;
    flags.seed = 1;
    const fs::path out =
        fs::temp_directory_path() / ("casmap_sim_e2e_" + std::to_string(::getpid()) + ".h5");
    double setup = 0, rig = 0, cast = 0, truth = 0, write = 0, trace = 0, sim_s = 0;
    std::size_t triangles = 0;
    for (auto _ : state) {
        const double t0 = CpuSeconds();
        const casmap::pipeline::SimSetup setup_cfg = casmap::pipeline::ResolveSimSetup(flags);
        const Scene scene = LoadVariant(variant);
        const casmap::sim::World world(scene);
        const double t1 = CpuSeconds();
        casmap::core::Trajectory rig_poses = casmap::pipeline::RigTrajectory(setup_cfg, scene);
        const double t2 = CpuSeconds();
        casmap::pipeline::SimulateRunOptions options;
        options.threads = 1;
        options.truth = false;
        casmap::pipeline::SimulatedRun run =
            casmap::pipeline::SimulateRun(setup_cfg, scene, world, std::move(rig_poses), options);
        const casmap::core::Trajectory& poses = run.true_poses;
        const double t3 = CpuSeconds();
        run.run.maps.truth_m = casmap::sim::GroundTruthElevation(scene, setup_cfg.grid, 1);
        const double t4 = CpuSeconds();
        casmap::io::WriteRunFile(out, run.run);
        const double t5 = CpuSeconds();
        state.PauseTiming();
        const casmap::sensor_models::Lms200Model model(setup_cfg.lms, setup_cfg.seed);
        const double t6 = CpuSeconds();
        TraceOnly(world, model, poses, run.run.scans.size());
        trace += CpuSeconds() - t6;
        state.ResumeTiming();
        setup += t1 - t0;
        rig += t2 - t1;
        cast += t3 - t2;
        truth += t4 - t3;
        write += t5 - t4;
        sim_s += poses.EndTime() - poses.StartTime();
        triangles = Triangles(scene);
    }
    fs::remove(out);
    const double total = setup + rig + cast + truth + write;
    state.counters["realtime_factor"] = sim_s / total;
    state.counters["cast_rt"] = sim_s / cast;
    state.counters["sim_s"] = sim_s / static_cast<double>(state.iterations());
    state.counters["setup_pct"] = 100.0 * setup / total;
    state.counters["rig_pct"] = 100.0 * rig / total;
    state.counters["cast_pct"] = 100.0 * cast / total;
    state.counters["trace_pct"] = 100.0 * trace / total;
    state.counters["truth_pct"] = 100.0 * truth / total;
    state.counters["write_pct"] = 100.0 * write / total;
    state.counters["triangles"] = static_cast<double>(triangles);
}

// Run length (T and TRP on course 4), then scene size (51 s runs of T).
BENCHMARK(BM_SimulateEndToEnd)
    ->ArgNames({"trp", "speed_mm_s", "scene"})
    ->Args({0, 1000, 0})
    ->Args({0, 100, 0})
    ->Args({0, 25, 0})
    ->Args({1, 100, 0})
    ->Args({1, 25, 0})
    ->Args({0, 100, 1})
    ->Args({0, 100, 2})
    ->Args({0, 100, 3})
    ->Args({0, 100, 4})
    ->Args({0, 100, 5})
    ->Iterations(1)
    ->MeasureProcessCPUTime()
    ->Unit(benchmark::kMillisecond);

// The Bullet table alone (the rig stage), T or TRP at `speed` mm/s: simulated s per CPU s.
void BM_TableRig(benchmark::State& state) {
    casmap::pipeline::SimFlags flags;
    flags.scene_path = Course4Path();
    flags.motion = state.range(0) == 1 ? "TRP" : "T";
    flags.speed_m_s = static_cast<double>(state.range(1)) / 1000.0;
    const casmap::pipeline::SimSetup setup = casmap::pipeline::ResolveSimSetup(flags);
    const Scene scene;
    double sim_s = 0.0;
    for (auto _ : state) {
        const casmap::core::Trajectory poses = casmap::pipeline::RigTrajectory(setup, scene);
        sim_s += poses.EndTime() - poses.StartTime();
        benchmark::DoNotOptimize(poses);
    }
    state.counters["realtime_factor"] = benchmark::Counter(sim_s, benchmark::Counter::kIsRate);
}
BENCHMARK(BM_TableRig)
    ->ArgNames({"trp", "speed_mm_s"})
    ->Args({0, 25})
    ->Args({1, 25})
    ->MeasureProcessCPUTime()
    ->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
