#include "casmap/pipeline/serve.hpp"

#include <chrono>
#include <cstdio>
#include <filesystem>
#include <mutex>
#include <thread>
#include <utility>
#include <vector>

#include "casmap/core/check.hpp"
#include "casmap/core/input_error.hpp"
#include "casmap/drivers/pose_file.hpp"
#include "casmap/drivers/scan_list_source.hpp"
#include "casmap/io/atomic_file.hpp"
#include "casmap/io/output_set.hpp"
#include "casmap/io/run_file.hpp"
#ifdef CASMAP_PIPELINE_WITH_SIM
#include "casmap/pipeline/live_sim.hpp"
#endif

namespace casmap::pipeline {
namespace {

/// The run to serve: read from `run`, or simulated from the scene (simulator builds).
io::RunData LoadServedRun(const ServeOptions& o, int threads) {
    if (!o.run.empty()) {
        return io::ReadRunFile(o.run);
    }
#ifdef CASMAP_PIPELINE_WITH_SIM
    return SimulateServedRun(o, threads);
#else
    (void)threads;
    throw MakeInputError("", "scene", o.scene, "built without the simulator; use run");
#endif
}

/// Writes the pose file on its own thread once the first sweep fixed the offset between run
/// time and the system clock; joined (and its error kept) by Finish or the destructor.
class PoseWriter {
public:
    PoseWriter(std::string path, const core::Trajectory& poses)
        : path_(std::move(path)), poses_(poses) {
        thread_ = std::thread([this] {
            while (!have_offset_ && !done_) {
                std::this_thread::sleep_for(std::chrono::milliseconds(10));
            }
            if (have_offset_) {
                try {
                    io::WriteTextAtomically(path_, drivers::PoseFileText(poses_, offset_s_));
                } catch (const std::exception& e) {  // the folder went away while serving
                    const std::lock_guard lock(mutex_);
                    error_ = e.what();
                }
            }
        });
    }
    ~PoseWriter() { Join(); }
    PoseWriter(const PoseWriter&) = delete;
    PoseWriter& operator=(const PoseWriter&) = delete;

    /// Called by the scanner for each sweep it sends (the first one fixes the offset).
    void Sent(double beam0_wall_s, double run_stamp_s) {
        if (!have_offset_) {
            offset_s_ = beam0_wall_s - run_stamp_s;
            have_offset_ = true;
        }
    }
    /// Waits for the file; the write's error, if any (empty otherwise).
    std::string Finish() {
        Join();
        const std::lock_guard lock(mutex_);
        return error_;
    }

private:
    void Join() {
        done_ = true;
        if (thread_.joinable()) {
            thread_.join();
        }
    }
    std::string path_;
    const core::Trajectory& poses_;
    std::atomic<bool> have_offset_{false};
    std::atomic<bool> done_{false};
    double offset_s_ = 0.0;
    std::mutex mutex_;
    std::string error_;
    std::thread thread_;
};

}  // namespace

void ServeOptions::Validate() const {
    const core::Check check;
    const bool from_run = !run.empty();
    const bool from_scene = !scene.empty() || !motion.empty();
    check.That(from_run != from_scene, "run / scene", "", "give either run or scene and motion");
    check.That(!from_scene || (!scene.empty() && !motion.empty()), "scene / motion", "",
               "scene and motion go together");
    drivers::CheckLmsBaud(baud, "baud");
    if (!faults.empty()) {
        (void)drivers::ParseFaults(faults);
    }
    if (!poses_out.empty()) {
        io::CheckOutputPath(poses_out, "poses_out");
    }
    if (!eeprom.empty()) {
        io::CheckOutputPath(eeprom, "eeprom");
        if (std::filesystem::exists(eeprom)) {
            (void)drivers::ReadEepromFile(eeprom);  // a broken file fails before serving
        }
    }
}

ServeResult Serve(const ServeOptions& o,
                  int threads,
                  const std::atomic<bool>& stop,
                  const std::function<void(const ServeStarted&)>& on_started) {
    o.Validate();
    drivers::VirtualLms200Config vc;
    vc.link_path = o.link;
    vc.power_on_baud = o.baud;
    vc.eeprom_path = o.eeprom;
    if (!o.faults.empty()) {
        vc.faults = drivers::ParseFaults(o.faults);
    }
    const std::string what = o.run.empty() ? o.scene : o.run;
    io::RunData run = LoadServedRun(o, threads);
    if (!o.poses_out.empty() && run.poses.empty()) {
        throw MakeInputError("", "poses_out", o.poses_out, "no poses in " + what);
    }
    if (run.format) {
        vc.config.set_measuring_mode(drivers::ModeByteOf(*run.format));
        vc.config.set_units(drivers::UnitsByteOf(*run.format));
    }
    std::vector<double> stamps;
    for (const core::Scan& s : run.scans) {
        stamps.push_back(s.stamp_s);
    }
    drivers::ScanListSource source(std::move(run.scans), what);
    vc.variant = source.variant();
    drivers::VirtualLms200 scanner(vc, source);
    std::optional<PoseWriter> poses;
    if (!o.poses_out.empty()) {
        poses.emplace(o.poses_out, run.poses);
        scanner.SetScanObserver(
            [&](const drivers::SentScan& s) { poses->Sent(s.beam0_wall_s, stamps.at(s.index)); });
    }
    scanner.Open();
    if (on_started) {
        on_started({scanner.SlavePath(), source.size(), source.variant()});
    }
    scanner.Run(stop, true);
    ServeResult result{scanner.stats(), ""};
    if (poses) {
        result.poses_out_error = poses->Finish();
    }
    return result;
}

std::string ServeStatsJson(const drivers::VirtualLms200Stats& s) {
    const auto n = [](std::uint64_t v) { return static_cast<unsigned long long>(v); };
    char buf[512];
    std::snprintf(buf, sizeof(buf),
                  "{\"scans_sent\": %llu, \"scans_skipped\": %llu, \"requests\": %llu, "
                  "\"bytes\": %llu, \"crc_faults\": %llu, \"drop_faults\": %llu, "
                  "\"garbage_bytes\": %llu, \"disconnects\": %llu, \"source_exhausted\": %s}",
                  n(s.scans_sent), n(s.scans_skipped), n(s.requests), n(s.bytes_sent),
                  n(s.crc_faults), n(s.drop_faults), n(s.garbage_bytes), n(s.disconnects),
                  s.source_exhausted ? "true" : "false");
    return buf;
}

}  // namespace casmap::pipeline
