#pragma once

// The mapping stages' parameters (the scan pre-filters, the Kalman mapper's noise model and the
// consensus mapper's cell height) as
// one table of name/value texts. Every writer of an effective configuration (`casmap bench`'s
// `filters:` sections, `casmap map`'s map.yaml `mapper:` sections) renders this table, and the
// bench's stage-map key is made from it, so a field added to a stage's config struct is added
// here once and appears in all of them. Keys are FilterParams::Set's names without the stage
// prefix (`sweep_jump.reach` -> section `sweep_jump`, key `reach`); values read back through
// FilterParams::Set to the same numbers.

#include <string>
#include <string_view>
#include <vector>

#include "casmap/mapper/filter_params.hpp"

namespace casmap::mapper {

/// One parameter: numbers as core::FormatNumber writes them (shortest round trip), integers in
/// decimal, switches as on/off.
struct StageParam {
    std::string key;    // "jump_min_m"
    std::string value;  // "0.1"
};

/// One stage's parameters, in the order of its config struct.
struct StageSection {
    std::string_view stage;  // "shadow" | "range_jump" | "sweep_jump" | "kalman" | "consensus"
    std::vector<StageParam> params;
};

/// The sections of every mapping stage of `params`, in the order shadow, range_jump,
/// sweep_jump, kalman, consensus (whether a pipeline runs a stage is the caller's business).
[[nodiscard]] std::vector<StageSection> StageSections(const FilterParams& params);

}  // namespace casmap::mapper
