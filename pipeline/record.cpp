#include "casmap/pipeline/record.hpp"

#include <unistd.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "casmap/core/check.hpp"
#include "casmap/core/input_error.hpp"
#include "casmap/core/text.hpp"
#include "casmap/drivers/partial_scans.hpp"
#include "casmap/drivers/pose_file.hpp"
#include "casmap/io/output_set.hpp"
#include "casmap/io/run_file.hpp"
#include "casmap/io/yaml_emit.hpp"
#include "casmap/pipeline/connect_retry.hpp"

namespace casmap::pipeline {
namespace {
namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;

/// "180,1" / "180,0.5" / "100,0.25" (degrees) -> Variant; InputError otherwise.
drivers::Variant ParseVariant(const std::string& text) {
    const std::optional<std::vector<double>> numbers = core::ParseNumberList(text, 2);
    if (numbers) {
        const double angle = (*numbers)[0];
        const double res = (*numbers)[1];
        if (angle >= 0.0 && angle <= 1000.0 && res >= 0.0 && res <= 10.0) {
            const drivers::Variant v{static_cast<std::uint16_t>(std::lround(angle)),
                                     static_cast<std::uint16_t>(std::lround(res * 100.0))};
            if (v.IsValid() && angle == v.angle_deg &&
                std::abs(res * 100.0 - v.resolution_cdeg) < 1e-6) {
                return v;
            }
        }
    }
    throw MakeInputError("", "variant", text,
                         "ANGLE,RES_DEG: 180,1 180,0.5 100,1 100,0.5 or 100,0.25");
}

/// Everything checked before the scanner is touched (issue #13 item 2).
}  // namespace

void RecordOptions::Validate() const {
    io::CheckOutputPath(out, "out");
    const core::Check check;
    check.Positive("timeout_s", timeout_s, "a finite number of seconds > 0");
    check.NonNegative("duration_s", duration_s, "a finite number of seconds >= 0");
    if (!poses.empty()) {
        // `casmap serve --poses-out` may write the file only once streaming began: it may be
        // missing now, but then its folder must exist; if it exists it must be a file.
        const core::Check file(poses);
        const fs::path p(poses);
        if (fs::exists(p)) {
            file.That(fs::is_regular_file(p), "poses", poses, "is not a regular file");
            file.That(access(p.c_str(), R_OK) == 0, "poses", poses, "is not readable");
        } else {
            const fs::path dir = p.has_parent_path() ? p.parent_path() : fs::path(".");
            file.That(fs::is_directory(dir), "poses", poses,
                      "neither the file nor its folder exists");
        }
    }
}

namespace {

std::string ConfigYaml(const RecordOptions& opt, const drivers::Lms200Driver& driver) {
    const drivers::DeviceInfo& d = driver.info();
    YAML::Emitter out;
    out << YAML::Comment("casmap record: how this run was recorded");
    out << YAML::BeginMap;
    out << YAML::Key << "device" << YAML::Value << YAML::DoubleQuoted << opt.device;
    out << YAML::Key << "baud" << YAML::Value << d.baud;
    out << YAML::Key << "scanner" << YAML::Value << YAML::BeginMap;
    out << YAML::Key << "type" << YAML::Value << YAML::DoubleQuoted << d.type;
    out << YAML::Key << "variant" << YAML::Value << YAML::Flow << YAML::BeginMap;
    out << YAML::Key << "angle_deg" << YAML::Value << d.variant.angle_deg;
    out << YAML::Key << "resolution_cdeg" << YAML::Value << d.variant.resolution_cdeg;
    out << YAML::EndMap;
    out << YAML::Key << "measuring_mode" << YAML::Value << int{d.config.measuring_mode()};
    out << YAML::Key << "units" << YAML::Value << (d.config.units() == 1 ? "mm" : "cm");
    out << YAML::Key << "output_mode" << YAML::Value << YAML::DoubleQuoted << d.output.ToString();
    out << YAML::Key << "realtime_indices" << YAML::Value
        << (d.config.realtime_indices() ? "true" : "false");
    out << YAML::EndMap;
    out << YAML::Key << "stamps" << YAML::Value << YAML::DoubleQuoted
        << std::string("system clock, s since 1970; beam 0 = ") +
               (driver.synchronised() ? "sweep grid t0 + k T (scan clock)"
                                      : "arrival - transmission - sweep");
    out << YAML::Key << "poses" << YAML::Value;
    if (opt.poses.empty()) {
        io::EmitNull(out);
    } else {
        out << YAML::DoubleQuoted << opt.poses;
    }
    out << YAML::EndMap;
    return io::EmittedText(out);
}

/// --mode's parameters, checked before the device is opened and named as the flag: a mean count
/// outside 2..250 or a sub-range that fits no variant (the device's own variant, when
/// --variant does not set one, bounds the sub-range again at Connect).
void CheckMode(const drivers::OutputMode& mode,
               const std::optional<drivers::Variant>& variant,
               const std::string& variant_text,
               const std::string& text) {
    if (mode.HasMean() && (mode.mean_scans < 2 || mode.mean_scans > 250)) {
        throw MakeInputError(
            "", "mode", text,
            "mean scans N = " + std::to_string(mode.mean_scans) + " (allowed: 2..250)");
    }
    if (mode.HasSubRange()) {
        constexpr int kMostBeams = 401;  // 100 deg at 0.25 deg, the largest variant
        const int beams = variant ? variant->BeamCount() : kMostBeams;
        if (mode.first_beam < 1 || mode.first_beam > mode.last_beam || mode.last_beam > beams) {
            throw MakeInputError(
                "", "mode", text,
                "sub-range FIRST-LAST needs 1 <= FIRST <= LAST <= " + std::to_string(beams) +
                    (variant ? " (the beams of variant " + variant_text + ")"
                             : " (the most beams of any LMS 200 scan: 100 deg "
                               "at 0.25 deg)"));
        }
    }
}

drivers::DriverConfig DriverConfigOf(const RecordOptions& opt) {
    drivers::DriverConfig dc;
    dc.device = opt.device;
    dc.baud = opt.baud;
    if (!opt.variant.empty()) {
        dc.variant = ParseVariant(opt.variant);
    }
    dc.output = drivers::ParseOutputMode(opt.mode, "mode");
    CheckMode(dc.output, dc.variant, opt.variant, opt.mode);
    if (opt.realtime_indices) {
        dc.config_changes.availability = drivers::ConfigBlock::kRealTimeIndices;
    }
    if (opt.stamps == "arrival") {
        dc.stamps = drivers::StampMode::kArrival;
    } else if (opt.stamps != "scan-clock") {
        throw MakeInputError("", "stamps", opt.stamps, "scan-clock or arrival");
    }
    return dc;
}

/// Writes what was received; a failure with --poses still writes the scans (without poses),
/// and a failing --out falls back to a file in the system's temporary folder.
void SaveRun(const RecordOptions& opt, io::RunData& run) {
    std::string poses_error;
    if (!opt.poses.empty()) {  // read last: `casmap serve --poses-out` writes it on demand
        try {
            run.poses = drivers::ReadPoseFile(opt.poses);
        } catch (const InputError& e) {
            poses_error = e.what();
        }
    }
    try {
        io::WriteRunFile(opt.out, run);
    } catch (const std::exception& e) {
        const fs::path rescue =
            fs::temp_directory_path() / ("casmap_record_" + std::to_string(getpid()) + ".h5");
        io::WriteRunFile(rescue.string(), run);
        throw std::runtime_error(std::string(e.what()) + "; the " +
                                 std::to_string(run.scans.size()) +
                                 " scans received were saved to " + rescue.string());
    }
    if (!poses_error.empty()) {
        throw std::runtime_error(poses_error + "; the " + std::to_string(run.scans.size()) +
                                 " scans received were saved without poses to " + opt.out);
    }
}

}  // namespace

void Record(const RecordOptions& opt,
            const std::function<bool()>& stop_requested,
            const std::function<void(const RecordStats&)>& report) {
    opt.Validate();
    io::RunData run;
    drivers::Lms200Driver driver(DriverConfigOf(opt));
    const int attempts = ConnectWithRetry(opt.device, opt.timeout_s,
                                          DeviceConnectSteps(driver, opt.device, stop_requested));
    drivers::PartialScanAssembler assembler(driver.info().variant);
    const bool partial = driver.info().output.kind == drivers::OutputKind::kPartial;
    const Clock::time_point start = Clock::now();
    Clock::time_point last_scan = start;
    bool timed_out = false;
    while (!(stop_requested && stop_requested())) {
        if (opt.scans > 0 && run.scans.size() >= opt.scans) {
            break;
        }
        const Clock::time_point now = Clock::now();
        if (opt.duration_s > 0.0 &&
            std::chrono::duration<double>(now - start).count() >= opt.duration_s) {
            break;
        }
        if (std::chrono::duration<double>(now - last_scan).count() >= opt.timeout_s) {
            timed_out = true;
            break;
        }
        std::optional<core::Scan> scan = driver.NextScan(0.2);
        if (!scan) {
            continue;
        }
        last_scan = Clock::now();
        if (partial) {  // one geometry per run: join the turns of each complete scan
            scan = assembler.Add(*scan);
            if (!scan) {
                continue;
            }
        }
        run.scans.push_back(std::move(*scan));
    }
    driver.Close();
    const drivers::DriverCounters c = driver.counters();
    // The rate of the recorded scans' own stamps (the scan clock, or arrival corrected for the
    // line): read times bunch up when telegrams wait in the line's buffer (337 "scans/s" for
    // 10 scans read at once), the stamps are what the run file holds.
    const double span_s =
        run.scans.size() >= 2 ? run.scans.back().stamp_s - run.scans.front().stamp_s : 0.0;
    const double rate = run.scans.size() >= 2 && span_s > 0.0
                            ? static_cast<double>(run.scans.size() - 1) / span_s
                            : 0.0;
    if (report) {
        report(RecordStats{run.scans.size(), c, attempts, rate});
    }
    if (!run.scans.empty()) {
        run.format = driver.info().format;
        run.config_yaml = ConfigYaml(opt, driver);
        SaveRun(opt, run);
    }
    if (run.scans.empty() && !timed_out) {
        throw std::runtime_error(opt.device + ": no scan received; nothing written");
    }
    if (timed_out) {
        throw std::runtime_error(
            opt.device + ": no scan for " + core::FormatNumber(opt.timeout_s) + " s; " +
            (run.scans.empty() ? std::string("nothing written")
                               : "wrote the " + std::to_string(run.scans.size()) +
                                     " scans received to " + opt.out));
    }
}

}  // namespace casmap::pipeline
