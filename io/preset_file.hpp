#pragma once

// Filter-parameter presets (config/presets/NAME.yaml, docs/commands/bench.md "Presets"):
//   description: "free text"     # optional
//   set:                         # required mapping; keys = `casmap filter --set` names
//     A: 45
//     h_sum_min: 10
//   pipelines:                   # optional: more settings for one named pipeline only
//     cas_trail: {support_min: 9}
// This reader checks the shape only; pipeline::LoadPreset applies the values (ranges, names).

#include <string>
#include <utility>
#include <vector>

namespace casmap::io {

struct PresetEntry {
    std::string name;   // the --set name
    std::string value;  // the YAML scalar's text
    std::string where;  // "file:line:col" of the value
};

struct PresetFile {
    std::string path;
    std::string description;
    std::vector<PresetEntry> entries;  // `set:`, in file order
    /// `pipelines:`: per pipeline name (as written), its entries in file order.
    std::vector<std::pair<std::string, std::vector<PresetEntry>>> pipelines;
    std::vector<std::string> pipeline_where;  // "file:line:col" of each pipeline key
};

/// Reads a preset file; InputError naming file:line:col and the field (description, set,
/// set.<NAME>, pipelines.<P>.<NAME>) for a missing file, bad YAML, an unknown top-level key, a
/// missing or non-mapping `set`, a `pipelines` that is not a mapping of mappings, or a value
/// that is not a scalar.
[[nodiscard]] PresetFile ReadPresetFile(const std::string& path);

}  // namespace casmap::io
