// casmap serve (--scene FILE --motion T|TR|TP|TRP|vehicle [--speed M_S] [--seed N] [--rig R]
//               | --run RUN.h5) [--link PATH] [--baud N]
//               [--faults crc=P,garbage=P,drop=P,collide=P,disconnect=S] [--poses-out FILE]
//               [--eeprom FILE]
// A virtual LMS 200 on a pseudo-terminal (drivers/virtual_lms200.hpp) streaming the scans of a
// run file or of a run simulated at start-up, until the run is exhausted or SIGINT/SIGTERM.
// --baud is the power-on rate (9600 as the real unit); the client switches it. Prints the
// device path on start and one JSON line of counters on exit. --poses-out writes the run's
// poses re-stamped into the system clock of the served sweeps (docs/pose-file.md), so that
// `casmap record --poses` can give a recorded run its poses. --eeprom keeps the scanner's
// configuration (what clients write with 0x77) in a file across restarts.
#include <unistd.h>

#include <atomic>
#include <csignal>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <thread>

#include "apps/casmap/commands.hpp"
#include "casmap/core/input_error.hpp"
#include "casmap/drivers/pose_file.hpp"
#include "casmap/drivers/scan_list_source.hpp"
#include "casmap/drivers/virtual_lms200.hpp"
#include "casmap/io/atomic_file.hpp"
#include "casmap/io/run_file.hpp"
#ifdef CASMAP_WITH_SIM
#include "apps/casmap/flag_names.hpp"
#include "casmap/core/parallel.hpp"
#include "casmap/io/scene_file.hpp"
#include "casmap/pipeline/sim_pipeline.hpp"
#include "casmap/sim/world.hpp"
#endif

namespace casmap::app {
namespace {

std::atomic<bool> g_serve_stop{false};

extern "C" void OnServeSignal(int /*signal*/) { g_serve_stop = true; }

/// SIGINT/SIGTERM end serving cleanly (the link is removed) while this lives.
struct ServeSignals {
    ServeSignals() {
        g_serve_stop = false;
        std::signal(SIGINT, OnServeSignal);
        std::signal(SIGTERM, OnServeSignal);
    }
    ~ServeSignals() {
        std::signal(SIGINT, SIG_DFL);
        std::signal(SIGTERM, SIG_DFL);
    }
    ServeSignals(const ServeSignals&) = delete;
    ServeSignals& operator=(const ServeSignals&) = delete;
};

struct ServeOptions {
    std::string run;
    std::string scene;
    std::string motion;
    double speed_m_s = 0.0;
    std::uint64_t seed = 1;
    std::string rig;
    std::string link;
    int baud = 9600;
    std::string faults;
    std::string poses_out;
    std::string eeprom;
};

namespace fs = std::filesystem;

/// The folder of an output file must exist and be writable before anything is served.
void CheckOutputFile(const std::string& path, const std::string& field) {
    const fs::path p(path);
    const fs::path dir = p.has_parent_path() ? p.parent_path() : fs::path(".");
    if (p.filename().empty() || !fs::is_directory(dir)) {
        throw MakeInputError(path, field, path, "folder " + dir.string() + " does not exist");
    }
    if (fs::is_directory(p)) {
        throw MakeInputError(path, field, path, "is a folder, not a file name");
    }
    if (access(dir.c_str(), W_OK) != 0) {
        throw MakeInputError(path, field, path, "folder " + dir.string() + " is not writable");
    }
}

#ifdef CASMAP_WITH_SIM
const FlagNames kSimFlags = {{"motion", "--motion"}, {"speed_m_s", "--speed"}};
#endif

/// The run to serve: read from --run, or simulated from --scene/--motion (simulator builds).
io::RunData LoadServedRun(const ServeOptions& opt, const CommonOptions& common, bool speed_given) {
    if (!opt.run.empty()) {
        return io::ReadRunFile(opt.run);
    }
#ifdef CASMAP_WITH_SIM
    pipeline::SimFlags flags;
    flags.scene_path = opt.scene;
    flags.motion = opt.motion;
    if (speed_given) {
        flags.speed_m_s = opt.speed_m_s;
    }
    flags.seed = opt.seed;
    flags.rig_path = opt.rig;
    pipeline::SimSetup setup;
    WithFlagNames(kSimFlags, [&] { setup = pipeline::ResolveSimSetup(flags); });
    const core::Scene scene = io::LoadScene(setup.scene_path);
    const sim::World world(scene);
    const core::Trajectory poses = pipeline::RigTrajectory(setup, scene);
    pipeline::SimulateRunOptions options;
    options.threads = common.threads;
    options.truth = false;
    return pipeline::SimulateRun(setup, scene, world, poses, options).run;
#else
    (void)common;
    (void)speed_given;
    throw MakeInputError("command line", "--scene", opt.scene,
                         "this casmap was built without the simulator; use --run RUN.h5");
#endif
}

void CheckSource(const ServeOptions& opt) {
    const bool from_run = !opt.run.empty();
    const bool from_scene = !opt.scene.empty() || !opt.motion.empty();
    if (from_run == from_scene) {
        throw MakeInputError("command line", "--run / --scene", "",
                             "give either --run RUN.h5 or --scene FILE --motion M");
    }
    if (from_scene && (opt.scene.empty() || opt.motion.empty())) {
        throw MakeInputError("command line", "--scene / --motion", "",
                             "--scene and --motion go together");
    }
}

void PrintStats(const drivers::VirtualLms200Stats& s) {
    std::printf(
        "{\"scans_sent\": %llu, \"scans_skipped\": %llu, \"requests\": %llu, \"bytes\": %llu, "
        "\"crc_faults\": %llu, \"drop_faults\": %llu, \"garbage_bytes\": %llu, "
        "\"disconnects\": %llu, \"source_exhausted\": %s}\n",
        static_cast<unsigned long long>(s.scans_sent),
        static_cast<unsigned long long>(s.scans_skipped),
        static_cast<unsigned long long>(s.requests), static_cast<unsigned long long>(s.bytes_sent),
        static_cast<unsigned long long>(s.crc_faults),
        static_cast<unsigned long long>(s.drop_faults),
        static_cast<unsigned long long>(s.garbage_bytes),
        static_cast<unsigned long long>(s.disconnects), s.source_exhausted ? "true" : "false");
}

void RunServe(const ServeOptions& opt, const CommonOptions& common, bool speed_given) {
    CheckSource(opt);
    drivers::CheckLmsBaud(opt.baud, "--baud");
    if (!opt.poses_out.empty()) {
        CheckOutputFile(opt.poses_out, "--poses-out");
    }
    if (!opt.eeprom.empty()) {
        CheckOutputFile(opt.eeprom, "--eeprom");
        if (fs::exists(opt.eeprom)) {
            (void)drivers::ReadEepromFile(opt.eeprom);  // a broken file: exit 2 before serving
        }
    }
    drivers::VirtualLms200Config vc;
    vc.link_path = opt.link;
    vc.power_on_baud = opt.baud;
    vc.eeprom_path = opt.eeprom;
    if (!opt.faults.empty()) {
        vc.faults = drivers::ParseFaults(opt.faults);
    }
    const std::string what = opt.run.empty() ? opt.scene : opt.run;
    io::RunData run = LoadServedRun(opt, common, speed_given);
    if (run.format) {
        vc.config.set_measuring_mode(drivers::ModeByteOf(*run.format));
        vc.config.set_units(drivers::UnitsByteOf(*run.format));
    }
    std::vector<double> sim_stamps;
    for (const core::Scan& s : run.scans) {
        sim_stamps.push_back(s.stamp_s);
    }
    drivers::ScanListSource source(std::move(run.scans), what);
    vc.variant = source.variant();
    drivers::VirtualLms200 scanner(vc, source);

    // The first served sweep fixes the offset between run time and the system clock.
    // The first served sweep fixes the offset between run time and the system clock; the
    // file is written on another thread so the real-time loop never waits for the disk.
    std::atomic<bool> have_offset{false};
    std::atomic<bool> serving_done{false};
    double offset_s = 0.0;
    std::thread pose_writer;
    std::mutex pose_error_mutex;
    std::string pose_error;
    if (!opt.poses_out.empty()) {
        if (run.poses.empty()) {
            throw MakeInputError(what, "--poses-out", opt.poses_out, "the run holds no poses");
        }
        scanner.SetScanObserver([&](const drivers::SentScan& s) {
            if (!have_offset) {
                offset_s = s.beam0_wall_s - sim_stamps.at(s.index);
                have_offset = true;
            }
        });
        pose_writer = std::thread([&] {
            while (!have_offset && !serving_done) {
                std::this_thread::sleep_for(std::chrono::milliseconds(10));
            }
            if (have_offset) {
                try {
                    io::WriteTextAtomically(opt.poses_out,
                                            drivers::PoseFileText(run.poses, offset_s));
                } catch (const std::exception& e) {  // the folder went away while serving
                    std::lock_guard lock(pose_error_mutex);
                    pose_error = e.what();
                }
            }
        });
    }
    struct JoinOnExit {
        std::atomic<bool>& done;
        std::thread& thread;
        ~JoinOnExit() {
            done = true;
            if (thread.joinable()) {
                thread.join();
            }
        }
    } join_writer{serving_done, pose_writer};
    const ServeSignals signals;
    scanner.Open();
    std::fprintf(stderr,
                 "casmap serve: virtual LMS 200 on %s%s%s, power-on %d baud, %zu scans "
                 "(%d deg / %.2f deg)\n",
                 scanner.SlavePath().c_str(), opt.link.empty() ? "" : " linked at ",
                 opt.link.c_str(), opt.baud, source.size(), source.variant().angle_deg,
                 source.variant().resolution_cdeg / 100.0);
    std::fflush(stderr);
    scanner.Run(g_serve_stop, true);
    PrintStats(scanner.stats());
    serving_done = true;
    if (pose_writer.joinable()) {
        pose_writer.join();
    }
    std::lock_guard lock(pose_error_mutex);
    if (!pose_error.empty()) {
        throw std::runtime_error("--poses-out: " + pose_error);
    }
}

}  // namespace

void AddServeCommand(CLI::App& app, CommonOptions& common) {
    auto opt = std::make_shared<ServeOptions>();
    CLI::App* sub = app.add_subcommand(
        "serve", "Serve a virtual LMS 200 on a pseudo-terminal, streaming a run's scans");
    sub->add_option("--run", opt->run, "run file (HDF5) whose scans to serve");
    sub->add_option("--scene", opt->scene, "scene YAML to simulate (with --motion)");
    sub->add_option("--motion", opt->motion, "T, TR, TP, TRP (table) or vehicle");
    CLI::Option* speed = sub->add_option("--speed", opt->speed_m_s, "cruise speed (m/s)");
    sub->add_option("--seed", opt->seed, "simulator seed")->capture_default_str();
    sub->add_option("--rig", opt->rig, "rig YAML (table or vehicle settings)");
    sub->add_option("--link", opt->link, "stable symlink to the pseudo-terminal");
    sub->add_option("--baud", opt->baud, "power-on baud rate (9600, 19200, 38400, 500000)")
        ->capture_default_str();
    sub->add_option("--faults", opt->faults,
                    "inject faults: crc=P,garbage=P,drop=P,collide=P (per telegram),"
                    "disconnect=S (s)");
    sub->add_option("--poses-out", opt->poses_out,
                    "write the run's poses, stamped in the served sweeps' system clock");
    sub->add_option("--eeprom", opt->eeprom,
                    "file keeping the scanner's configuration across restarts (0x77 writes)");
    AddThreadsOption(sub, common);
    sub->callback([opt, speed, &common] { RunServe(*opt, common, speed->count() > 0); });
}

}  // namespace casmap::app
