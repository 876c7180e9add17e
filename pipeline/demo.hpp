#pragma once

// `casmap demo`: all five filters on the synthetic elevation/certainty pair with exact truth
// (mapper/synthetic_map.hpp), scored over the paper's 200 x 80 PI region, and optionally every
// map written as TIFF + PNG. Prints nothing; the CLI prints the table.

#include <cstdint>
#include <filesystem>
#include <vector>

#include "casmap/mapper/filters.hpp"
#include "casmap/mapper/metrics.hpp"
#include "casmap/mapper/synthetic_map.hpp"

namespace casmap::pipeline {

struct DemoOptions {
    std::uint64_t seed = 1;       ///< of the synthetic map
    mapper::FilterParams params;  ///< every filter's; params.cas.a is also the map's increment
};

struct DemoResult {
    mapper::SyntheticMap map;
    mapper::Region region;                       ///< the PI region (Eq. 11)
    std::vector<mapper::FilterMethod> methods;   ///< mapper::AllFilterMethods(): CAS first
    std::vector<mapper::FilterResult> results;   ///< one per method
    std::vector<mapper::FilterMetrics> metrics;  ///< one per method
    mapper::ClassReport cas_classes;             ///< Table II shares of the CAS result
};

/// Validates the parameters (InputError, "filter parameters" where), builds the map and runs
/// the filters on `threads` threads (0: all cores); the result does not depend on `threads`.
[[nodiscard]] DemoResult RunDemo(const DemoOptions& options, int threads);

/// Writes elevation, certainty, truth and filtered_<method> as DIR/<name>.tiff + .png, and
/// DIR/cas_classes.png; creates DIR. Each file atomically.
void WriteDemoMaps(const DemoResult& result, const std::filesystem::path& dir);

}  // namespace casmap::pipeline
