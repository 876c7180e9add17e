#pragma once

// Live mapping (paper Sec. IV.B; docs/commands/live.md): scans from a source (an LMS 200 on a
// serial line, or the simulator paced in real time) and poses from a pose stream feed the
// active window (mapper/active_window.hpp); the session reports its status through a callback,
// writes snapshots of the window and the obstacle map plus status.json into the output
// directory (each replaced atomically), and on exit the final maps and a run file of every
// scan and pose received. No printing here; apps/casmap/live_command.cpp prints.

#include <atomic>
#include <cstdint>
#include <filesystem>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "casmap/core/lms200.hpp"
#include "casmap/core/scan.hpp"
#include "casmap/core/trajectory.hpp"
#include "casmap/drivers/pose_stream.hpp"
#include "casmap/mapper/active_window.hpp"
#include "casmap/mapper/sweep_jump.hpp"
#include "casmap/pipeline/map_run.hpp"

namespace casmap::pipeline {

/// Line and link counters of a scan source (zero where the source has none).
struct LiveSourceCounters {
    std::uint64_t crc_errors = 0;
    std::uint64_t resyncs = 0;
    std::uint64_t reconnects = 0;
    std::uint64_t bytes = 0;
};

/// Where scans come from.
class LiveScanSource {
public:
    virtual ~LiveScanSource() = default;
    /// Connects (may throw InputError for a missing device or bad settings).
    virtual void Start() {}
    /// The next scan, or nullopt if none arrived within `timeout_s`.
    virtual std::optional<core::Scan> Next(double timeout_s) = 0;
    /// True once a finite source (a simulated run) has delivered its last scan.
    [[nodiscard]] virtual bool finished() const { return false; }
    [[nodiscard]] virtual LiveSourceCounters counters() const { return {}; }
    [[nodiscard]] virtual std::optional<core::Lms200Format> format() const { return {}; }
    [[nodiscard]] virtual std::string name() const = 0;
    virtual void Stop() {}
};

/// A scan source on an LMS 200 driver (drivers/lms200_driver.hpp): a real scanner or
/// `casmap serve`. Start() connects; if no LMS 200 answers it retries every second for
/// `connect_timeout_s`, then throws SerialError. The driver reconnects by itself afterwards.
[[nodiscard]] std::unique_ptr<LiveScanSource> MakeDeviceSource(const std::string& device,
                                                               int baud,
                                                               double connect_timeout_s);

/// A pose stream that delivers a known trajectory whole on its first Poll (simulated runs).
class TrajectoryPoseStream final : public drivers::PoseStream {
public:
    explicit TrajectoryPoseStream(core::Trajectory poses) : poses_(std::move(poses)) {}
    void Poll(std::vector<core::TimedPose>& out) override;
    [[nodiscard]] std::string name() const override { return "simulated poses"; }

private:
    core::Trajectory poses_;
    bool sent_ = false;
};

struct LiveConfig {
    mapper::ActiveWindowConfig window;  // window.consensus set: the consensus mapper mode
    // The scan pre-filter before the window: kNone, or kSweepJump as a stream
    // (mapper::SweepJumpStream: each scan mapped once the next sweep_jump.reach scans with
    // poses arrived, the last ones at the end of the session; rejected beams are not mapped).
    Prefilter prefilter = Prefilter::kNone;
    mapper::SweepJumpConfig sweep_jump;  // used when prefilter == kSweepJump
    // Called with each row the window filtered, in order (a viewer, a test); may be empty.
    std::function<void(const mapper::FilteredRow&)> on_row;
    std::filesystem::path out_dir;
    double snapshot_every_s = 2.0;   // window + obstacle map PNG/TIFF; 0: only at exit
    double status_every_s = 0.5;     // status callback and status.json
    double pose_tolerance_s = 0.05;  // largest gap between pose samples a scan may span
    double pose_wait_s = 0.5;        // a scan waits this long for poses to cover it
    double timeout_s = 10.0;         // stop (timed out) after this long without a scan
    double duration_s = 0.0;         // stop after this long; 0: no limit
    std::uint64_t max_scans = 0;     // stop after this many scans received; 0: no limit
    void Validate() const;           // InputError naming the field ("prefilter", "sweep_jump.<f>")
};

struct LiveStatus {
    double elapsed_s = 0.0;
    std::uint64_t scans = 0;           // received from the source
    std::uint64_t scans_mapped = 0;    // given to the window with poses
    std::uint64_t dropped = 0;         // no pose within tolerance: counted, never mapped
    std::uint64_t poses = 0;           // received
    std::uint64_t rows_filtered = 0;   // rows the window CAS-filtered and registered
    std::uint64_t beams_rejected = 0;  // beams the pre-filter rejected: never mapped
    double scans_per_s = 0.0;          // over the last status period
    double latency_p50_ms = 0.0;       // scan handed over -> window updated and rows filtered
    double latency_p99_ms = 0.0;       // (including any wait for poses), last 1000 scans
    LiveSourceCounters source;
    bool finished = false;  // the final status
};
using LiveStatusFn = std::function<void(const LiveStatus&)>;

struct LiveResult {
    LiveStatus status;
    bool timed_out = false;          // stopped because no scan came for timeout_s
    std::filesystem::path run_file;  // empty if nothing was received
    mapper::ActiveWindowStats window;
};

/// Runs the session until `stop` becomes true, the source finishes, duration_s or max_scans
/// is reached, or no scan arrives for timeout_s. Then (also when an exception escapes the
/// loop) writes the final maps, run.h5 and status.json, and returns or rethrows.
LiveResult RunLive(const LiveConfig& config,
                   LiveScanSource& scans,
                   drivers::PoseStream& poses,
                   const std::atomic<bool>& stop,
                   const LiveStatusFn& on_status);

/// config.yaml text of a session (the effective configuration: window, mapper mode and
/// pre-filter with their stages' parameters, CAS, pose limits) reading from `source`.
[[nodiscard]] std::string LiveConfigYaml(const LiveConfig& config, const std::string& source);

/// status.json text of a status (the format docs/commands/live.md documents).
[[nodiscard]] std::string StatusJson(const LiveStatus& status, const mapper::ActiveWindow& window);

}  // namespace casmap::pipeline
