#pragma once

// Helpers shared by the io tests: a file's bytes, and a small valid run.
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>

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

}  // namespace casmap::io::test
