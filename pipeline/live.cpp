#include "casmap/pipeline/live.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <deque>
#include <optional>
#include <span>
#include <thread>

#include "casmap/core/check.hpp"
#include "casmap/core/input_error.hpp"
#include "casmap/drivers/lms200_driver.hpp"
#include "casmap/io/atomic_file.hpp"
#include "casmap/io/run_file.hpp"
#include "casmap/mapper/sweep_jump_stream.hpp"
#include "casmap/pipeline/map_run.hpp"

namespace casmap::pipeline {
namespace {

using Clock = std::chrono::steady_clock;

double Seconds(Clock::duration d) { return std::chrono::duration<double>(d).count(); }

class DeviceSource final : public LiveScanSource {
public:
    DeviceSource(const std::string& device, int baud, double connect_timeout_s)
        : driver_(MakeConfig(device, baud)),
          device_(device),
          connect_timeout_s_(connect_timeout_s) {}

    void Start() override {
        // A missing device or bad settings are InputErrors (not retried); a device that is
        // there but silent is retried: a scanner still powering up or a serve restarting.
        const Clock::time_point deadline =
            Clock::now() + std::chrono::duration_cast<Clock::duration>(
                               std::chrono::duration<double>(connect_timeout_s_));
        for (;;) {
            try {
                driver_.Connect();
                return;
            } catch (const drivers::SerialError&) {
                if (Clock::now() >= deadline) {
                    throw;
                }
                ++connect_retries_;
                std::this_thread::sleep_for(std::chrono::seconds(1));
            }
        }
    }
    std::optional<core::Scan> Next(double timeout_s) override {
        return driver_.NextScan(timeout_s);
    }
    LiveSourceCounters counters() const override {
        const drivers::DriverCounters c = driver_.counters();
        return {c.crc_errors, c.resyncs, c.reconnects + connect_retries_, c.bytes};
    }
    std::optional<core::Lms200Format> format() const override {
        return driver_.connected() || driver_.info().baud != 0
                   ? std::optional<core::Lms200Format>(driver_.info().format)
                   : std::nullopt;
    }
    std::string name() const override { return device_; }
    void Stop() override { driver_.Close(); }

private:
    static drivers::DriverConfig MakeConfig(const std::string& device, int baud) {
        drivers::DriverConfig c;
        c.device = device;
        c.baud = baud;
        return c;
    }
    drivers::Lms200Driver driver_;
    std::string device_;
    double connect_timeout_s_;
    std::uint64_t connect_retries_ = 0;
};

// The session's state: what was received, what waits for poses, the window.
class Session {
public:
    Session(const LiveConfig& config, LiveScanSource& scans, drivers::PoseStream& poses)
        : config_(config), scans_(scans), poses_(poses), window_(config.window) {
        if (config.prefilter == Prefilter::kSweepJump) {
            stream_.emplace(config.sweep_jump);
        }
    }

    LiveResult Run(const std::atomic<bool>& stop, const LiveStatusFn& on_status);

private:
    enum class Coverage { kCovered, kWait, kNever };
    struct Pending {
        std::size_t index;
        Clock::time_point received;
    };
    Coverage Covers(const core::Scan& scan, std::size_t& first, std::size_t& last) const;
    void ProcessPending(Clock::time_point now, bool final);
    void Map(const core::Scan& scan,
             const core::Trajectory& poses,
             std::span<const std::uint8_t> keep,
             Clock::time_point received);
    void MapLabelled();  // the scans the pre-filter has labelled
    LiveStatus Status(Clock::time_point now, bool finished);
    void WriteSnapshots() const;
    void WriteFinal(const LiveStatus& status, LiveResult& result) const;

    LiveConfig config_;
    LiveScanSource& scans_;
    drivers::PoseStream& poses_;
    mapper::ActiveWindow window_;
    std::optional<mapper::SweepJumpStream> stream_;  // the sweep_jump pre-filter
    std::deque<Clock::time_point> stream_received_;  // arrival of each scan in stream_
    std::vector<core::Scan> received_;
    std::vector<core::TimedPose> pose_log_;
    std::deque<Pending> pending_;
    std::vector<double> latency_ms_;  // ring of the last kLatencies
    std::size_t latency_next_ = 0;
    std::uint64_t mapped_ = 0;
    std::uint64_t dropped_ = 0;
    Clock::time_point start_;
    Clock::time_point last_status_;
    std::uint64_t scans_at_last_status_ = 0;
    static constexpr std::size_t kLatencies = 1000;
};

Session::Coverage Session::Covers(const core::Scan& scan,
                                  std::size_t& first,
                                  std::size_t& last) const {
    const double t0 = scan.stamp_s;
    const double t1 = scan.BeamTime(scan.beams.empty() ? 0 : scan.beams.size() - 1);
    const auto by_stamp = [](const core::TimedPose& p, double t) { return p.stamp_s < t; };
    if (pose_log_.empty()) {
        return Coverage::kWait;
    }
    if (pose_log_.front().stamp_s > t0) {
        return Coverage::kNever;  // poses started after the scan
    }
    const auto end = std::lower_bound(pose_log_.begin(), pose_log_.end(), t1, by_stamp);
    if (end == pose_log_.end()) {
        return Coverage::kWait;  // poses lag behind the scan
    }
    // The last sample at or before t (poses_log_.front() <= t0 here, so at_t0 exists).
    const auto at_or_before = [&](double t) {
        auto it =
            std::upper_bound(pose_log_.begin(), pose_log_.end(), t,
                             [](double x, const core::TimedPose& p) { return x < p.stamp_s; });
        return it == pose_log_.begin() ? it : it - 1;
    };
    // From one scan period before beam 0: the motion term of Eq. 4 looks one period back.
    const auto begin = at_or_before(t0 - config_.window.scan_period_s);
    const auto at_t0 = at_or_before(t0);
    for (auto it = at_t0; it != end; ++it) {
        if ((it + 1)->stamp_s - it->stamp_s > config_.pose_tolerance_s) {
            return Coverage::kNever;  // a hole in the poses: never map with a stale pose
        }
    }
    first = static_cast<std::size_t>(begin - pose_log_.begin());
    last = static_cast<std::size_t>(end - pose_log_.begin());
    return Coverage::kCovered;
}

void Session::ProcessPending(Clock::time_point now, bool final) {
    while (!pending_.empty()) {
        const Pending p = pending_.front();
        const core::Scan& scan = received_[p.index];
        std::size_t first = 0;
        std::size_t last = 0;
        const Coverage c = Covers(scan, first, last);
        if (c == Coverage::kWait && !final && Seconds(now - p.received) < config_.pose_wait_s) {
            return;  // keep the order: later scans wait behind it
        }
        pending_.pop_front();
        if (c != Coverage::kCovered) {
            ++dropped_;
            continue;
        }
        core::Trajectory slice(std::vector<core::TimedPose>(
            pose_log_.begin() + static_cast<std::ptrdiff_t>(first),
            pose_log_.begin() + static_cast<std::ptrdiff_t>(last) + 1));
        if (!stream_) {
            Map(scan, slice, {}, p.received);
            continue;
        }
        stream_->Push(scan, std::move(slice));
        stream_received_.push_back(p.received);
        MapLabelled();
    }
    if (final && stream_) {  // the session's last scans: labelled as the run's last ones
        stream_->Finish();
        MapLabelled();
    }
}

void Session::MapLabelled() {
    while (std::optional<mapper::SweepJumpStream::Labelled> l = stream_->Pop()) {
        const Clock::time_point received = stream_received_.front();
        stream_received_.pop_front();
        Map(l->scan, l->poses, l->keep, received);
    }
}

void Session::Map(const core::Scan& scan,
                  const core::Trajectory& poses,
                  std::span<const std::uint8_t> keep,
                  Clock::time_point received) {
    for (const mapper::FilteredRow& row : window_.AddScan(scan, poses, keep)) {
        if (config_.on_row) {
            config_.on_row(row);
        }
    }
    ++mapped_;
    // From the scan's arrival: with a pre-filter this includes the wait for its neighbours.
    const double ms = Seconds(Clock::now() - received) * 1e3;
    if (latency_ms_.size() < kLatencies) {
        latency_ms_.push_back(ms);
    } else {
        latency_ms_[latency_next_] = ms;
        latency_next_ = (latency_next_ + 1) % kLatencies;
    }
}

LiveStatus Session::Status(Clock::time_point now, bool finished) {
    LiveStatus s;
    s.elapsed_s = Seconds(now - start_);
    s.scans = received_.size();
    s.scans_mapped = mapped_;
    s.dropped = dropped_;
    s.poses = pose_log_.size();
    s.rows_filtered = window_.stats().rows_filtered;
    s.beams_rejected = window_.stats().beams.beams_rejected;
    const double span = Seconds(now - last_status_);
    if (span > 0.0) {
        s.scans_per_s = static_cast<double>(s.scans - scans_at_last_status_) / span;
    }
    if (finished && s.elapsed_s > 0.0) {
        s.scans_per_s = static_cast<double>(s.scans) / s.elapsed_s;
    }
    scans_at_last_status_ = s.scans;
    last_status_ = now;
    if (!latency_ms_.empty()) {
        std::vector<double> l = latency_ms_;
        std::sort(l.begin(), l.end());
        const auto at = [&](double q) {
            return l[std::min(l.size() - 1,
                              static_cast<std::size_t>(q * static_cast<double>(l.size())))];
        };
        s.latency_p50_ms = at(0.5);
        s.latency_p99_ms = at(0.99);
    }
    s.source = scans_.counters();
    s.finished = finished;
    return s;
}

void Session::WriteSnapshots() const {
    core::MapF h;
    core::MapF c;
    window_.Snapshot(h, c);
    const core::Raster<std::uint8_t> unknown = UnknownMask(c);
    WriteMapFiles(config_.out_dir, "window_elevation", h, "active window elevation", "m", &unknown);
    WriteMapFiles(config_.out_dir, "window_certainty", c, "active window certainty", "counts",
                  &unknown);
    const mapper::ObstacleRaster o = window_.obstacles().ToRaster();
    if (o.grid.rows > 0) {
        core::Raster<std::uint8_t> none(o.grid.rows, o.grid.cols, 0);
        for (std::size_t i = 0; i < none.data.size(); ++i) {
            none.data[i] = o.count.data[i] == 0 ? 1 : 0;
        }
        WriteMapFiles(config_.out_dir, "obstacle_elevation", o.elevation,
                      "obstacle map elevation (highest filtered)", "m", &none);
        WriteMapFiles(config_.out_dir, "obstacle_certainty", o.certainty, "obstacle map certainty",
                      "counts", &none);
    }
}

void Session::WriteFinal(const LiveStatus& status, LiveResult& result) const {
    WriteSnapshots();
    io::WriteTextAtomically(config_.out_dir / "status.json", StatusJson(status, window_));
    io::WriteTextAtomically(config_.out_dir / "config.yaml",
                            LiveConfigYaml(config_, scans_.name()));
    if (received_.empty()) {
        return;
    }
    io::RunData run;
    run.scans = received_;
    if (!pose_log_.empty()) {
        run.poses = core::Trajectory(pose_log_);
    }
    run.format = scans_.format();
    run.config_yaml = LiveConfigYaml(config_, scans_.name());
    result.run_file = config_.out_dir / "run.h5";
    io::WriteRunFile(result.run_file, run);
}

LiveResult Session::Run(const std::atomic<bool>& stop, const LiveStatusFn& on_status) {
    LiveResult result;
    start_ = Clock::now();
    last_status_ = start_;
    Clock::time_point last_scan = start_;
    Clock::time_point last_snapshot = start_;
    Clock::time_point last_report = start_;
    std::vector<core::TimedPose> fresh;
    try {
        while (!stop) {
            const Clock::time_point now = Clock::now();
            if ((config_.duration_s > 0.0 && Seconds(now - start_) >= config_.duration_s) ||
                (config_.max_scans > 0 && received_.size() >= config_.max_scans) ||
                (scans_.finished() && pending_.empty())) {
                break;
            }
            if (Seconds(now - last_scan) >= config_.timeout_s) {
                result.timed_out = true;
                break;
            }
            std::optional<core::Scan> scan = scans_.Next(0.05);
            const Clock::time_point got = Clock::now();
            fresh.clear();
            poses_.Poll(fresh);
            pose_log_.insert(pose_log_.end(), fresh.begin(), fresh.end());
            if (scan) {
                last_scan = got;
                pending_.push_back({received_.size(), got});
                received_.push_back(std::move(*scan));
            }
            ProcessPending(got, false);
            if (Seconds(got - last_report) >= config_.status_every_s) {
                last_report = got;
                const LiveStatus s = Status(got, false);
                io::WriteTextAtomically(config_.out_dir / "status.json", StatusJson(s, window_));
                if (on_status) {
                    on_status(s);
                }
            }
            if (config_.snapshot_every_s > 0.0 &&
                Seconds(got - last_snapshot) >= config_.snapshot_every_s) {
                last_snapshot = got;
                WriteSnapshots();
            }
        }
        fresh.clear();
        poses_.Poll(fresh);
        pose_log_.insert(pose_log_.end(), fresh.begin(), fresh.end());
        ProcessPending(Clock::now(), true);
    } catch (...) {
        // Nothing received is lost: the run file and maps are written, then the error goes on.
        scans_.Stop();
        LiveResult partial;
        WriteFinal(Status(Clock::now(), true), partial);
        throw;
    }
    scans_.Stop();
    result.status = Status(Clock::now(), true);
    result.window = window_.stats();
    WriteFinal(result.status, result);
    if (on_status) {
        on_status(result.status);
    }
    return result;
}

}  // namespace

std::unique_ptr<LiveScanSource> MakeDeviceSource(const std::string& device,
                                                 int baud,
                                                 double connect_timeout_s) {
    return std::make_unique<DeviceSource>(device, baud, connect_timeout_s);
}

void TrajectoryPoseStream::Poll(std::vector<core::TimedPose>& out) {
    if (!sent_) {
        for (const core::TimedPose& p : poses_.samples()) {
            (void)Accept(p, out);
        }
        sent_ = true;
    }
}

void LiveConfig::Validate() const {
    window.Validate();
    const core::Check check("live");
    check.That(prefilter == Prefilter::kNone || prefilter == Prefilter::kSweepJump, "prefilter",
               ToString(prefilter), "allowed live: none | sweep_jump");
    if (prefilter == Prefilter::kSweepJump) {
        sweep_jump.Validate();
    }
    check.NonNegative("snapshot_every_s", snapshot_every_s, ">= 0");
    check.Positive("status_every_s", status_every_s, "> 0");
    check.Positive("pose_tolerance_s", pose_tolerance_s, "> 0");
    check.NonNegative("pose_wait_s", pose_wait_s, ">= 0");
    check.Positive("timeout_s", timeout_s, "> 0");
    check.NonNegative("duration_s", duration_s, ">= 0");
}

LiveResult RunLive(const LiveConfig& config,
                   LiveScanSource& scans,
                   drivers::PoseStream& poses,
                   const std::atomic<bool>& stop,
                   const LiveStatusFn& on_status) {
    config.Validate();
    io::EnsureDirectory(config.out_dir);
    scans.Start();
    Session session(config, scans, poses);
    return session.Run(stop, on_status);
}

}  // namespace casmap::pipeline
