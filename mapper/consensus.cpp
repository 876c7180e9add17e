#include "casmap/mapper/consensus.hpp"

#include "casmap/core/check.hpp"

namespace casmap::mapper {

void ConsensusConfig::Validate(const std::string& where) const {
    const core::Check check(where);
    check.NonNegative("consensus.spread_m", spread_m, "must be finite and >= 0");
    check.That(min_hits >= 2, "consensus.min_hits", min_hits, "must be an integer >= 2");
}

}  // namespace casmap::mapper
