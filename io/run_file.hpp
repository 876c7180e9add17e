#pragma once

// Run files (DESIGN.md "Run files"; docs/run-file.md): one HDF5 file per run holding the scans
// (ranges, raw values, statuses, truth labels of simulated runs), the sensor poses, the maps
// once computed, the sensor settings, the seed and the effective configuration as YAML text.
// The HDF5 C API stays inside run_file.cpp.

#include <cstdint>
#include <filesystem>
#include <map>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "casmap/core/grid.hpp"
#include "casmap/core/lms200.hpp"
#include "casmap/core/scan.hpp"
#include "casmap/core/trajectory.hpp"

namespace casmap::io {

/// The maps of a run, all on one grid (/maps). Absent layers are not written.
struct RunMaps {
    std::optional<core::GridGeometry> grid;      // origin and cell size; rows/cols = map shape
    std::optional<core::MapF> elevation_m;       // /maps/elevation_m, Eq. 6 (m)
    std::optional<core::MapF> certainty;         // /maps/certainty, Eq. 5 (counts)
    std::optional<core::MapF> truth_m;           // /maps/truth_m, exact ground truth (m)
    std::map<std::string, core::MapF> filtered;  // /maps/filtered/<method> (m)
    /// /maps/cas_classes: the CAS filter's per-cell class (mapper::PixelClass values).
    std::optional<core::Raster<std::uint8_t>> cas_classes;

    [[nodiscard]] bool empty() const {
        return !elevation_m && !certainty && !truth_m && filtered.empty() && !cas_classes;
    }
};

/// Everything a run file holds. Scan geometry (start angle, step, beam period, per-beam time
/// offsets) is stored once for the run, so all scans must share it and the beam count.
struct RunData {
    std::vector<core::Scan> scans;
    std::vector<core::ScanTruth> truth;  // empty for recorded runs, else one per scan
    core::Trajectory poses;              // world_T_sensor (may be empty, e.g. a fixed scanner)
    RunMaps maps;
    std::optional<core::Lms200Format> format;  // range mode and units, when known
    std::optional<std::uint64_t> seed;         // simulated runs
    std::string config_yaml;                   // the effective configuration (YAML text)
};

/// Writes `data` to `path` atomically (temporary file + rename): an interrupted write leaves no
/// truncated file under `path`. Same data -> byte-identical file (no timestamps). Throws
/// InputError for inconsistent data (beam counts, scan geometry, truth sizes, map shapes) or
/// an unwritable path.
void WriteRunFile(const std::filesystem::path& path, const RunData& data);

/// Reads and validates a run file. Throws InputError naming the file, the dataset or
/// attribute, and the rule when the file is missing, not HDF5, or has a wrong shape or type.
/// Ranges of beams whose status is not kOk are NaN.
/// Sizes (scans, beams, poses, map cells) are checked against core/limits.hpp before reading.
[[nodiscard]] RunData ReadRunFile(const std::filesystem::path& path);

/// ReadRunFile on the bytes of a run file held in memory (HDF5 core driver); `name` names it.
[[nodiscard]] RunData ReadRunFileImage(std::string_view bytes, const std::string& name);

/// Reads only the maps (and their grid) of a run file.
[[nodiscard]] RunMaps ReadRunMaps(const std::filesystem::path& path);

/// Adds or replaces map layers of an existing run file: every layer present in `maps`
/// replaces the stored one, the others are kept. Rewrites the file atomically. If both `maps`
/// and the file hold a grid, they must agree in shape.
void AddRunMaps(const std::filesystem::path& path, const RunMaps& maps);

}  // namespace casmap::io
