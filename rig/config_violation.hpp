#pragma once

#include <optional>
#include <string>

#include "casmap/core/text.hpp"

namespace casmap::rig {

/// The first rule a rig config breaks: field path (e.g. "table.speed_m_s"), value and rule.
/// io/ turns it into an InputError with file:line:col; Validate() throws it with a plain prefix.
struct ConfigViolation {
    std::string field;
    std::string value;
    std::string rule;
};

/// Throws InputError "<where>: <field> = <value> (<rule>)" if `violation` holds one.
void ThrowIfViolated(const std::optional<ConfigViolation>& violation, const std::string& where);

/// core::FormatNumber, the one number formatter (shortest round-trip form, e.g. "1.5").
using core::FormatNumber;

}  // namespace casmap::rig
