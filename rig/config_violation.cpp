#include "casmap/rig/config_violation.hpp"

#include "casmap/core/input_error.hpp"

namespace casmap::rig {

void ThrowIfViolated(const std::optional<ConfigViolation>& violation, const std::string& where) {
    if (violation) {
        throw MakeInputError(where, violation->field, violation->value, violation->rule);
    }
}

}  // namespace casmap::rig
