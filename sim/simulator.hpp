#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "casmap/core/pose.hpp"
#include "casmap/core/progress.hpp"
#include "casmap/core/scan.hpp"
#include "casmap/core/trajectory.hpp"
#include "casmap/sensor_models/lms200_model.hpp"
#include "casmap/sim/world.hpp"

namespace casmap::sim {

/// One simulated scan and what only a simulation knows about it.
struct ScanResult {
    core::Scan scan;
    core::ScanTruth truth;
};

/// One pulse of `model` fired from `world_T_sensor` (sensor frame: x forward, y left, z up):
/// all its sub-rays traced together as one packet, then the sensor model applied.
/// pulse.beam_direction_world is filled in here.
[[nodiscard]] sensor_models::PulseResult CastPulse(const World& world,
                                                   const sensor_models::Lms200Model& model,
                                                   const core::Pose& world_T_sensor,
                                                   sensor_models::PulseContext pulse);

/// One scan whose beam 0 fires at stamp_s; every pulse is placed at the pose of its own time
/// (interleaved turns included). Throws InputError if the trajectory does not cover the scan.
[[nodiscard]] ScanResult CastScan(const World& world,
                                  const sensor_models::Lms200Model& model,
                                  const core::Trajectory& world_T_sensor,
                                  double stamp_s,
                                  std::uint64_t scan_index);

/// One scan from a fixed pose (the `casmap scan` command, tests).
[[nodiscard]] ScanResult CastScanAt(const World& world,
                                    const sensor_models::Lms200Model& model,
                                    const core::Pose& world_T_sensor,
                                    double stamp_s,
                                    std::uint64_t scan_index);

struct SimulateOptions {
    double start_s = 0.0;        // stamp of scan 0
    double period_s = 0.0;       // between scan stamps; 0 = the model's scan period
    std::size_t scan_count = 0;  // scans to simulate
    std::uint64_t first_scan_index = 0;
    int threads = 0;            // 0 = all cores; results never depend on it
    core::ProgressFn progress;  // called once per finished scan (may be empty)
};

/// Scans k = 0..scan_count-1 at start_s + k * period_s with scan index first_scan_index + k,
/// simulated in parallel; identical results at any thread count.
[[nodiscard]] std::vector<ScanResult> Simulate(const World& world,
                                               const sensor_models::Lms200Model& model,
                                               const core::Trajectory& world_T_sensor,
                                               const SimulateOptions& options);

}  // namespace casmap::sim
