#pragma once

// Internal to pipeline/dataset*.cpp: from one sample's draws to the generator's region and the
// simulator's setup (rig, sensor, pose error, grid).

#include <string>

#include "casmap/pipeline/sim_pipeline.hpp"
#include "casmap/scenegen/dataset_spec.hpp"

namespace casmap::pipeline {

/// The scene generator's config for a sample: the spec's ranges, the mapped region, the ground
/// extent the rig needs and (vehicle) the lane kept clear of obstacles.
[[nodiscard]] scenegen::SceneGenConfig SampleSceneConfig(const scenegen::DatasetSpec& spec,
                                                         const scenegen::DomainDraw& draw);

/// The simulator setup of a sample (validated: InputError naming the field otherwise).
[[nodiscard]] SimSetup SampleSetup(const scenegen::DatasetSpec& spec,
                                   const scenegen::DomainDraw& draw,
                                   const std::string& scene_path);

}  // namespace casmap::pipeline
