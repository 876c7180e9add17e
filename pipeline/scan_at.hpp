#pragma once

// One simulated LMS 200 scan from a fixed pose (`casmap scan`, Python's casmap.scan_at): the
// sensor configuration from a file with the command line's overrides, the pose from six
// numbers, the scan, and the scan as the JSON object `casmap scan` prints (docs/DESIGN.md).

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "casmap/core/pose.hpp"
#include "casmap/sensor_models/lms200_config.hpp"
#include "casmap/sim/simulator.hpp"

namespace casmap::pipeline {

/// The LMS 200 of a single scan: a config file (or the built-in config) with overrides.
struct ScanSensorOptions {
    std::string sensor;                ///< LMS 200 YAML; empty: the built-in config
    bool ideal = false;                ///< one exact centre ray per beam (or the file's `ideal`)
    std::optional<int> range_mode_m;   ///< 8, 16 or 32; unset: the file's (8 m by default)
    std::optional<std::string> units;  ///< "mm" or "cm"; unset: the file's (mm by default)

    /// InputError naming range_mode_m or units for a value the LMS 200 does not have.
    void Validate() const;
};

/// The configuration of `options`: the file (io::LoadLms200Config) with the overrides applied.
[[nodiscard]] sensor_models::Lms200Config MakeScanSensorConfig(const ScanSensorOptions& options);

/// (x_m, y_m, z_m, roll_deg, pitch_deg, yaw_deg) -> world_T_sensor (R = Rz Ry Rx); InputError
/// naming `field` unless there are exactly six finite numbers.
[[nodiscard]] core::Pose PoseFromXyzRpyDeg(const std::vector<double>& values,
                                           const std::string& field = "pose");
/// The same from the text "X,Y,Z,ROLL_DEG,PITCH_DEG,YAW_DEG" (core::ParseNumberList).
[[nodiscard]] core::Pose ParsePoseXyzRpyDeg(std::string_view text,
                                            const std::string& field = "pose");

struct ScanAtOptions {
    std::string scene;  ///< scene YAML
    core::Pose world_T_sensor;
    ScanSensorOptions sensor;
    std::uint64_t seed = 0;  ///< noise, footprint rotation, artifacts
};

struct ScanAtResult {
    sensor_models::Lms200Config sensor;  ///< the configuration used
    sim::ScanResult scan;                ///< stamped 0, scan index 0
};

/// Loads the scene and casts one scan (InputError for a bad scene, sensor file or override).
[[nodiscard]] ScanAtResult ScanAt(const ScanAtOptions& options);

/// The JSON object of a scan: angles_deg, ranges_m (null when no range; the ideal range with
/// 6 decimals, else the reported value in the scanner's unit), status, labels, raw.
[[nodiscard]] std::string ScanJson(const ScanAtResult& result);

}  // namespace casmap::pipeline
