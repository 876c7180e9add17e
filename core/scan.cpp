#include "casmap/core/scan.hpp"

namespace casmap::core {
namespace {
constexpr std::array<std::string_view, kBeamStatusCount> kStatusNames = {
    "ok", "no_return", "dazzle", "overflow", "low_signal", "read_error", "out_of_range"};
constexpr std::array<std::string_view, kBeamLabelCount> kLabelNames = {
    "valid", "mixed", "missing", "spike", "no_target", "dazzled"};
}  // namespace

std::string_view ToString(BeamStatus status) {
    return kStatusNames.at(static_cast<std::size_t>(status));
}

std::string_view ToString(BeamLabel label) {
    return kLabelNames.at(static_cast<std::size_t>(label));
}

std::optional<BeamLabel> BeamLabelFromString(std::string_view name) {
    for (std::size_t i = 0; i < kLabelNames.size(); ++i) {
        if (kLabelNames[i] == name) {
            return static_cast<BeamLabel>(i);
        }
    }
    return std::nullopt;
}

}  // namespace casmap::core
