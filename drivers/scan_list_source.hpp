#pragma once

#include <vector>

#include "casmap/core/scan.hpp"
#include "casmap/drivers/virtual_lms200.hpp"

namespace casmap::drivers {

/// The LMS 200 variant a scan's geometry matches (beam count and angular step), or nullopt.
[[nodiscard]] std::optional<Variant> VariantOf(const core::Scan& scan);

/// Serves a list of scans (a run file, or a simulated run): sweep i is scans[i]; exhausted
/// after the last. Supports only the variant of the scans.
class ScanListSource : public ScanSource {
public:
    /// Throws InputError (naming `what`) if the list is empty or its scans are no LMS 200
    /// variant or differ in geometry.
    ScanListSource(std::vector<core::Scan> scans, const std::string& what);
    std::optional<core::Scan> Sweep(std::uint64_t index, const Variant& variant) override;
    [[nodiscard]] bool Supports(const Variant& variant) const override;
    [[nodiscard]] const Variant& variant() const { return variant_; }
    [[nodiscard]] std::size_t size() const { return scans_.size(); }

private:
    std::vector<core::Scan> scans_;
    Variant variant_;
};

}  // namespace casmap::drivers
