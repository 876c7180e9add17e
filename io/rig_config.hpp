#pragma once

// Rig YAML files (config/rig_table.yaml, config/rig_vehicle.yaml) -> rig config structs.
// Built only with CASMAP_BUILD_SIM (io/CMakeLists.txt builds io/rig_*.cpp only then).

#include <string>

#include "casmap/rig/pose_error.hpp"
#include "casmap/rig/table.hpp"
#include "casmap/rig/vehicle.hpp"

namespace casmap::io {

/// Everything a rig file can set. Every section and key is optional (defaults otherwise).
struct RigConfig {
    rig::TableConfig table;
    rig::VehicleConfig vehicle;
    rig::PoseErrorConfig pose_error;
};

/// Loads a rig YAML file with top-level keys `table`, `vehicle`, `pose_error` (key names as
/// the struct fields; vectors as lists; profile shapes "sinusoid" | "triangle"). Throws
/// InputError "file:line:col: table.speed_m_s = 1.5 (allowed: 0 < v <= 1 m/s)" for an unknown
/// key, a value of the wrong type, or a value breaking a rule of the config's Validate().
[[nodiscard]] RigConfig LoadRigConfig(const std::string& path);

/// The effective configuration as YAML text listing every key (LoadRigConfig reads it back to
/// the same values).
[[nodiscard]] std::string RigConfigToYaml(const RigConfig& config);

}  // namespace casmap::io
