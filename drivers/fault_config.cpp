#include <optional>
#include <string>

#include "casmap/core/check.hpp"
#include "casmap/core/input_error.hpp"
#include "casmap/core/text.hpp"
#include "casmap/drivers/virtual_lms200.hpp"

namespace casmap::drivers {
namespace {
// Fault settings are named by their key in the "crc=P,..." spec; a CLI shows "faults" as its
// flag.
const char* const kWhere = "faults";

}  // namespace

void FaultConfig::Validate() const {
    const core::Check check(kWhere);
    const char* const probability = "a probability in [0, 1]";
    check.That(crc_rate >= 0.0 && crc_rate <= 1.0, "crc", crc_rate, probability);
    check.That(garbage_rate >= 0.0 && garbage_rate <= 1.0, "garbage", garbage_rate, probability);
    check.That(drop_rate >= 0.0 && drop_rate <= 1.0, "drop", drop_rate, probability);
    check.That(collide_rate >= 0.0 && collide_rate <= 1.0, "collide", collide_rate, probability);
    check.That(disconnect_period_s >= 0.0, "disconnect", disconnect_period_s,
               "seconds >= 0 (0 = never)");
    check.That(offline_s >= 0.0, "offline_s", offline_s, ">= 0");
}

FaultConfig ParseFaults(std::string_view spec) {
    const core::Check check(kWhere);
    const char* const rule = "NAME=VALUE with NAME in crc, garbage, drop, collide, disconnect";
    FaultConfig f;
    for (const std::string& item : core::SplitList(spec)) {
        const std::size_t eq = item.find('=');
        check.That(eq != std::string::npos, item, "", rule);
        const std::string key = item.substr(0, eq);
        const std::string text = item.substr(eq + 1);
        const std::optional<double> number = core::ParseFiniteDouble(text);
        check.That(number.has_value(), key, text, "a finite number");
        double* const field = key == "crc"          ? &f.crc_rate
                              : key == "garbage"    ? &f.garbage_rate
                              : key == "drop"       ? &f.drop_rate
                              : key == "collide"    ? &f.collide_rate
                              : key == "disconnect" ? &f.disconnect_period_s
                                                    : nullptr;
        check.That(field != nullptr, key, text, rule);
        *field = *number;
    }
    f.Validate();
    return f;
}

void VirtualLms200Config::Validate() const {
    CheckLmsBaud(power_on_baud, "power_on_baud");
    const core::Check check("virtual LMS 200");
    check.That(variant.IsValid(), "variant",
               std::to_string(variant.angle_deg) + "/" + std::to_string(variant.resolution_cdeg),
               "180/100, 180/50, 100/100, 100/50 or 100/25");
    const std::size_t bytes = config.bytes.size();
    check.That(bytes == ConfigBlock::kLongSize || bytes == ConfigBlock::kShortSize, "config bytes",
               std::to_string(bytes), "34 or 32");
    CheckConfigBlock(config, "virtual LMS 200");
    check.That(config_write_s >= 0.0 && reset_s >= 0.0, "config_write_s / reset_s",
               core::FormatNumber(config_write_s) + " / " + core::FormatNumber(reset_s),
               "seconds >= 0");
    faults.Validate();
}

}  // namespace casmap::drivers
