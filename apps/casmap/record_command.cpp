// casmap record --device PATH [--baud N] [--scans N | --duration S] --out RUN.h5
//                [--variant ANGLE,RES_DEG] [--mode MODE] [--realtime-indices]
//                [--poses FILE] [--timeout S] [--stamps scan-clock|arrival]
// Records scans from an LMS 200 (a real one, or `casmap serve`) into a run file. The driver
// starts at 9600 baud and switches to --baud. --mode picks the output mode (continuous,
// mean:N, subrange:A-B, mean-subrange:N:A-B, partial; partial scans of an interleaved variant
// are joined into complete scans). Every input is checked before connecting; a scanner that
// is absent or fails during the start-up is retried with back-off until --timeout. Stops
// after --scans or --duration, on SIGINT/SIGTERM, or (with an error) after --timeout seconds
// without a scan. Prints one JSON line: {"scans", "bytes", "crc_errors", "bad_followers",
// "malformed", "resyncs", "reconnects", "connect_attempts", "scans_per_second"}. Scans are
// stamped on the system clock (docs/drivers.md); --poses adds a pose file in that clock
// (docs/pose-file.md), read when recording ends, as the run's /poses so `casmap map` can map
// the run. Whatever was received is written even when something fails afterwards.
#include <cstdio>
#include <memory>
#include <string>
#include <utility>

#include "apps/casmap/commands.hpp"
#include "apps/casmap/flag_names.hpp"
#include "apps/casmap/stop_signals.hpp"
#include "casmap/core/input_error.hpp"
#include "casmap/pipeline/record.hpp"

namespace casmap::app {
namespace {

void PrintStats(const pipeline::RecordStats& s) {
    const drivers::DriverCounters& c = s.counters;
    std::printf(
        "{\"scans\": %zu, \"bytes\": %llu, \"crc_errors\": %llu, \"bad_followers\": %llu, "
        "\"malformed\": %llu, \"resyncs\": %llu, \"reconnects\": %llu, "
        "\"connect_attempts\": %d, \"scans_per_second\": %.3f}\n",
        s.scans, static_cast<unsigned long long>(c.bytes),
        static_cast<unsigned long long>(c.crc_errors),
        static_cast<unsigned long long>(c.bad_followers),
        static_cast<unsigned long long>(c.malformed), static_cast<unsigned long long>(c.resyncs),
        static_cast<unsigned long long>(c.reconnects), s.connect_attempts, s.scans_per_second);
    std::fflush(stdout);
}

/// The library names option fields ("timeout_s"); the user typed flags ("--timeout"). Errors
/// about the options read "command line: --flag = value (rule)", errors about a given path
/// "PATH: --flag (rule)".
void RunRecord(const pipeline::RecordOptions& opt) {
    static const FlagNames kFlags = {{"device", "--device"},       {"baud", "--baud"},
                                     {"variant", "--variant"},     {"out", "--out"},
                                     {"poses", "--poses"},         {"timeout_s", "--timeout"},
                                     {"duration_s", "--duration"}, {"mode", "--mode"},
                                     {"stamps", "--stamps"}};
    const StopSignals signals;
    WithCommandLineFlags(kFlags,
                         [&] {
                             pipeline::Record(
                                 opt, [] { return g_stop_requested.load(); }, PrintStats);
                         },
                         {{"device", opt.device}, {"out", opt.out}, {"poses", opt.poses}});
}

}  // namespace

void AddRecordCommand(CLI::App& app, CommonOptions& common) {
    auto opt = std::make_shared<pipeline::RecordOptions>();
    CLI::App* sub =
        app.add_subcommand("record", "Record scans from an LMS 200 on a serial line to a run file");
    sub->add_option("--device", opt->device, "serial device (or the link of casmap serve)")
        ->required();
    sub->add_option("--baud", opt->baud, "rate to switch to (9600, 19200, 38400, 500000)")
        ->capture_default_str();
    CLI::Option* scans =
        sub->add_option("--scans", opt->scans, "stop after N scans");  // checked by flag_checks.hpp
    CLI::Option* duration = sub->add_option("--duration", opt->duration_s, "stop after S seconds");
    scans->excludes(duration);
    sub->add_option("--out", opt->out, "run file to write (HDF5)")->required();
    sub->add_option("--variant", opt->variant, "set the variant ANGLE,RES_DEG (e.g. 180,0.5)");
    sub->add_option("--mode", opt->mode,
                    "output mode: continuous, mean:N, subrange:A-B, mean-subrange:N:A-B, partial")
        ->capture_default_str();
    sub->add_flag("--realtime-indices", opt->realtime_indices,
                  "configure the scanner to append real-time scan indices (EEPROM write)");
    sub->add_option("--poses", opt->poses, "pose file (docs/pose-file.md) stored as /poses");
    sub->add_option("--timeout", opt->timeout_s, "give up after S seconds without a scan")
        ->capture_default_str();
    sub->add_option("--stamps", opt->stamps,
                    "scan-clock (on the sweep grid) or arrival (per-scan latency correction)")
        ->capture_default_str();
    AddThreadsOption(sub, common);
    sub->callback([opt] { RunRecord(*opt); });
}

}  // namespace casmap::app
