#pragma once

// The mapping stages' parameters (mapper/stage_params.hpp) as YAML, for the effective
// configurations pipeline writes: `casmap bench` (under `filters:`) and `casmap map` (under
// map.yaml's `mapper:`). Private to pipeline (names yaml-cpp; not installed).

#include <yaml-cpp/yaml.h>

#include "casmap/mapper/stage_params.hpp"

namespace casmap::pipeline::detail {

/// `<stage>: {<key>: <value>, ...}` into the open map, the section as one flow map. (map.yaml's
/// sections sit inside the flow map `mapper:`, where yaml-cpp writes every nested map in flow
/// style anyway: both writers' bytes are this renderer's.)
void EmitStageSection(YAML::Emitter& out, const mapper::StageSection& section);

}  // namespace casmap::pipeline::detail
