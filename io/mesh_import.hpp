#pragma once

// Triangle-mesh import through assimp (any format it reads: STL, OBJ, PLY, DAE, glTF, ...).
// Built only with CASMAP_BUILD_SIM (io/CMakeLists.txt excludes io/mesh_*.cpp otherwise).

#include <Eigen/Core>
#include <filesystem>
#include <string>
#include <string_view>

#include "casmap/core/scene.hpp"

namespace casmap::io {

/// Reads every triangle of a mesh file into one MeshShape in the file's own frame: node
/// transforms are applied, then each vertex is multiplied component-wise by `scale` (file units
/// to metres). Points and lines are ignored; polygons are triangulated.
/// Throws InputError "<path>: mesh (<rule>)" when the file is missing, unreadable, holds no
/// triangle, or has a non-finite vertex. `scale` must be positive and finite (checked).
/// Element counts declared in a header (PLY `element` lines, binary STL triangle count) and the
/// file size are checked against core/limits.hpp before assimp allocates anything.
[[nodiscard]] core::MeshShape ImportMesh(const std::filesystem::path& path,
                                         const Eigen::Vector3d& scale);

/// ImportMesh on bytes in memory; `format_hint` is the file extension ("ply", "stl", "obj", ...)
/// and `name` names the bytes in messages. The same checks apply.
[[nodiscard]] core::MeshShape ImportMeshFromMemory(std::string_view bytes,
                                                   const std::string& format_hint,
                                                   const std::string& name,
                                                   const Eigen::Vector3d& scale);

}  // namespace casmap::io
