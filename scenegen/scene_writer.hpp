#pragma once

// Generated scenes on disk: the scene YAML of DESIGN.md "Scene files" (read back by
// io::LoadScene and `casmap simulate --scene`) and the ground mesh as binary little-endian PLY.
// Pure text/byte producers: the caller writes them (atomically).

#include <string>
#include <vector>

#include "casmap/core/scene.hpp"
#include "casmap/core/text.hpp"
#include "casmap/scenegen/scene_generator.hpp"

namespace casmap::scenegen {

/// core::FormatNumber, the one number formatter (shortest text that reads back exactly).
using core::FormatNumber;

/// The scene as YAML: the ground (mesh `ground_mesh`, terrain: true) and every object; rocks
/// name `rock_files[rock_mesh]` with their per-axis scale. Paths are written as given (relative
/// to the YAML file). `comment` lines are prefixed with "# ".
[[nodiscard]] std::string SceneYaml(const GeneratedScene& scene,
                                    const std::string& ground_mesh,
                                    const std::vector<std::string>& rock_files,
                                    const std::string& comment);

/// Binary little-endian PLY of a triangle mesh (float32 vertices, int32 indices).
[[nodiscard]] std::string PlyBinary(const core::MeshShape& mesh);

}  // namespace casmap::scenegen
