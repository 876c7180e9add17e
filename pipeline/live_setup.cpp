#include "casmap/pipeline/live_setup.hpp"

#include <cstdio>
#include <optional>
#include <utility>
#include <vector>

#include "casmap/core/check.hpp"
#include "casmap/core/input_error.hpp"
#include "casmap/core/text.hpp"
#include "casmap/drivers/telegram.hpp"
#include "casmap/mapper/filter_params.hpp"
#include "casmap/pipeline/map_run.hpp"
#ifdef CASMAP_PIPELINE_WITH_SIM
#include "casmap/pipeline/live_sim.hpp"
#endif

namespace casmap::pipeline {
namespace {

/// The device half: the driver's source and exactly one pose stream.
void SetUpDevice(const LiveOptions& o, LiveSetup& setup) {
    if (!o.poses.empty()) {
        setup.poses = std::make_unique<drivers::PoseFileFollower>(o.poses);
    } else {
        setup.poses = std::make_unique<drivers::PoseSocket>(o.poses_socket);
    }
    setup.scans = MakeDeviceSource(o.device, o.baud, o.timeout_s);
}

}  // namespace

void LiveOptions::Validate() const {
    const core::Check check;
    const bool from_device = !device.empty();
    const bool from_scene = !scene.empty() || !motion.empty();
    check.That(from_device != from_scene, "device / scene", "",
               "give either device or scene and motion");
    if (from_device) {
        drivers::CheckLmsBaud(baud, "baud");
        check.That(poses.empty() != poses_socket.empty(), "poses / poses_socket", "",
                   "a scanner needs exactly one pose stream");
        return;
    }
    check.That(!scene.empty() && !motion.empty(), "scene / motion", "",
               "scene and motion go together");
#ifndef CASMAP_PIPELINE_WITH_SIM
    check.Fail("scene", scene, "built without the simulator; use device");
#endif
}

void ParseWindowSize(std::string_view text, LiveOptions& options, const std::string& field) {
    const std::vector<std::string> rc = core::SplitList(text);
    const std::optional<int> rows = rc.size() == 2 ? core::ParseWholeInt(rc[0]) : std::nullopt;
    const std::optional<int> cols = rc.size() == 2 ? core::ParseWholeInt(rc[1]) : std::nullopt;
    core::Check().That(rows && cols, field, text, "R,C: two integers (rows, columns)");
    options.window_rows = *rows;
    options.window_cols = *cols;
}

LiveSetup MakeLiveSetup(const LiveOptions& o, int threads) {
    o.Validate();
    LiveSetup setup;
    LiveConfig& cfg = setup.config;
    cfg.out_dir = o.out;
    cfg.window.rows = o.window_rows;
    cfg.window.cols = o.window_cols;
    cfg.window.obstacle_cell_m = o.obstacle_cell_m;
    cfg.snapshot_every_s = o.snapshot_every_s;
    cfg.duration_s = o.duration_s;
    cfg.max_scans = o.scans;
    cfg.timeout_s = o.timeout_s;
    cfg.pose_tolerance_s = o.pose_tolerance_s;
    if (!o.device.empty()) {
        SetUpDevice(o, setup);
    } else {
#ifdef CASMAP_PIPELINE_WITH_SIM
        SetUpSimulatedLive(o, threads, setup);
#else
        (void)threads;  // unreachable: Validate() rejects a scene in this build
#endif
    }
    if (o.m != 0) {
        cfg.window.m = o.m;
    }
    // The mapper mode and pre-filter, and their parameters as casmap map takes them.
    const core::Check check;
    MapSettings stages;
    stages.mode = ParseMapperMode(o.mapper, "mapper");
    check.That(stages.mode != MapperMode::kKalman, "mapper", o.mapper,
               "allowed live: paper | consensus (the Kalman mapper has no window form)");
    stages.prefilter = ParsePrefilter(o.prefilter, "prefilter");
    check.That(stages.prefilter == Prefilter::kNone || stages.prefilter == Prefilter::kSweepJump,
               "prefilter", o.prefilter,
               "allowed live: none | sweep_jump (shadow and range_jump run in casmap map)");
    std::vector<std::string> stage_sets;
    std::vector<std::string> cas_sets;
    for (const std::string& s : o.cas) {
        (IsStageParameter(s.substr(0, s.find('='))) ? stage_sets : cas_sets).push_back(s);
    }
    ApplyStageSettings(stages, stage_sets, "set");
    if (stages.mode == MapperMode::kConsensus) {
        cfg.window.consensus = stages.consensus;
    }
    cfg.prefilter = stages.prefilter;
    cfg.sweep_jump = stages.sweep_jump;
    // CAS parameters by name; the window's mapping cell and increment follow the filter's.
    mapper::FilterParams params;
    params.cas = cfg.window.cas;
    for (const std::string& s : cas_sets) {
        params.SetAssignment(s);
    }
    params.Validate();
    cfg.window.cas = params.cas;
    cfg.window.a = params.cas.a;
    cfg.window.cell_m = params.cas.cell_m;
    cfg.Validate();
    return setup;
}

std::string LiveTimeoutMessage(const LiveResult& r,
                               const std::string& source_name,
                               double timeout_s) {
    return source_name + ": no scan for " + core::FormatNumber(timeout_s) + " s; " +
           (r.run_file.empty() ? std::string("nothing received")
                               : "wrote the " + std::to_string(r.status.scans) +
                                     " scans received to " + r.run_file.string());
}

std::string LiveSummaryJson(const LiveResult& r) {
    const LiveStatus& s = r.status;
    const auto n = [](std::uint64_t v) { return static_cast<unsigned long long>(v); };
    char buf[1024];
    std::snprintf(buf, sizeof(buf),
                  "{\"scans\": %llu, \"scans_mapped\": %llu, \"dropped\": %llu, \"poses\": %llu, "
                  "\"rows_filtered\": %llu, \"beams_rejected\": %llu, \"scans_per_s\": %.3f, "
                  "\"latency_p50_ms\": %.3f, "
                  "\"latency_p99_ms\": %.3f, \"crc_errors\": %llu, \"resyncs\": %llu, "
                  "\"reconnects\": %llu, \"beams_behind\": %llu, \"beams_late\": %llu, "
                  "\"turns\": %llu}",
                  n(s.scans), n(s.scans_mapped), n(s.dropped), n(s.poses), n(s.rows_filtered),
                  n(s.beams_rejected), s.scans_per_s, s.latency_p50_ms, s.latency_p99_ms,
                  n(s.source.crc_errors), n(s.source.resyncs), n(s.source.reconnects),
                  n(r.window.beams_behind), n(r.window.beams_late), n(r.window.turns));
    return buf;
}

}  // namespace casmap::pipeline
