#pragma once

#include <string>
#include <string_view>

namespace casmap::mapper {

/// What a never-observed cell holds in an elevation map (and what the filters treat as
/// unknown): 0 as in the paper (the default of the paper's benchmark), or NaN as in grid_map
/// and elevation_mapping, so unknown terrain below or above the datum is not mistaken for
/// ground at 0 m. Certainty maps hold 0 for unknown cells either way.
enum class Unknown { kZero, kNaN };

/// "zero" | "nan" -> Unknown; throws InputError naming `where` and `field`.
[[nodiscard]] Unknown ParseUnknown(std::string_view value,
                                   const std::string& where,
                                   const std::string& field);
[[nodiscard]] std::string_view ToString(Unknown unknown);

}  // namespace casmap::mapper
