#pragma once

// A complete structural check of a PLY file (header and body) before assimp reads it.
// assimp 5.2's PLY reader writes past a heap buffer on malformed files (fuzz finding, found with
// valgrind: a property of an unknown type followed by a second header; docs/fuzzing.md), so
// casmap hands it only files that follow the PLY format exactly (Greg Turk's specification):
//   ply
//   format ascii|binary_little_endian|binary_big_endian 1.0
//   comment ... / obj_info ...
//   element <name> <count>
//   property <type> <name>  |  property list <count type> <index type> <name>
//   end_header
// followed by each element's instances in order: one line per instance (ASCII) or the packed
// values (binary). Face indices must name one of the vertices.

#include <cstdint>
#include <string>
#include <string_view>

namespace casmap::io {

/// Throws InputError naming `name`, the line (header, ASCII body) or byte offset (binary body)
/// and the rule broken, unless `bytes` is a well-formed PLY file. Element counts are checked
/// against core::limits::kMaxMeshElements and the file size before anything is allocated, list
/// lengths against core::limits::kMaxPolygonCorners.
void CheckPly(std::string_view bytes, const std::string& name);

}  // namespace casmap::io
