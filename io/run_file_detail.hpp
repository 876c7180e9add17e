#pragma once

// Internals of the run file (io/run_file.cpp, docs/run-file.md), split by direction:
// run_file_write.cpp checks a RunData and writes the HDF5 layout, run_file_read.cpp reads it
// back with the checks of every field. Private to io (names HDF5; not installed).

#include <cstdint>
#include <filesystem>
#include <limits>

#include "casmap/io/hdf5_util.hpp"
#include "casmap/io/run_file.hpp"

namespace casmap::io::detail {

// Version 2 holds no variable-length data (no HDF5 global heap): config_yaml is a fixed-length
// string dataset and the string attributes are fixed-length. Version 1 (config_yaml a
// variable-length attribute) is still read, after a check of its global heap
// (docs/run-file.md).
constexpr std::int32_t kFormatVersion = 2;
constexpr std::int32_t kOldestFormatVersion = 1;
/// /scans/ranges_m of a beam whose status is not ok, and its range once read.
constexpr float kNaN = std::numeric_limits<float>::quiet_NaN();

/// Writes `data` as a new run file at `tmp` (h5::LibraryLock held); InputErrors name `path`,
/// the file `tmp` will replace.
void WriteRunFileTo(const std::filesystem::path& tmp,
                    const std::filesystem::path& path,
                    const RunData& data);

/// InputError unless the file's casmap_run_format_version is one this casmap reads (a file
/// without one is read as the current version).
void CheckVersion(const h5::FileReader& r);

/// The /maps group (empty maps without one); InputError naming the attribute or dataset.
[[nodiscard]] RunMaps ReadMaps(const h5::FileReader& r);

/// The whole run (version, seed, config, scans, poses, maps); InputError naming the object.
[[nodiscard]] RunData ReadRun(const h5::FileReader& r);

}  // namespace casmap::io::detail
