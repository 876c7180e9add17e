#pragma once

#include <optional>
#include <string>

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

/// Number formatting for messages (shortest round-trip form, e.g. "1.5").
[[nodiscard]] std::string FormatNumber(double value);

}  // namespace casmap::rig
