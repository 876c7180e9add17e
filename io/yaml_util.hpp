#pragma once

// Helpers for reading YAML into typed config structs with errors that name
// file:line:column, the field path, the value and the rule (STYLE.md section 4 and 5).
// Only io/*.cpp include this header (yaml-cpp stays out of public module headers).

#include <yaml-cpp/yaml.h>

#include <initializer_list>
#include <string>
#include <string_view>

#include "casmap/core/input_error.hpp"

namespace casmap::io {

/// Where a node sits: "file:line:col" (1-based), or just the file when the mark is unknown.
[[nodiscard]] std::string Where(const std::string& file, const YAML::Node& node);

/// Loads a YAML file; throws InputError for a missing file, a syntax error (with line:col), a
/// map key that is not a plain scalar, a duplicate key, or a file beyond the limits of
/// core/limits.hpp (size, nodes, depth).
[[nodiscard]] YAML::Node LoadYamlFile(const std::string& file);

/// LoadYamlFile on text already in memory; `file` names it in messages.
[[nodiscard]] YAML::Node LoadYamlText(const std::string& text, const std::string& file);

/// Throws InputError if `map` has a key not in `allowed` (typos are errors, not ignored).
void RejectUnknownKeys(const std::string& file,
                       const YAML::Node& map,
                       const std::string& path,
                       std::initializer_list<std::string_view> allowed);

/// Reads map[key] as T if present (else leaves `out` unchanged). Throws InputError with
/// file:line:col and field path when the value does not convert.
template <typename T>
void ReadOptional(const std::string& file,
                  const YAML::Node& map,
                  const std::string& path,
                  const char* key,
                  T& out) {
    const YAML::Node node = map[key];
    if (!node) {
        return;
    }
    try {
        out = node.as<T>();
    } catch (const YAML::Exception&) {
        throw MakeInputError(Where(file, node), path + "." + key,
                             node.IsScalar()
                                 ? node.Scalar()
                                 : "<" + std::string(node.IsMap() ? "map" : "sequence") + ">",
                             "wrong type");
    }
}

/// Like ReadOptional but the key must be present.
template <typename T>
void ReadRequired(const std::string& file,
                  const YAML::Node& map,
                  const std::string& path,
                  const char* key,
                  T& out) {
    if (!map[key]) {
        throw MakeInputError(Where(file, map), path + "." + key, "", "required key is missing");
    }
    ReadOptional(file, map, path, key, out);
}

}  // namespace casmap::io
