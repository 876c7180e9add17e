#pragma once

// Helpers shared by the io tests: a file's bytes, small valid runs, an h5py oracle.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <random>
#include <string>
#include <vector>

#include "casmap/core/lms200.hpp"
#include "casmap/io/run_file.hpp"

namespace casmap::io::test {

/// The whole file at `path` (empty if it cannot be read).
inline std::string ReadBytes(const std::filesystem::path& path) {
    std::ifstream in(path, std::ios::binary);
    return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

/// Two scans of five 1.5 m beams at 1 deg steps, 1/75 s apart, with the LMS 200 format.
inline RunData SmallRun() {
    RunData run;
    run.config_yaml = "scene: course04.yaml\nmotion: T\n";
    core::Scan scan;
    scan.stamp_s = 0.0;
    scan.start_angle_rad = 0.0;
    scan.angle_step_rad = 0.0174533;
    scan.beam_period_s = 3.7e-5;
    scan.beams.assign(5, core::Beam{1.5F, core::BeamStatus::kOk, 1500});
    run.scans.push_back(scan);
    scan.stamp_s = 1.0 / 75;
    run.scans.push_back(scan);
    run.format = core::Lms200Format{};
    return run;
}

constexpr double kDeg = 3.14159265358979323846 / 180.0;
constexpr std::uint32_t kSeed = 20240611;

/// Runs /usr/bin/python3 (Debian's, with h5py) on `script`; returns stdout.
inline std::string RunPython(const std::filesystem::path& dir,
                             const std::string& script,
                             int* status = nullptr) {
    const std::filesystem::path py = dir / "oracle.py";
    std::ofstream(py) << script;
    const std::string cmd = "/usr/bin/python3 " + py.string() + " 2>&1";
    FILE* pipe = popen(cmd.c_str(), "r");
    std::string out;
    char buffer[4096];
    while (pipe != nullptr && fgets(buffer, sizeof(buffer), pipe) != nullptr) {
        out += buffer;
    }
    const int rc = pipe != nullptr ? pclose(pipe) : -1;
    if (status != nullptr) {
        *status = rc;
    }
    return out;
}

inline core::MapF Ramp(int rows, int cols, float offset) {
    core::MapF map(rows, cols);
    for (int r = 0; r < rows; ++r) {
        for (int c = 0; c < cols; ++c) {
            map.at(r, c) = offset + static_cast<float>(r) * 0.5F - static_cast<float>(c) * 0.25F;
        }
    }
    return map;
}

/// A small run with every feature: statuses, NaNs, labels, true ranges, poses, maps.
inline RunData MakeRun(std::size_t scans, std::size_t beams) {
    SCOPED_TRACE("seed " + std::to_string(kSeed));
    std::mt19937 rng(kSeed);
    std::uniform_real_distribution<float> range(0.2F, 7.9F);
    std::uniform_int_distribution<int> status(0, core::kBeamStatusCount - 1);
    std::uniform_int_distribution<int> label(0, core::kBeamLabelCount - 1);
    RunData run;
    run.format = core::Lms200Format{core::RangeMode::k8m, core::RangeUnits::kMillimetre};
    run.seed = 0xFEDCBA9876543210ULL;
    run.config_yaml = "scene: course04.yaml\nmotion: T\nspeed_m_s: 1.0\n";
    for (std::size_t i = 0; i < scans; ++i) {
        core::Scan s;
        s.stamp_s = 0.5 + static_cast<double>(i) / 75.0;
        s.start_angle_rad = -90.0 * kDeg;
        s.angle_step_rad = 1.0 * kDeg;
        s.beam_period_s = core::Lms200Timing::kBeamPeriodS;
        core::ScanTruth t;
        for (std::size_t j = 0; j < beams; ++j) {
            core::Beam b;
            b.status =
                (j % 3 == 0) ? static_cast<core::BeamStatus>(status(rng)) : core::BeamStatus::kOk;
            b.range_m = range(rng);
            b.raw = b.status == core::BeamStatus::kOk ? run.format->EncodeRange(b.range_m)
                                                      : run.format->CodeFor(b.status);
            s.beams.push_back(b);
            t.labels.push_back(static_cast<core::BeamLabel>(label(rng)));
            t.true_range_m.push_back(j % 7 == 0 ? std::nanf("") : b.range_m + 0.01F);
        }
        run.scans.push_back(s);
        run.truth.push_back(t);
    }
    std::vector<core::TimedPose> poses;
    for (int i = 0; i < 12; ++i) {
        poses.push_back(
            {0.4 + 0.001 * i,
             core::PoseFromXyzRpy({0.001 * i, 0.3, 0.8}, {0.01 * i, 30 * kDeg + 0.02 * i, 0.0})});
    }
    run.poses = core::Trajectory(poses);
    run.maps.grid = core::GridGeometry{0.25, -1.0, 0.025, 4, 3};
    run.maps.elevation_m = Ramp(4, 3, 0.1F);
    run.maps.certainty = Ramp(4, 3, 2.0F);
    run.maps.truth_m = Ramp(4, 3, 0.0F);
    run.maps.filtered["cas"] = Ramp(4, 3, -0.1F);
    run.maps.filtered["median"] = Ramp(4, 3, -0.2F);
    return run;
}

}  // namespace casmap::io::test
