// casmap simulate --scene FILE --motion T|TR|TP|TRP|vehicle [--speed M_S] [--seed N]
//                 [--rig RIG.yaml] [--sensor LMS200.yaml] [--pose-error NAME=VALUE]...
//                 --out RUN.h5
// One simulated run -> one HDF5 run file (scans, raw values, statuses, truth labels, poses, the
// ground-truth map of the course region, the effective configuration and seed), plus
// RUN.config.yaml beside it. Byte-identical output at any --threads.
#include <cstdio>
#include <filesystem>
#include <memory>
#include <string>

#include "apps/casmap/commands.hpp"
#include "apps/casmap/flag_names.hpp"
#include "apps/casmap/progress_bar.hpp"
#include "casmap/core/input_error.hpp"
#include "casmap/io/atomic_file.hpp"
#include "casmap/io/output_set.hpp"
#include "casmap/io/run_file.hpp"
#include "casmap/io/scene_file.hpp"
#include "casmap/pipeline/sim_pipeline.hpp"

namespace casmap::app {
namespace {
namespace fs = std::filesystem;

struct SimulateOptions {
    pipeline::SimFlags flags;
    double speed_m_s = 0.0;
    std::string out;
};

const FlagNames kFlags = {
    {"motion", "--motion"}, {"speed_m_s", "--speed"}, {"pose_error", "--pose-error"}};

void RunSimulate(SimulateOptions& opt, const CommonOptions& common, bool speed_given) {
    if (speed_given) {
        opt.flags.speed_m_s = opt.speed_m_s;
    }
    // Both outputs are checked before minutes of work and published together at the end,
    // the config first: a kill leaves either the old pair or the new config beside the old run.
    io::OutputSet outputs;
    const fs::path config_tmp = outputs.AddFile(opt.out + ".config.yaml", "--out (config)");
    const fs::path run_tmp = outputs.AddFile(opt.out, "--out");
    pipeline::SimSetup setup;
    WithFlagNames(kFlags, [&] { setup = pipeline::ResolveSimSetup(opt.flags); });
    const core::Scene scene = io::LoadScene(setup.scene_path);
    const sim::World world(scene);
    pipeline::SimulatedRun result;
    {
        ProgressBar bar("simulate");
        pipeline::SimulateRunOptions options;
        options.threads = common.threads;
        options.progress = bar.Fn();
        result = pipeline::SimulateRun(setup, scene, world, pipeline::RigTrajectory(setup, scene),
                                       options);
    }
    const core::Trajectory& poses = result.true_poses;
    io::WriteTextAtomically(config_tmp, result.run.config_yaml);
    io::WriteRunFile(run_tmp, result.run);
    outputs.Publish();
    std::printf("simulated %zu scans (%.2f s, %zu poses) of %s, motion %s, seed %llu -> %s\n",
                result.run.scans.size(), poses.empty() ? 0.0 : poses.EndTime() - poses.StartTime(),
                poses.size(), setup.scene_path.c_str(), setup.motion_name.c_str(),
                static_cast<unsigned long long>(setup.seed), opt.out.c_str());
}

}  // namespace

void AddSimulateCommand(CLI::App& app, CommonOptions& common) {
    auto opt = std::make_shared<SimulateOptions>();
    CLI::App* sub = app.add_subcommand(
        "simulate", "Simulate one run of the LMS 200 on a rig over a scene into an HDF5 run file");
    sub->add_option("--scene", opt->flags.scene_path, "scene YAML")->required();
    sub->add_option("--motion", opt->flags.motion, "T, TR, TP, TRP (table) or vehicle")->required();
    CLI::Option* speed =
        sub->add_option("--speed", opt->speed_m_s, "cruise speed (m/s; table <= 1, vehicle <= 3)");
    sub->add_option("--seed", opt->flags.seed, "simulator seed")->capture_default_str();
    sub->add_option("--rig", opt->flags.rig_path, "rig YAML (table or vehicle settings)");
    sub->add_option("--sensor", opt->flags.sensor_path,
                    "LMS 200 YAML (config/lms200.yaml; default: the built-in config)");
    sub->add_option("--pose-error", opt->flags.pose_error,
                    "pose-estimate error NAME=VALUE (position_bias_m=X,Y,Z, attitude_bias_deg=..., "
                    "position_jitter_m=..., ...); repeatable");
    sub->add_option("--out", opt->out, "run file to write (HDF5)")->required();
    AddThreadsOption(sub, common);
    sub->callback([opt, speed, &common] { RunSimulate(*opt, common, speed->count() > 0); });
}

}  // namespace casmap::app
