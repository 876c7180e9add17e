#include "casmap/drivers/scan_list_source.hpp"

#include <cmath>
#include <numbers>
#include <string>

#include "casmap/core/input_error.hpp"
#include "casmap/drivers/scan_codec.hpp"

namespace casmap::drivers {

std::optional<Variant> VariantOf(const core::Scan& scan) {
    const double step_cdeg = scan.angle_step_rad * 180.0 / std::numbers::pi * 100.0;
    for (const Variant v : {Variant{180, 100}, Variant{180, 50}, Variant{100, 100},
                            Variant{100, 50}, Variant{100, 25}}) {
        if (scan.beams.size() == static_cast<std::size_t>(v.BeamCount()) &&
            std::abs(step_cdeg - v.resolution_cdeg) < 1e-3 &&
            std::abs(scan.start_angle_rad - StartAngleRad(v)) < 1e-6) {
            return v;
        }
    }
    return std::nullopt;
}

ScanListSource::ScanListSource(std::vector<core::Scan> scans, const std::string& what)
    : scans_(std::move(scans)) {
    if (scans_.empty()) {
        throw MakeInputError(what, "scans", "0", "at least one scan to serve");
    }
    const std::optional<Variant> v = VariantOf(scans_.front());
    if (!v) {
        throw MakeInputError(what, "scans[0]",
                             std::to_string(scans_.front().beams.size()) + " beams",
                             "181, 361 (180 deg) or 101, 201, 401 (100 deg) beams at the "
                             "LMS 200's angles");
    }
    variant_ = *v;
    for (std::size_t i = 1; i < scans_.size(); ++i) {
        if (VariantOf(scans_[i]) != v) {
            throw MakeInputError(what, "scans[" + std::to_string(i) + "]", "",
                                 "same beam geometry as scans[0]");
        }
    }
}

std::optional<core::Scan> ScanListSource::Sweep(std::uint64_t index, const Variant& variant) {
    if (index >= scans_.size() || !Supports(variant)) {
        return std::nullopt;
    }
    return scans_[index];
}

bool ScanListSource::Supports(const Variant& variant) const { return variant == variant_; }

}  // namespace casmap::drivers
