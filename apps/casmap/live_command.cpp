// casmap live (--device PATH [--baud B] (--poses FILE | --poses-socket udp:PORT|unix:PATH)
//              | --scene S --motion vehicle|T|TR|TP|TRP [--speed V] [--seed N] [--rig R]
//                [--realtime])
//             --out DIR [--window R,C] [--m M] [--obstacle-cell-m S] [--snapshot-every-s N]
//             [--duration S] [--scans N] [--timeout S] [--pose-tolerance-s T]
//             [--mapper paper|consensus] [--prefilter none|sweep_jump]
//             [--set NAME=VALUE]... [--view [--port P] [--host H]]
// Live mapping with the paper's active window: flags -> pipeline::LiveOptions ->
// MakeLiveSetup + RunLive (pipeline/live_setup.hpp). Prints a status line on a terminal
// (nothing otherwise) and one JSON line of counters at the end; on stderr at start-up, the
// bound port of a UDP pose socket (what `udp:0` chose) and the --view address.
#include <unistd.h>

#include <cstdio>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include "apps/casmap/commands.hpp"
#include "apps/casmap/flag_names.hpp"
#include "apps/casmap/stop_signals.hpp"
#include "casmap/core/parallel.hpp"
#include "casmap/drivers/pose_stream.hpp"
#include "casmap/pipeline/live_setup.hpp"
#ifdef CASMAP_WITH_VIEW
#include "apps/casmap/view_start.hpp"
#include "casmap/io/atomic_file.hpp"
#endif

namespace casmap::app {
namespace {

struct LiveFlags {
    pipeline::LiveOptions options;
    std::string window = "200,400";
    bool view = false;  // --view: serve the live page (casmap view) while mapping
    int port = 8080;
    std::string host = "127.0.0.1";
};

void StatusLine(const pipeline::LiveStatus& s) {
    using U = unsigned long long;
    std::fprintf(stderr,
                 "\rlive: %llu scans, %.1f scans/s, latency p99 %.2f ms, dropped %llu, "
                 "rejected beams %llu, crc errors %llu, reconnects %llu   %s",
                 U{s.scans}, s.scans_per_s, s.latency_p99_ms, U{s.dropped}, U{s.beams_rejected},
                 U{s.source.crc_errors}, U{s.source.reconnects}, s.finished ? "\n" : "");
    std::fflush(stderr);
}

void RunLiveCommand(LiveFlags& f, const CommonOptions& common) {
    WithCommandLineFlags({{"window", "--window"}},
                         [&] { pipeline::ParseWindowSize(f.window, f.options); });
    static const FlagNames kFlags = {{"device", "--device"},   {"baud", "--baud"},
                                     {"poses", "--poses"},     {"poses_socket", "--poses-socket"},
                                     {"scene", "--scene"},     {"motion", "--motion"},
                                     {"speed_m_s", "--speed"}, {"rig", "--rig"},
                                     {"mapper", "--mapper"},   {"prefilter", "--prefilter"},
                                     {"set", "--set"}};
    pipeline::LiveSetup setup;
    WithSetFlag([&] {
        WithCommandLineFlags(kFlags, [&] {
            setup = pipeline::MakeLiveSetup(f.options, core::ResolveThreads(common.threads));
        });
    });
    // The port is bound by now: a publisher started with `udp:0` learns it from this line.
    if (const auto* socket = dynamic_cast<const drivers::PoseSocket*>(setup.poses.get());
        socket != nullptr && socket->port() != 0) {
        std::fprintf(stderr, "casmap live: poses on udp:%d\n", socket->port());
        std::fflush(stderr);
    }
#ifdef CASMAP_WITH_VIEW
    std::unique_ptr<view::Server> server;  // the live page, while mapping; address on stderr
    if (f.view) {
        io::EnsureDirectory(f.options.out);
        server = StartViewServer("live", f.options.out, view::FolderKind::kLive, f.host, f.port);
        std::fprintf(stderr, "casmap live: view at %s\n", server->Url().c_str());
        std::fflush(stderr);
    }
#endif
    const StopSignals signals;
    pipeline::LiveStatusFn on_status;
    if (::isatty(STDERR_FILENO) != 0) {
        on_status = StatusLine;
    }
    const pipeline::LiveResult r =
        pipeline::RunLive(setup.config, *setup.scans, *setup.poses, g_stop_requested, on_status);
    std::printf("%s\n", pipeline::LiveSummaryJson(r).c_str());
    std::fflush(stdout);
    if (r.timed_out) {
        throw std::runtime_error(
            pipeline::LiveTimeoutMessage(r, setup.scans->name(), f.options.timeout_s));
    }
}

}  // namespace

void AddLiveCommand(CLI::App& app, CommonOptions& common) {
    auto f = std::make_shared<LiveFlags>();
    pipeline::LiveOptions& o = f->options;
    CLI::App* sub = app.add_subcommand(
        "live", "Map live with the paper's active window (LMS 200 device or real-time simulator)");
    sub->add_option("--device", o.device, "serial device (or the link of casmap serve)");
    sub->add_option("--baud", o.baud, "rate to switch the scanner to")->capture_default_str();
    sub->add_option("--poses", o.poses, "pose file followed as it grows (docs/pose-file.md)");
    sub->add_option("--poses-socket", o.poses_socket,
                    "pose records on udp:PORT (127.0.0.1) or unix:PATH datagrams");
    sub->add_option("--scene", o.scene, "scene to simulate (simulator builds)");
    sub->add_option("--motion", o.motion, "T, TR, TP, TRP or vehicle");
    sub->add_option("--speed", o.speed_m_s, "rig speed (m/s)");
    sub->add_option("--seed", o.seed, "simulation seed")->capture_default_str();
    sub->add_option("--rig", o.rig, "rig YAML");
    sub->add_flag("--realtime", o.realtime, "pace the simulator at the scanner's 75 Hz");
    sub->add_option("--out", o.out, "output directory")->required();
    sub->add_option("--window", f->window, "active window R,C (rows along travel, columns)")
        ->capture_default_str();
    sub->add_option("--m", o.m,
                    "rows R-m..R-1 updated, row R-m filtered (default 142; simulated rigs: "
                    "from their height and pitch)");
    sub->add_option("--obstacle-cell-m", o.obstacle_cell_m, "obstacle map cell (m)")
        ->capture_default_str();
    sub->add_option("--snapshot-every-s", o.snapshot_every_s,
                    "snapshot period (s); 0: only at exit")
        ->capture_default_str();
    sub->add_option("--duration", o.duration_s, "stop after S seconds (0: no limit)");
    sub->add_option("--scans", o.scans, "stop after N scans received");
    sub->add_option("--timeout", o.timeout_s, "stop (exit 1) after S s without a scan")
        ->capture_default_str();
    sub->add_option("--pose-tolerance-s", o.pose_tolerance_s,
                    "largest pose gap a scan may span; wider: the scan is dropped")
        ->capture_default_str();
    sub->add_option("--mapper", o.mapper,
                    "paper (Eq. 1-6) | consensus (Eq. 1-5, the mean of a cell whose heights agree)")
        ->capture_default_str();
    sub->add_option("--prefilter", o.prefilter,
                    "scan pre-filter before the window: none | sweep_jump (each scan mapped once "
                    "the next has arrived)")
        ->capture_default_str();
    sub->add_option("--set", o.cas,
                    "NAME=VALUE, repeatable: a CAS parameter (names as casmap filter --set), or "
                    "consensus.<field> / sweep_jump.<field> of the mode / pre-filter chosen "
                    "(names as casmap map --set)");
    AddThreadsOption(sub, common);
#ifdef CASMAP_WITH_VIEW
    sub->add_flag("--view", f->view, "serve the live page while mapping (see casmap view)");
    sub->add_option("--port", f->port, "--view: TCP port (0 = any free port)")
        ->capture_default_str();
    sub->add_option("--host", f->host, "--view: bind address (not loopback: readable by others)")
        ->capture_default_str();
#endif
    sub->callback([f, &common] { RunLiveCommand(*f, common); });
}

}  // namespace casmap::app
