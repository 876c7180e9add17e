#include <cstdlib>
#include <string>

#include "casmap/core/input_error.hpp"
#include "casmap/core/text.hpp"
#include "casmap/drivers/virtual_lms200.hpp"

namespace casmap::drivers {
namespace {
// Fault settings are named by their key in the "crc=P,..." spec; a CLI shows "faults" as its
// flag.
const char* const kWhere = "faults";

void CheckRate(double rate, const std::string& field) {
    if (!(rate >= 0.0 && rate <= 1.0)) {
        throw MakeInputError(kWhere, field, core::FormatNumber(rate), "a probability in [0, 1]");
    }
}
}  // namespace

void FaultConfig::Validate() const {
    CheckRate(crc_rate, "crc");
    CheckRate(garbage_rate, "garbage");
    CheckRate(drop_rate, "drop");
    CheckRate(collide_rate, "collide");
    if (!(disconnect_period_s >= 0.0)) {
        throw MakeInputError(kWhere, "disconnect", core::FormatNumber(disconnect_period_s),
                             "seconds >= 0 (0 = never)");
    }
    if (!(offline_s >= 0.0)) {
        throw MakeInputError(kWhere, "offline_s", core::FormatNumber(offline_s), ">= 0");
    }
}

FaultConfig ParseFaults(std::string_view spec) {
    FaultConfig f;
    std::size_t at = 0;
    while (at < spec.size()) {
        std::size_t end = spec.find(',', at);
        if (end == std::string_view::npos) {
            end = spec.size();
        }
        const std::string item(spec.substr(at, end - at));
        at = end + 1;
        const std::size_t eq = item.find('=');
        const std::string rule = "NAME=VALUE with NAME in crc, garbage, drop, collide, disconnect";
        if (eq == std::string::npos) {
            throw MakeInputError(kWhere, item, "", rule);
        }
        const std::string key = item.substr(0, eq);
        const std::string text = item.substr(eq + 1);
        char* stop = nullptr;
        const double value = std::strtod(text.c_str(), &stop);
        if (text.empty() || stop == nullptr || *stop != '\0') {
            throw MakeInputError(kWhere, key, text, "a number");
        }
        if (key == "crc") {
            f.crc_rate = value;
        } else if (key == "garbage") {
            f.garbage_rate = value;
        } else if (key == "drop") {
            f.drop_rate = value;
        } else if (key == "collide") {
            f.collide_rate = value;
        } else if (key == "disconnect") {
            f.disconnect_period_s = value;
        } else {
            throw MakeInputError(kWhere, key, text, rule);
        }
    }
    f.Validate();
    return f;
}

void VirtualLms200Config::Validate() const {
    CheckLmsBaud(power_on_baud, "power_on_baud");
    if (!variant.IsValid()) {
        throw MakeInputError(
            "virtual LMS 200", "variant",
            std::to_string(variant.angle_deg) + "/" + std::to_string(variant.resolution_cdeg),
            "180/100, 180/50, 100/100, 100/50 or 100/25");
    }
    if (config.bytes.size() != ConfigBlock::kLongSize &&
        config.bytes.size() != ConfigBlock::kShortSize) {
        throw MakeInputError("virtual LMS 200", "config bytes", std::to_string(config.bytes.size()),
                             "34 or 32");
    }
    CheckConfigBlock(config, "virtual LMS 200");
    if (!(config_write_s >= 0.0) || !(reset_s >= 0.0)) {
        throw MakeInputError("virtual LMS 200", "config_write_s / reset_s",
                             std::to_string(config_write_s) + " / " + std::to_string(reset_s),
                             "seconds >= 0");
    }
    faults.Validate();
}

}  // namespace casmap::drivers
