#include "casmap/mapper/filter_inputs.hpp"

#include <cmath>

#include "casmap/core/input_error.hpp"
#include "casmap/core/text.hpp"

namespace casmap::mapper {
namespace {

std::string Shape(const core::MapF& map) {
    return std::to_string(map.rows) + "x" + std::to_string(map.cols);
}

// The first pixel breaking the rule, named by row and column (the map's own indices).
void CheckPixels(const core::MapF& map,
                 const std::string& name,
                 bool non_negative,
                 bool allow_nan) {
    for (int i = 0; i < map.rows; ++i) {
        for (int j = 0; j < map.cols; ++j) {
            const float v = map.at(i, j);
            if (allow_nan && std::isnan(v)) {
                continue;
            }
            if (std::isfinite(v) && !(non_negative && v < 0.0F)) {
                continue;
            }
            const std::string rule =
                non_negative ? "must be finite and >= 0"
                : allow_nan  ? "must be finite or NaN"
                             : "must be finite (NaN, an unknown cell, needs the filter parameter "
                               "unknown=nan)";
            throw MakeInputError(
                name, "pixel (row " + std::to_string(i) + ", col " + std::to_string(j) + ")",
                core::FormatNumber(v), rule);
        }
    }
}

}  // namespace

bool NeedsCertainty(FilterMethod method) {
    return method == FilterMethod::kCas || method == FilterMethod::kCasTerrain ||
           method == FilterMethod::kCasTrail || method == FilterMethod::kCasMedian ||
           method == FilterMethod::kCasEdge || method == FilterMethod::kCasHybrid;
}

void CheckFilterInputs(FilterMethod method,
                       const core::MapF& elevation,
                       const core::MapF& certainty,
                       const FilterParams& params,
                       const FilterInputNames& names) {
    const bool has_certainty = !certainty.data.empty() || certainty.rows > 0 || certainty.cols > 0;
    if (NeedsCertainty(method) && !has_certainty) {
        throw MakeInputError("", "certainty", "",
                             "required for method " + std::string(ToString(method)));
    }
    if (has_certainty && !certainty.SameShape(elevation)) {
        throw MakeInputError(
            names.certainty, "shape", Shape(certainty),
            "must equal the elevation map's " + Shape(elevation) + " (" + names.elevation + ")");
    }
    CheckPixels(elevation, names.elevation, false, params.cas.unknown == Unknown::kNaN);
    if (has_certainty) {
        CheckPixels(certainty, names.certainty, true, false);
    }
}

}  // namespace casmap::mapper
