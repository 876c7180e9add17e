#include "casmap/pipeline/live_sim.hpp"

#include <chrono>
#include <thread>
#include <utility>
#include <vector>

#include "casmap/core/pose.hpp"
#include "casmap/io/scene_file.hpp"
#include "casmap/mapper/active_window.hpp"
#include "casmap/sim/world.hpp"

namespace casmap::pipeline {
namespace {

using Clock = std::chrono::steady_clock;

class SimulatedSource final : public LiveScanSource {
public:
    SimulatedSource(io::RunData run, bool realtime, std::string name)
        : run_(std::move(run)), realtime_(realtime), name_(std::move(name)) {}

    void Start() override { start_ = Clock::now(); }

    std::optional<core::Scan> Next(double timeout_s) override {
        if (next_ >= run_.scans.size()) {
            std::this_thread::sleep_for(std::chrono::duration<double>(std::min(timeout_s, 0.01)));
            return std::nullopt;
        }
        const core::Scan& scan = run_.scans[next_];
        if (realtime_) {
            // Beam 0 is delivered when its whole sweep would have reached the host.
            const double last_beam_s =
                scan.BeamTime(scan.beams.empty() ? 0 : scan.beams.size() - 1);
            const auto due =
                start_ + std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(
                             last_beam_s - run_.scans.front().stamp_s));
            const auto limit = Clock::now() + std::chrono::duration_cast<Clock::duration>(
                                                  std::chrono::duration<double>(timeout_s));
            if (due > limit) {
                std::this_thread::sleep_until(limit);
                return std::nullopt;
            }
            std::this_thread::sleep_until(due);
        }
        ++next_;
        return scan;
    }
    bool finished() const override { return next_ >= run_.scans.size(); }
    std::optional<core::Lms200Format> format() const override { return run_.format; }
    std::string name() const override { return name_; }

private:
    io::RunData run_;
    bool realtime_;
    std::string name_;
    std::size_t next_ = 0;
    Clock::time_point start_;
};

/// The run of `setup` as `casmap simulate` makes it, without the truth.
io::RunData SimulateWithoutTruth(const SimSetup& setup, int threads) {
    const core::Scene scene = io::LoadScene(setup.scene_path);
    const sim::World world(scene);
    SimulateRunOptions options;
    options.threads = threads;
    options.truth = false;
    return SimulateRun(setup, scene, world, RigTrajectory(setup, scene), options).run;
}

}  // namespace

SimulatedLive MakeSimulatedSource(const SimFlags& flags, int threads, bool realtime) {
    SimulatedLive live;
    live.setup = ResolveSimSetup(flags);
    SimulatedRun sim;
    sim.run = SimulateWithoutTruth(live.setup, threads);
    live.poses = sim.run.poses;
    live.scans = std::make_unique<SimulatedSource>(
        std::move(sim.run), realtime, live.setup.scene_path + " (" + live.setup.motion_name + ")");
    return live;
}

io::RunData SimulateServedRun(const ServeOptions& options, int threads) {
    SimFlags flags;
    flags.scene_path = options.scene;
    flags.motion = options.motion;
    flags.speed_m_s = options.speed_m_s;
    flags.seed = options.seed;
    flags.rig_path = options.rig;
    return SimulateWithoutTruth(ResolveSimSetup(flags), threads);
}

void SetUpSimulatedLive(const LiveOptions& options, int threads, LiveSetup& setup) {
    SimFlags flags;
    flags.scene_path = options.scene;
    flags.motion = options.motion;
    flags.speed_m_s = options.speed_m_s;
    flags.seed = options.seed;
    flags.rig_path = options.rig;
    SimulatedLive sim = MakeSimulatedSource(flags, threads, options.realtime);
    mapper::ActiveWindowConfig& window = setup.config.window;
    window.origin_x_m = sim.setup.grid.x0_m;
    window.origin_y_m = sim.setup.grid.y0_m;
    if (!sim.poses.empty()) {
        const core::Pose& p0 = sim.poses.samples().front().world_T_sensor;
        const double pitch = core::RpyFromQuaternion(p0.rotation).y();
        window.m = mapper::LookAheadRows(window, p0.translation.z(), pitch, 0.3);
    }
    window.cas.speed_m_s =
        sim.setup.vehicle ? sim.setup.vehicle_config.speed_m_s : sim.setup.table.speed_m_s;
    setup.poses = std::make_unique<TrajectoryPoseStream>(sim.poses);
    setup.scans = std::move(sim.scans);
}

}  // namespace casmap::pipeline
