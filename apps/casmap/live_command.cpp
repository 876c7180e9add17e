// casmap live (--device PATH [--baud B] (--poses FILE | --poses-socket udp:PORT|unix:PATH)
//              | --scene S --motion vehicle|T|TR|TP|TRP [--speed V] [--seed N] [--rig R]
//                [--realtime])
//             --out DIR [--window R,C] [--m M] [--obstacle-cell-m S] [--snapshot-every-s N]
//             [--duration S] [--scans N] [--timeout S] [--pose-tolerance-s T]
//             [--set NAME=VALUE]... [--view [--port P] [--host H]]
// Live mapping with the paper's active window (pipeline/live.hpp). Parses flags, prints a
// status line on a terminal (nothing otherwise) and one JSON line of counters at the end.
#include <unistd.h>

#include <atomic>
#include <csignal>
#include <cstdio>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include "apps/casmap/commands.hpp"
#include "apps/casmap/flag_names.hpp"
#include "casmap/core/input_error.hpp"
#include "casmap/core/parallel.hpp"
#include "casmap/drivers/pose_stream.hpp"
#include "casmap/drivers/virtual_lms200.hpp"
#include "casmap/pipeline/live.hpp"
#include "casmap/pipeline/map_run.hpp"
#ifdef CASMAP_WITH_SIM
#include "casmap/pipeline/live_sim.hpp"
#endif
#ifdef CASMAP_WITH_VIEW
#include "casmap/io/atomic_file.hpp"
#include "casmap/view/server.hpp"
#endif

namespace casmap::app {
namespace {

std::atomic<bool> g_live_stop{false};

extern "C" void OnLiveSignal(int /*signal*/) { g_live_stop = true; }

struct LiveSignals {
    LiveSignals() {
        g_live_stop = false;
        std::signal(SIGINT, OnLiveSignal);
        std::signal(SIGTERM, OnLiveSignal);
    }
    ~LiveSignals() {
        std::signal(SIGINT, SIG_DFL);
        std::signal(SIGTERM, SIG_DFL);
    }
    LiveSignals(const LiveSignals&) = delete;
    LiveSignals& operator=(const LiveSignals&) = delete;
};

struct LiveOptions {
    std::string device;
    int baud = 500000;
    std::string poses;
    std::string poses_socket;
    std::string scene;
    std::string motion;
    double speed_m_s = 0.0;
    std::uint64_t seed = 1;
    std::string rig;
    bool realtime = false;
    std::string out;
    std::string window = "200,400";
    int m = 0;  // 0: the default (or, for a simulated rig, LookAheadRows)
    double obstacle_cell_m = 0.1;
    double snapshot_every_s = 2.0;
    double duration_s = 0.0;
    std::uint64_t scans = 0;
    double timeout_s = 10.0;
    double pose_tolerance_s = 0.05;
    std::vector<std::string> sets;  // CAS parameters NAME=VALUE, as casmap filter --set
    bool view = false;              // --view: serve the live page (casmap view) while mapping
    int port = 8080;
    std::string host = "127.0.0.1";
};

#ifdef CASMAP_WITH_VIEW
/// The live page of `casmap view` on DIR, served while mapping; the address goes to stderr
/// (stdout carries the final JSON line).
std::unique_ptr<view::Server> StartView(const LiveOptions& opt) {
    io::EnsureDirectory(opt.out);
    view::SiteOptions site;
    site.dir = opt.out;
    site.web_dir = view::FindWebDir();
    site.kind = view::FolderKind::kLive;  // status.json comes with the first status period
    auto server = std::make_unique<view::Server>(site, view::ServerOptions{opt.host, opt.port});
    server->Start();
    if (!view::IsLoopback(opt.host)) {
        std::fprintf(stderr,
                     "casmap live: warning: --host %s makes %s readable by anyone who can reach "
                     "this machine\n",
                     opt.host.c_str(), opt.out.c_str());
    }
    std::fprintf(stderr, "casmap live: view at %s\n", server->Url().c_str());
    std::fflush(stderr);
    return server;
}
#endif

void ParseWindow(const std::string& text, mapper::ActiveWindowConfig& w) {
    const std::size_t comma = text.find(',');
    try {
        std::size_t used_r = 0;
        std::size_t used_c = 0;
        if (comma != std::string::npos) {
            const std::string r = text.substr(0, comma);
            const std::string c = text.substr(comma + 1);
            w.rows = std::stoi(r, &used_r);
            w.cols = std::stoi(c, &used_c);
            if (used_r == r.size() && used_c == c.size()) {
                return;
            }
        }
    } catch (const std::logic_error&) {
        // reported below
    }
    throw MakeInputError("command line", "--window", text, "R,C: two integers (rows, columns)");
}

std::string Json(const pipeline::LiveResult& r) {
    const pipeline::LiveStatus& s = r.status;
    char buf[1024];
    std::snprintf(
        buf, sizeof(buf),
        "{\"scans\": %llu, \"scans_mapped\": %llu, \"dropped\": %llu, \"poses\": %llu, "
        "\"rows_filtered\": %llu, \"scans_per_s\": %.3f, \"latency_p50_ms\": %.3f, "
        "\"latency_p99_ms\": %.3f, \"crc_errors\": %llu, \"resyncs\": %llu, "
        "\"reconnects\": %llu, \"beams_behind\": %llu, \"beams_late\": %llu, "
        "\"turns\": %llu}",
        static_cast<unsigned long long>(s.scans), static_cast<unsigned long long>(s.scans_mapped),
        static_cast<unsigned long long>(s.dropped), static_cast<unsigned long long>(s.poses),
        static_cast<unsigned long long>(s.rows_filtered), s.scans_per_s, s.latency_p50_ms,
        s.latency_p99_ms, static_cast<unsigned long long>(s.source.crc_errors),
        static_cast<unsigned long long>(s.source.resyncs),
        static_cast<unsigned long long>(s.source.reconnects),
        static_cast<unsigned long long>(r.window.beams_behind),
        static_cast<unsigned long long>(r.window.beams_late),
        static_cast<unsigned long long>(r.window.turns));
    return buf;
}

void StatusLine(const pipeline::LiveStatus& s) {
    std::fprintf(stderr,
                 "\rlive: %llu scans, %.1f scans/s, latency p99 %.2f ms, dropped %llu, "
                 "crc errors %llu, reconnects %llu   %s",
                 static_cast<unsigned long long>(s.scans), s.scans_per_s, s.latency_p99_ms,
                 static_cast<unsigned long long>(s.dropped),
                 static_cast<unsigned long long>(s.source.crc_errors),
                 static_cast<unsigned long long>(s.source.reconnects), s.finished ? "\n" : "");
    std::fflush(stderr);
}

void RunLiveCommand(const LiveOptions& opt, const CommonOptions& common, bool speed_given) {
    const bool from_device = !opt.device.empty();
    const bool from_scene = !opt.scene.empty() || !opt.motion.empty();
    if (from_device == from_scene) {
        throw MakeInputError("command line", "--device / --scene", "",
                             "give either --device PATH or --scene FILE --motion M");
    }
    pipeline::LiveConfig cfg;
    cfg.out_dir = opt.out;
    ParseWindow(opt.window, cfg.window);
    cfg.window.obstacle_cell_m = opt.obstacle_cell_m;
    cfg.snapshot_every_s = opt.snapshot_every_s;
    cfg.duration_s = opt.duration_s;
    cfg.max_scans = opt.scans;
    cfg.timeout_s = opt.timeout_s;
    cfg.pose_tolerance_s = opt.pose_tolerance_s;
    std::unique_ptr<pipeline::LiveScanSource> source;
    std::unique_ptr<drivers::PoseStream> poses;
    if (from_device) {
        drivers::CheckLmsBaud(opt.baud, "--baud");
        if (opt.poses.empty() == opt.poses_socket.empty()) {
            throw MakeInputError("command line", "--poses / --poses-socket", "",
                                 "a scanner on a device needs exactly one pose stream");
        }
        if (!opt.poses.empty()) {
            poses = std::make_unique<drivers::PoseFileFollower>(opt.poses);
        } else {
            poses = std::make_unique<drivers::PoseSocket>(opt.poses_socket);
        }
        source = pipeline::MakeDeviceSource(opt.device, opt.baud, opt.timeout_s);
    } else {
#ifdef CASMAP_WITH_SIM
        if (opt.scene.empty() || opt.motion.empty()) {
            throw MakeInputError("command line", "--scene / --motion", "",
                                 "--scene and --motion go together");
        }
        pipeline::SimFlags flags;
        flags.scene_path = opt.scene;
        flags.motion = opt.motion;
        if (speed_given) {
            flags.speed_m_s = opt.speed_m_s;
        }
        flags.seed = opt.seed;
        flags.rig_path = opt.rig;
        pipeline::SimulatedLive sim;
        WithFlagNames({{"motion", "--motion"}, {"speed_m_s", "--speed"}}, [&] {
            sim = pipeline::MakeSimulatedSource(flags, core::ResolveThreads(common.threads),
                                                opt.realtime);
        });
        // The simulated map's grid origin, so live cells coincide with `casmap simulate`'s.
        cfg.window.origin_x_m = sim.setup.grid.x0_m;
        cfg.window.origin_y_m = sim.setup.grid.y0_m;
        if (opt.m == 0 && !sim.poses.empty()) {
            const core::Pose& p0 = sim.poses.samples().front().world_T_sensor;
            const double pitch = core::RpyFromQuaternion(p0.rotation).y();
            cfg.window.m = mapper::LookAheadRows(cfg.window, p0.translation.z(), pitch, 0.3);
        }
        // Eq. 8's v: the rig's cruise speed, as `casmap bench` and datasets use.
        cfg.window.cas.speed_m_s =
            sim.setup.vehicle ? sim.setup.vehicle_config.speed_m_s : sim.setup.table.speed_m_s;
        poses = std::make_unique<pipeline::TrajectoryPoseStream>(sim.poses);
        source = std::move(sim.scans);
#else
        (void)common;
        (void)speed_given;
        throw MakeInputError("command line", "--scene", opt.scene,
                             "this casmap was built without the simulator; use --device");
#endif
    }
    if (opt.m != 0) {
        cfg.window.m = opt.m;
    }
    // CAS parameters by name; the window's mapping cell and increment follow the filter's.
    mapper::FilterParams params;
    params.cas = cfg.window.cas;
    for (const std::string& s : opt.sets) {
        params.SetAssignment(s);
    }
    params.Validate();
    cfg.window.cas = params.cas;
    cfg.window.a = params.cas.a;
    cfg.window.cell_m = params.cas.cell_m;
#ifdef CASMAP_WITH_VIEW
    const std::unique_ptr<view::Server> server = opt.view ? StartView(opt) : nullptr;
#endif
    const LiveSignals signals;
    const bool tty = ::isatty(STDERR_FILENO) != 0;
    pipeline::LiveStatusFn on_status;
    if (tty) {
        on_status = StatusLine;
    }
    const pipeline::LiveResult r = pipeline::RunLive(cfg, *source, *poses, g_live_stop, on_status);
    std::printf("%s\n", Json(r).c_str());
    std::fflush(stdout);
    if (r.timed_out) {
        char seconds[32];
        std::snprintf(seconds, sizeof(seconds), "%g", opt.timeout_s);
        throw std::runtime_error(source->name() + ": no scan for " + seconds + " s; " +
                                 (r.run_file.empty()
                                      ? std::string("nothing received")
                                      : "wrote the " + std::to_string(r.status.scans) +
                                            " scans received to " + r.run_file.string()));
    }
}

}  // namespace

void AddLiveCommand(CLI::App& app, CommonOptions& common) {
    auto opt = std::make_shared<LiveOptions>();
    CLI::App* sub = app.add_subcommand(
        "live", "Map live with the paper's active window (LMS 200 device or real-time simulator)");
    sub->add_option("--device", opt->device, "serial device (or the link of casmap serve)");
    sub->add_option("--baud", opt->baud, "rate to switch the scanner to")->capture_default_str();
    sub->add_option("--poses", opt->poses, "pose file followed as it grows (docs/pose-file.md)");
    sub->add_option("--poses-socket", opt->poses_socket,
                    "pose records on udp:PORT (127.0.0.1) or unix:PATH datagrams");
    sub->add_option("--scene", opt->scene, "scene to simulate (simulator builds)");
    sub->add_option("--motion", opt->motion, "T, TR, TP, TRP or vehicle");
    CLI::Option* speed = sub->add_option("--speed", opt->speed_m_s, "rig speed (m/s)");
    sub->add_option("--seed", opt->seed, "simulation seed")->capture_default_str();
    sub->add_option("--rig", opt->rig, "rig YAML");
    sub->add_flag("--realtime", opt->realtime, "pace the simulator at the scanner's 75 Hz");
    sub->add_option("--out", opt->out, "output directory")->required();
    sub->add_option("--window", opt->window, "active window R,C (rows along travel, columns)")
        ->capture_default_str();
    sub->add_option("--m", opt->m,
                    "rows R-m..R-1 updated, row R-m filtered (default 142; simulated rigs: "
                    "from their height and pitch)");
    sub->add_option("--obstacle-cell-m", opt->obstacle_cell_m, "obstacle map cell (m)")
        ->capture_default_str();
    sub->add_option("--snapshot-every-s", opt->snapshot_every_s,
                    "snapshot period (s); 0: only at exit")
        ->capture_default_str();
    sub->add_option("--duration", opt->duration_s, "stop after S seconds (0: no limit)");
    sub->add_option("--scans", opt->scans, "stop after N scans received");
    sub->add_option("--timeout", opt->timeout_s, "stop (exit 1) after S s without a scan")
        ->capture_default_str();
    sub->add_option("--pose-tolerance-s", opt->pose_tolerance_s,
                    "largest pose gap a scan may span; wider: the scan is dropped")
        ->capture_default_str();
    sub->add_option("--set", opt->sets,
                    "CAS parameter NAME=VALUE (repeatable; names as casmap filter --set)");
    AddThreadsOption(sub, common);
#ifdef CASMAP_WITH_VIEW
    sub->add_flag("--view", opt->view, "serve the live page while mapping (see casmap view)");
    sub->add_option("--port", opt->port, "--view: TCP port (0 = any free port)")
        ->capture_default_str();
    sub->add_option("--host", opt->host, "--view: bind address (not loopback: readable by others)")
        ->capture_default_str();
#endif
    sub->callback([opt, &common, speed] { RunLiveCommand(*opt, common, speed->count() > 0); });
}

}  // namespace casmap::app
