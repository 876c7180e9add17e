#pragma once

// Writing YAML with yaml-cpp's emitter (never by string concatenation): quoting, indentation and
// nesting are the emitter's; every number goes through core::FormatNumber (shortest round-trip
// text, .nan/.inf), never through the emitter's own double output. Private to casmap (not
// installed): io/, pipeline/ and apps/ sources include it; public headers return plain text.

#include <yaml-cpp/yaml.h>

#include <string>

#include "casmap/core/grid.hpp"
#include "casmap/core/text.hpp"

namespace casmap::sensor_models {
struct Lms200Config;
}  // namespace casmap::sensor_models
namespace casmap::scenegen {
struct DatasetSpec;
}  // namespace casmap::scenegen

namespace casmap::io {

struct RigConfig;

/// `key: value` with the value through core::FormatNumber.
inline void EmitNumber(YAML::Emitter& out, const char* key, double value) {
    out << YAML::Key << key << YAML::Value << core::FormatNumber(value);
}

/// A null value spelled `null` (yaml-cpp's default is `~`).
inline void EmitNull(YAML::Emitter& out) { out << YAML::LowerNull << YAML::Null; }

/// `key: path`, or `key: null` when `path` is empty (no file given).
inline void EmitPathOrNull(YAML::Emitter& out, const char* key, const std::string& path) {
    out << YAML::Key << key << YAML::Value;
    if (path.empty()) {
        EmitNull(out);
    } else {
        out << path;
    }
}

/// A grid as one flow map: {origin_x_m: .., origin_y_m: .., cell_m: .., rows: .., cols: ..}.
inline void EmitGrid(YAML::Emitter& out, const core::GridGeometry& grid) {
    out << YAML::Flow << YAML::BeginMap;
    EmitNumber(out, "origin_x_m", grid.x0_m);
    EmitNumber(out, "origin_y_m", grid.y0_m);
    EmitNumber(out, "cell_m", grid.cell_m);
    out << YAML::Key << "rows" << YAML::Value << grid.rows;
    out << YAML::Key << "cols" << YAML::Value << grid.cols;
    out << YAML::EndMap;
}

/// A comment on a line of its own (yaml-cpp would otherwise append it to the previous value).
inline void EmitCommentLine(YAML::Emitter& out, const std::string& text) {
    out << YAML::Newline << YAML::Comment(text);
}

/// The emitter's text with a final newline; throws std::logic_error if the emitter reports an
/// unbalanced document (a bug of the writer, never of the input).
[[nodiscard]] std::string EmittedText(const YAML::Emitter& out);

/// The keys `table`, `vehicle`, `pose_error` of a rig file, every field, into the open map.
/// Simulator builds only (io/rig_config.cpp).
void EmitRigConfig(YAML::Emitter& out, const RigConfig& config);

/// Every field of the LMS 200 config as one block map, in the order of the struct.
/// Simulator builds only (io/sensor_config.cpp).
void EmitLms200Config(YAML::Emitter& out, const sensor_models::Lms200Config& config);

/// The keys of a dataset spec file (io/dataset_spec_file.hpp), every field, into the open map.
void EmitDatasetSpec(YAML::Emitter& out, const scenegen::DatasetSpec& spec);

}  // namespace casmap::io
