#pragma once

// The simulator as a source for `casmap live` and `casmap serve` (simulator builds only): the run
// of `casmap simulate` with the same flags, simulated at start-up, then handed out scan by scan at
// the scanner's rate (`realtime`: scan i at start + (stamp_i - stamp_0) on the steady clock) or as
// fast as the session takes them.

#include <memory>

#include "casmap/core/trajectory.hpp"
#include "casmap/pipeline/live.hpp"
#include "casmap/pipeline/live_setup.hpp"
#include "casmap/pipeline/serve.hpp"
#include "casmap/pipeline/sim_pipeline.hpp"

namespace casmap::pipeline {

struct SimulatedLive {
    std::unique_ptr<LiveScanSource> scans;
    core::Trajectory poses;  // the run's poses (what a pose stream would carry)
    SimSetup setup;
};

/// Simulates the run of `flags` (InputError for bad flags, as `casmap simulate`).
[[nodiscard]] SimulatedLive MakeSimulatedSource(const SimFlags& flags, int threads, bool realtime);

/// The simulator half of MakeLiveSetup (live_setup.hpp): the run of options' scene, motion,
/// speed, seed and rig as `setup`'s scans and poses. Anchors setup.config.window at the
/// simulated map's grid origin (live cells coincide with `casmap simulate`'s), sets its m from
/// the rig's height and pitch (LookAheadRows for 0.3 m obstacles) and Eq. 8's v to the rig's
/// cruise speed (as `casmap bench` and datasets use).
void SetUpSimulatedLive(const LiveOptions& options, int threads, LiveSetup& setup);

/// The simulator half of Serve (serve.hpp): the run (scans and poses, no truth) of options'
/// scene, motion, speed, seed and rig, as `casmap simulate` makes it.
[[nodiscard]] io::RunData SimulateServedRun(const ServeOptions& options, int threads);

}  // namespace casmap::pipeline
