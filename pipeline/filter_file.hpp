#pragma once

// Filtering an elevation map held in files (`casmap filter`): reads the elevation (and
// certainty) TIFFs, runs one filter, and writes OUT.tiff, OUT.png and, for the CAS family,
// OUT_classes.tiff (the PixelClass codes as floats: 0 untouched, 1 removed, 2 filled,
// 3 unprocessed border) and OUT_classes.png. Everything is computed before the first file is
// written; each file is written atomically. Prints nothing.

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "casmap/io/image.hpp"
#include "casmap/mapper/filters.hpp"
#include "casmap/mapper/metrics.hpp"

namespace casmap::pipeline {

struct FilterFileOptions {
    std::string method;     ///< mapper::ParseFilterMethod's names (cas, wiener, ...)
    std::string elevation;  ///< elevation map H: 32-bit float TIFF (m)
    std::string certainty;  ///< certainty map C: 32-bit float TIFF (counts); CAS family only
    std::string out;        ///< OUT.tiff or OUT.tif; OUT.png and OUT_classes.* beside it
    mapper::FilterParams params;

    /// method known, `out` a .tiff/.tif in an existing folder, `params` valid, a certainty
    /// file for the CAS family: InputError naming the field (method, out, certainty) or, for a
    /// parameter, mapper::FilterParams' "filter parameters" where.
    void Validate() const;
};

struct FilterFileResult {
    mapper::FilterResult result;
    std::optional<mapper::ClassReport> classes;  ///< the CAS family only
    std::vector<std::filesystem::path> written;  ///< in the order written
};

/// The legend of the CAS class PNGs: untouched, removed, filled, border (BGR colours).
[[nodiscard]] const std::vector<io::ClassLegendEntry>& CasClassLegend();

/// `<out folder>/<out stem><suffix><ext>`: the file names written beside OUT.tiff.
[[nodiscard]] std::filesystem::path BesideOutput(const std::filesystem::path& out,
                                                 const std::string& suffix,
                                                 const std::string& ext);

/// Validates, reads the maps (InputError naming a bad file), filters and writes the outputs.
[[nodiscard]] FilterFileResult FilterMapFiles(const FilterFileOptions& options);

}  // namespace casmap::pipeline
