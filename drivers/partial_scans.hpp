#pragma once

// Partial scans (output mode 0x2A) back into complete scans: at 0.5 and 0.25 deg the LMS 200
// interleaves 2 or 4 mirror turns, and in mode 0x2A sends each turn's beams as soon as the turn
// ends. A run file holds scans of one geometry, so `casmap record` joins each complete set.

#include <optional>
#include <vector>

#include "casmap/core/scan.hpp"
#include "casmap/drivers/telegram.hpp"

namespace casmap::drivers {

class PartialScanAssembler {
public:
    /// `variant`: the scanner's variant (turns per complete scan = variant.Turns()).
    explicit PartialScanAssembler(const Variant& variant);

    /// Adds one partial scan as Lms200Driver delivers it (beams p, p + turns, ... of turn p,
    /// p from its start angle). Returns the complete scan when this one ends a set of turns
    /// 0..turns-1 of consecutive turns (stamp of beam 0 of turn 0, beam i measured at
    /// (i mod turns) / 75 s + i * resolution / (360 * 75 s), as ScanFromValues), else nullopt.
    /// A set with a turn missing (a lost telegram) is dropped and counted.
    [[nodiscard]] std::optional<core::Scan> Add(const core::Scan& partial);
    /// Sets dropped because a turn was missing.
    [[nodiscard]] std::uint64_t incomplete() const { return incomplete_; }

private:
    Variant variant_;
    std::vector<core::Scan> parts_;  // turns 0..p of the set being collected
    std::uint64_t incomplete_ = 0;
};

}  // namespace casmap::drivers
