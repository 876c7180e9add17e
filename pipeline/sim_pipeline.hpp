#pragma once

// Simulated runs for `casmap simulate`, `bench` and `sweep` (simulator builds only): scene +
// rig + motion + seed -> scans with truth labels, poses, the ground-truth map and the
// effective configuration, as io::RunData.

#include <cstdint>
#include <optional>
#include <string>

#include "casmap/core/grid.hpp"
#include "casmap/core/progress.hpp"
#include "casmap/core/scene.hpp"
#include "casmap/io/run_file.hpp"
#include "casmap/rig/pose_error.hpp"
#include "casmap/rig/table.hpp"
#include "casmap/rig/vehicle.hpp"
#include "casmap/sensor_models/lms200_config.hpp"
#include "casmap/sim/world.hpp"

namespace casmap::pipeline {

/// The scene layout of scenes/courses/*.yaml: the paper's N = 200 x M = 80 cells of 25 mm,
/// x in [1, 6) m, y in [-1, 1) m.
[[nodiscard]] rig::CourseConfig PaperCourse();

/// Everything a simulated run depends on, resolved from flags and files.
struct SimSetup {
    std::string scene_path;
    std::string motion_name = "T";  // T, TR, TP, TRP or vehicle
    bool vehicle = false;
    rig::Motion motion = rig::Motion::kT;
    rig::TableConfig table;
    rig::VehicleConfig vehicle_config;
    sensor_models::Lms200Config lms;
    std::string sensor_path;  // the --sensor file lms came from; empty: the defaults
    rig::PoseErrorConfig pose_error;
    std::uint64_t seed = 1;
    core::GridGeometry grid;  // the map grid: the course region (truth and maps)
    std::string rig_path;
};

/// Flags of `casmap simulate` (and the per-run settings of bench and sweep).
struct SimFlags {
    std::string scene_path;
    std::string motion = "T";
    std::optional<double> speed_m_s;
    std::uint64_t seed = 1;
    std::string rig_path;                 // optional rig YAML
    std::string sensor_path;              // optional LMS 200 YAML (io/sensor_config.hpp)
    std::vector<std::string> pose_error;  // NAME=VALUE settings of rig::PoseErrorConfig
};

/// Resolves flags and the rig file into a validated setup; InputError naming the flag, file
/// and field otherwise (unknown motion, speed beyond the rig's limit, ...).
[[nodiscard]] SimSetup ResolveSimSetup(const SimFlags& flags);

/// The effective configuration as YAML text (written into the run file and beside outputs).
/// Independent of the thread count, so runs stay byte-identical.
[[nodiscard]] std::string EffectiveConfigYaml(const SimSetup& setup);

/// The sensor trajectory of the rig (true poses).
[[nodiscard]] core::Trajectory RigTrajectory(const SimSetup& setup, const core::Scene& scene);

struct SimulatedRun {
    io::RunData run;              // poses = what the mapper sees (with pose error, if any)
    core::Trajectory true_poses;  // what the simulator used
};

/// How SimulateRun runs (not what it simulates: results never depend on these).
struct SimulateRunOptions {
    int threads = 0;            // 0 = all cores
    core::ProgressFn progress;  // once per finished scan; may be empty
    bool truth = true;          // also compute the ground truth on setup.grid
};

/// Simulates every full scan `true_poses` covers (scan k at StartTime + k * scan period, scan
/// index k) with sim::Simulate, plus the ground truth on setup.grid unless options.truth is
/// false. Identical output at any thread count. `true_poses` ends in the result's true_poses:
/// callers done with their trajectory move it in (a 201 s table run's is 13 MB).
[[nodiscard]] SimulatedRun SimulateRun(const SimSetup& setup,
                                       const core::Scene& scene,
                                       const sim::World& world,
                                       core::Trajectory true_poses,
                                       const SimulateRunOptions& options = {});

/// Number of scans SimulateRun will produce (for progress bars).
[[nodiscard]] std::size_t ScanCount(const SimSetup& setup, const core::Trajectory& trajectory);

}  // namespace casmap::pipeline
