#include "casmap/drivers/partial_scans.hpp"

#include <cmath>
#include <numbers>

#include "casmap/core/lms200.hpp"
#include "casmap/drivers/scan_codec.hpp"

namespace casmap::drivers {

PartialScanAssembler::PartialScanAssembler(const Variant& variant) : variant_(variant) {}

std::optional<core::Scan> PartialScanAssembler::Add(const core::Scan& partial) {
    const int turns = variant_.Turns();
    if (turns == 1) {
        return partial;  // at 1 deg every turn is a complete scan
    }
    const double res_rad =
        static_cast<double>(variant_.resolution_cdeg) / 100.0 * std::numbers::pi / 180.0;
    const int p = static_cast<int>(
        std::lround((partial.start_angle_rad - StartAngleRad(variant_)) / res_rad));
    const double turn_s = core::Lms200Timing::kTurnPeriodS;
    // Turn p's beam 0 comes one turn plus one resolution step after turn p - 1's.
    const double step_s = static_cast<double>(variant_.resolution_cdeg) / 100.0 / 360.0 * turn_s;
    const bool follows =
        !parts_.empty() && p == static_cast<int>(parts_.size()) &&
        std::abs(partial.stamp_s - parts_.back().stamp_s - turn_s - step_s) < 0.25 * turn_s;
    if (p == 0) {
        if (!parts_.empty()) {
            ++incomplete_;
        }
        parts_.assign(1, partial);
    } else if (follows) {
        parts_.push_back(partial);
    } else {
        if (!parts_.empty()) {
            ++incomplete_;
        }
        parts_.clear();
        return std::nullopt;
    }
    if (static_cast<int>(parts_.size()) < turns) {
        return std::nullopt;
    }
    // Interleave: global beam g = p + turns * i.
    MeasuredValues all;
    const std::size_t count = static_cast<std::size_t>(variant_.BeamCount());
    core::Scan scan;
    scan.beams.resize(count);
    for (int q = 0; q < turns; ++q) {
        const core::Scan& s = parts_[static_cast<std::size_t>(q)];
        for (std::size_t i = 0; i < s.beams.size(); ++i) {
            const std::size_t g = static_cast<std::size_t>(q) + static_cast<std::size_t>(turns) * i;
            if (g < count) {
                scan.beams[g] = s.beams[i];
            }
        }
    }
    // Geometry and timing exactly as a complete scan of mode 0x24 (ScanFromValues).
    all.values.assign(count, 0);
    core::Scan shape = ScanFromValues(all, core::Lms200Format{}, variant_, parts_[0].stamp_s);
    shape.beams = std::move(scan.beams);
    parts_.clear();
    return shape;
}

}  // namespace casmap::drivers
