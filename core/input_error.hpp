#pragma once

#include <stdexcept>
#include <string>

namespace casmap {

/// Bad input caught at a boundary (config, scene, run file, CLI, serial stream, options struct).
/// The message names the file (with line:column or byte offset when known), the field,
/// the value and the rule broken, e.g.
/// `scenes/a.yaml:7:3: objects[2].reflectivity = 1.4 (allowed: 0..1)`.
class InputError : public std::runtime_error {
public:
    explicit InputError(const std::string& message) : std::runtime_error(message) {}
    /// The canonical form "<where>: <field> = <value> (<rule>)", parts kept for WithField.
    InputError(std::string where, std::string field, std::string value, std::string rule);

    [[nodiscard]] const std::string& where() const { return where_; }
    /// The field named by MakeInputError (empty for an InputError built from a message).
    [[nodiscard]] const std::string& field() const { return field_; }
    [[nodiscard]] const std::string& value() const { return value_; }
    [[nodiscard]] const std::string& rule() const { return rule_; }
    /// The same error naming `field` instead (a CLI maps an options field to its flag).
    [[nodiscard]] InputError WithField(const std::string& field) const;

private:
    std::string where_;
    std::string field_;
    std::string value_;
    std::string rule_;
};

/// Builds the canonical message: "<where>: <field> = <value> (<rule>)".
[[nodiscard]] InputError MakeInputError(const std::string& where,
                                        const std::string& field,
                                        const std::string& value,
                                        const std::string& rule);

}  // namespace casmap
