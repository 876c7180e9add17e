#pragma once

// Scene files (DESIGN.md "Scene files"): YAML with boxes, cylinders and meshes -> core::Scene.
// Built only with CASMAP_BUILD_SIM (io/CMakeLists.txt excludes io/scene_*.cpp otherwise).

#include <string>

#include "casmap/core/scene.hpp"

namespace casmap::io {

/// Loads a scene YAML file and the meshes it names (paths relative to the YAML file) into a
/// core::Scene, poses in the world frame (m, R = Rz(yaw) Ry(pitch) Rx(roll)), meshes scaled to
/// metres. Throws InputError "file:line:col: objects[i].field = value (rule)" for an unknown
/// key, a missing/unreadable/empty mesh, a size <= 0, a reflectivity outside 0..1, a pose that
/// is not six numbers, a duplicate name, or anything of the wrong type.
[[nodiscard]] core::Scene LoadScene(const std::string& path);

}  // namespace casmap::io
