// casmap serve (--scene FILE --motion T|TR|TP|TRP|vehicle [--speed M_S] [--seed N] [--rig R]
//               | --run RUN.h5) [--link PATH] [--baud N]
//               [--faults crc=P,garbage=P,drop=P,collide=P,disconnect=S] [--poses-out FILE]
//               [--eeprom FILE]
// A virtual LMS 200 on a pseudo-terminal streaming the scans of a run file or of a run
// simulated at start-up, until the run is exhausted or SIGINT/SIGTERM: flags ->
// pipeline::ServeOptions -> pipeline::Serve (pipeline/serve.hpp). --baud is the power-on rate
// (9600 as the real unit); the client switches it. Prints the device path on start and one
// JSON line of counters on exit. --poses-out writes the run's poses re-stamped into the system
// clock of the served sweeps (docs/pose-file.md), so that `casmap record --poses` can give a
// recorded run its poses. --eeprom keeps the scanner's configuration (what clients write with
// 0x77) in a file across restarts.
#include <cstdio>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>

#include "apps/casmap/commands.hpp"
#include "apps/casmap/flag_names.hpp"
#include "apps/casmap/stop_signals.hpp"
#include "casmap/pipeline/serve.hpp"

namespace casmap::app {
namespace {

void RunServe(const pipeline::ServeOptions& opt, const CommonOptions& common) {
    static const FlagNames kFlags = {
        {"run", "--run"},         {"scene", "--scene"},         {"motion", "--motion"},
        {"speed_m_s", "--speed"}, {"baud", "--baud"},           {"faults", "--faults"},
        {"link_path", "--link"},  {"poses_out", "--poses-out"}, {"eeprom", "--eeprom"}};
    const FlagPaths paths = {
        {"poses_out", opt.poses_out}, {"eeprom", opt.eeprom}, {"link_path", opt.link}};
    std::optional<StopSignals> signals;  // from the start of serving: the link is removed
    const auto started = [&](const pipeline::ServeStarted& s) {
        signals.emplace();
        std::fprintf(stderr,
                     "casmap serve: virtual LMS 200 on %s%s%s, power-on %d baud, %zu scans "
                     "(%d deg / %.2f deg)\n",
                     s.device.c_str(), opt.link.empty() ? "" : " linked at ", opt.link.c_str(),
                     opt.baud, s.scans, s.variant.angle_deg, s.variant.resolution_cdeg / 100.0);
        std::fflush(stderr);
    };
    pipeline::ServeResult r;
    WithWhereAsFlag("faults", "--faults", [&] {
        WithCommandLineFlags(
            kFlags, [&] { r = pipeline::Serve(opt, common.threads, g_stop_requested, started); },
            paths);
    });
    std::printf("%s\n", pipeline::ServeStatsJson(r.stats).c_str());
    if (!r.poses_out_error.empty()) {
        throw std::runtime_error("--poses-out: " + r.poses_out_error);
    }
}

}  // namespace

void AddServeCommand(CLI::App& app, CommonOptions& common) {
    auto opt = std::make_shared<pipeline::ServeOptions>();
    CLI::App* sub = app.add_subcommand(
        "serve", "Serve a virtual LMS 200 on a pseudo-terminal, streaming a run's scans");
    sub->add_option("--run", opt->run, "run file (HDF5) whose scans to serve");
    sub->add_option("--scene", opt->scene, "scene YAML to simulate (with --motion)");
    sub->add_option("--motion", opt->motion, "T, TR, TP, TRP (table) or vehicle");
    sub->add_option("--speed", opt->speed_m_s, "cruise speed (m/s)");
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
    sub->callback([opt, &common] { RunServe(*opt, common); });
}

}  // namespace casmap::app
