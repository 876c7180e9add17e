#pragma once

#include <stdexcept>
#include <string>

namespace casmap {

/// Bad input caught at a boundary (config, scene, run file, CLI, serial stream).
/// The message names the file (with line:column or byte offset when known), the field,
/// the value and the rule broken, e.g.
/// `scenes/a.yaml:7:3: objects[2].reflectivity = 1.4 (allowed: 0..1)`.
class InputError : public std::runtime_error {
public:
    explicit InputError(const std::string& message) : std::runtime_error(message) {}
};

/// Builds the canonical message: "<where>: <field> = <value> (<rule>)".
[[nodiscard]] InputError MakeInputError(const std::string& where,
                                        const std::string& field,
                                        const std::string& value,
                                        const std::string& rule);

}  // namespace casmap
