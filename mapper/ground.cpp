// Ground-relative votes (mapper/ground.hpp, docs/paper-notes.md "Ground-relative votes on
// terrain").
#include "casmap/mapper/ground.hpp"

#include <cmath>
#include <cstdint>
#include <limits>

#include "casmap/mapper/cas_variants.hpp"

namespace casmap::mapper {

core::MapF LocalGroundEstimate(const core::MapF& elevation,
                               const core::MapF& certainty,
                               int k,
                               double quantile) {
    return detail::LocalGround(elevation, certainty, k, quantile);
}

core::MapF GroundRelativeVotes(const core::MapF& elevation,
                               const core::MapF& certainty,
                               const CasParams& params,
                               const FilterResult& cleaned) {
    core::MapF votes = cleaned.elevation;
    if (params.unknown != Unknown::kNaN || params.ground != Ground::kZero) {
        return votes;
    }
    const auto removed = static_cast<std::uint8_t>(PixelClass::kRemoved);
    const auto filled = static_cast<std::uint8_t>(PixelClass::kFilled);
    const std::size_t cells = votes.data.size();
    core::MapF ground;
    for (std::size_t n = 0; n < cells; ++n) {
        const bool known = certainty.data[n] > 0.0F && !std::isnan(elevation.data[n]);
        if (cleaned.classes.data[n] == removed && known) {
            if (ground.data.empty()) {
                ground =
                    detail::LocalGround(elevation, certainty, params.k, params.ground_quantile);
            }
            votes.data[n] = ground.data[n];
        } else if (cleaned.classes.data[n] == filled && !known) {
            votes.data[n] = std::numeric_limits<float>::quiet_NaN();
        }
    }
    return votes;
}

}  // namespace casmap::mapper
