#pragma once

// Named pipelines of `casmap bench` (issue 10 section 5): a pipeline is a mapper mode (the
// paper's Eq. 1-6 or the Kalman mapper), an optional scan pre-filter (shadow | range_jump |
// sweep_jump) and a map filter (raw = none, the paper's five, or the CAS variants). The
// unknown-cell convention is the run's (0 on the paper's courses, NaN on terrain scenes; --set
// unknown=). Names are stable: bench.json keys runs[].filters.<name> by them. docs/paper-notes.md
// "Named pipelines" defines each.

#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "casmap/mapper/filter_params.hpp"
#include "casmap/pipeline/map_run.hpp"

namespace casmap::pipeline {

struct PipelineSpec {
    std::string name;
    MapperMode mode = MapperMode::kPaper;
    Prefilter prefilter = Prefilter::kNone;
    std::optional<mapper::FilterMethod> filter;  // nullopt: the map itself ("raw")
    std::string description;                     // one line, for docs and --help
};

/// Every named pipeline, the paper's five first (cas, wiener, average, median, cwm: exactly
/// the benchmark's columns), then raw, the CAS variants, the Kalman mapper and the
/// pre-filtered pipelines. The order is the order of bench.json and the tables.
[[nodiscard]] const std::vector<PipelineSpec>& AllPipelines();

/// The paper's five filters' names (the default of `casmap bench --pipelines`).
[[nodiscard]] std::vector<std::string> PaperPipelineNames();

/// Every registered name, in AllPipelines() order.
[[nodiscard]] std::vector<std::string> AllPipelineNames();

/// The pipeline called `name`; InputError naming `field` (listing the names) if none is.
[[nodiscard]] const PipelineSpec& FindPipeline(std::string_view name, const std::string& field);

/// "all" or a comma list of names -> the names in AllPipelines() order, no repeats;
/// InputError naming `field` for an unknown name or an empty list.
[[nodiscard]] std::vector<std::string> ParsePipelines(const std::string& text,
                                                      const std::string& field);

/// Throws InputError naming "pipelines" unless every name is registered, none repeated and the
/// list is not empty.
void CheckPipelines(const std::vector<std::string>& names);

/// `names` sorted into AllPipelines() order (unregistered names last, alphabetically).
[[nodiscard]] std::vector<std::string> InPipelineOrder(std::vector<std::string> names);

}  // namespace casmap::pipeline
