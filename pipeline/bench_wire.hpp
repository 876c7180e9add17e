#pragma once

// One benchmark run as bytes and back, exactly (doubles bit for bit, NaN included): what a rank
// sends to rank 0 when `casmap bench` runs under MPI (distributed.hpp).

#include <string>

#include "casmap/pipeline/benchmark_report.hpp"

namespace casmap::pipeline {

/// A run's score, its name and effective configuration, and (when `sheet` is non-null) its maps.
struct BenchRunRecord {
    BenchRun run;
    std::string name;
    std::string config_yaml;
    bool has_sheet = false;
    SheetMaps sheet;
};

[[nodiscard]] std::string EncodeBenchRun(const BenchRunRecord& record);
/// Throws std::runtime_error on a truncated or malformed payload (a bug, not bad input).
[[nodiscard]] BenchRunRecord DecodeBenchRun(const std::string& bytes);

}  // namespace casmap::pipeline
