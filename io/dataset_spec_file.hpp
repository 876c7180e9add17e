#pragma once

// Dataset specs on disk (docs/commands/dataset.md): YAML <-> scenegen::DatasetSpec.

#include <string>

#include "casmap/scenegen/dataset_spec.hpp"

namespace casmap::io {

/// Loads and validates a dataset spec. Missing keys keep their defaults; an unknown key, a
/// wrong type or a value outside its allowed range throws InputError naming the file
/// (line:column where known), the field and the rule.
[[nodiscard]] scenegen::DatasetSpec LoadDatasetSpec(const std::string& path);

/// The spec as YAML in the format LoadDatasetSpec reads (every key, effective values).
[[nodiscard]] std::string DatasetSpecToYaml(const scenegen::DatasetSpec& spec);

}  // namespace casmap::io
