#pragma once

// Sizes read from files and flags are checked against these limits BEFORE anything is
// allocated, so a tiny hostile input cannot make casmap allocate gigabytes (docs/limits.md
// gives the reason for each figure). Every limit is far above what the paper's experiments
// and the bundled courses need.

#include <cstdint>
#include <string>

namespace casmap::core::limits {

/// Map cells of one grid (rows x cols): 25 M cells = 100 MB per float layer; the bundled
/// courses need < 1 M at 25 mm.
inline constexpr std::uint64_t kMaxGridCells = 25'000'000;
/// Scans of one run: 100 000 scans = 22 min at the LMS 200's 75 Hz.
inline constexpr std::uint64_t kMaxScans = 100'000;
/// Beams of one scan: the LMS 200 sends at most 401 (100 deg at 0.25 deg).
inline constexpr std::uint64_t kMaxBeamsPerScan = 1'000;
/// Timed poses of one run or pose file: 2 M poses = 128 MB.
inline constexpr std::uint64_t kMaxPoses = 2'000'000;
/// Simulated motion of one run (rig course length / speed): 20 min.
inline constexpr double kMaxRunDurationS = 1200.0;
/// Length and width of a rig course.
inline constexpr double kMaxCourseLengthM = 1000.0;
/// Size of any object of a scene, and distance of its pose from the origin.
inline constexpr double kMaxSceneExtentM = 10'000.0;
/// YAML files (configs, scenes, rigs): bytes, nodes visited (aliases counted every time they
/// are used, so alias bombs stop here) and nesting depth.
inline constexpr std::uint64_t kMaxYamlBytes = 4u << 20;
inline constexpr std::uint64_t kMaxYamlNodes = 200'000;
inline constexpr int kMaxYamlDepth = 64;
/// One line of a pose file.
inline constexpr std::uint64_t kMaxPoseLineBytes = 4096;
/// Pixels of a TIFF map (same as the grid limit).
inline constexpr std::uint64_t kMaxImagePixels = kMaxGridCells;
/// Bytes of a file read whole into memory (TIFF maps, meshes).
inline constexpr std::uint64_t kMaxFileBytes = 1u << 30;
/// Vertices or faces of an imported mesh (10 M = 120 MB of float vertices).
inline constexpr std::uint64_t kMaxMeshElements = 10'000'000;
/// Corners of one mesh polygon with more than 4 corners, and of all such polygons of a mesh.
/// assimp's triangulation (ear clipping) takes time quadratic in a polygon's corners: a 900 KB
/// OBJ holding one 32 000-corner polygon took 20 s. These bound it to about 2 s.
inline constexpr std::uint64_t kMaxPolygonCorners = 1024;
inline constexpr std::uint64_t kMaxPolygonCornersTotal = 100'000;

/// Throws InputError "<where>: <field> = <size> (<what> limit <limit>, see docs/limits.md)"
/// when `size` > `limit`.
void CheckLimit(const std::string& where,
                const std::string& field,
                std::uint64_t size,
                std::uint64_t limit,
                const std::string& what);

}  // namespace casmap::core::limits
