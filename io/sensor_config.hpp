#pragma once

// The simulated LMS 200's parameters (sensor_models::Lms200Config) as a YAML file
// (docs/sensor-config.md, config/lms200.yaml). Simulator builds only.

#include <string>
#include <vector>

#include "casmap/sensor_models/lms200_config.hpp"

namespace casmap::io {

/// Reads a YAML mapping whose keys are the fields of Lms200Config (units in the key names;
/// `format` is split into range_mode_m: 8|16|32 and range_units: mm|cm). Missing keys keep
/// their defaults. Throws InputError naming file:line:col and the key for an unknown key, a
/// wrong type or a value Lms200Config::Validate() rejects.
[[nodiscard]] sensor_models::Lms200Config LoadLms200Config(const std::string& path);

/// Every field as YAML (one `key: value` line each, in the order of the struct); loading the
/// text gives back the same config, bit for bit.
[[nodiscard]] std::string Lms200ConfigToYaml(const sensor_models::Lms200Config& config);

/// Applies NAME=VALUE settings (NAME a key of the file format, VALUE a YAML scalar or, for
/// sun_direction_world, X,Y,Z) to `config`, then validates it. InputError names `flag`, the
/// key and the value otherwise.
void ApplyLms200ConfigOverrides(sensor_models::Lms200Config& config,
                                const std::vector<std::string>& assignments,
                                const std::string& flag);

}  // namespace casmap::io
