#pragma once

#include <string>

namespace casmap::mapper {

/// The consensus cell height, an option beside the paper's Eq. 6 (docs/paper-notes.md
/// "Consensus cell height"): a cell whose heights all lie within `spread_m` of each other, over
/// at least `min_hits` points, holds their mean; any other cell keeps Eq. 6's height of largest
/// magnitude. Eq. 6's largest |z| over N noisy points of a flat surface sits about two standard
/// deviations off it; their mean sits 1 / sqrt(N) of one. A cell that holds two surfaces (a
/// pole and the floor beside it, a box edge, a mixed pixel) spreads wider and keeps Eq. 6.
struct ConsensusConfig {
    double spread_m = 0.02;  // largest max - min of a cell's heights that counts as one surface
    int min_hits = 2;        // fewest points for a mean (a single point is its own Eq. 6 height)
    /// Throws InputError naming consensus.<field>, the message opened by `where` (the owner:
    /// "mapper", "active window").
    void Validate(const std::string& where = "mapper") const;
};

}  // namespace casmap::mapper
