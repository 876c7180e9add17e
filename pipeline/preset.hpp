#pragma once

// Named filter-parameter presets: `--preset NAME` loads <DataDir>/config/presets/NAME.yaml
// (io/preset_file.hpp shows the format; docs/commands/bench.md "Presets"). `paper` holds the
// paper's values (the defaults); `tuned` is written by the training-seed sweep. The settings
// apply after the values a run derives (cell, speed, scan period, a) and before `--set`.

#include <filesystem>
#include <map>
#include <string>
#include <vector>

namespace casmap::pipeline {

struct Preset {
    std::string name;                   // as given ("paper", or the file's path)
    std::string path;                   // the file read
    std::string description;            // the file's description (may be empty)
    std::vector<std::string> settings;  // NAME=VALUE, in file order (FilterParams::SetAssignment)
    /// `pipelines:` sections: per registered pipeline name, NAME=VALUE applied after
    /// `settings` for that pipeline only (never `unknown`: the run decides it).
    std::map<std::string, std::vector<std::string>> pipeline_settings;
};

/// DataDir() / "config" / "presets".
[[nodiscard]] std::filesystem::path PresetsDir();

/// The preset names shipped in PresetsDir() (file stems, sorted); empty if the folder is missing.
[[nodiscard]] std::vector<std::string> PresetNames();

/// Loads `name` (a preset name: [A-Za-z0-9_-]+, from PresetsDir()) or a file path (anything
/// with a '/' or ending in .yaml). Every value is checked as `--set` would check it. Throws
/// InputError naming `field` for an unknown name (listing the presets that exist), and the
/// file:line:col plus `set.<NAME>` / `pipelines.<P>[.<NAME>]` for a bad entry or an unknown
/// pipeline name.
[[nodiscard]] Preset LoadPreset(const std::string& name, const std::string& field = "preset");

}  // namespace casmap::pipeline
