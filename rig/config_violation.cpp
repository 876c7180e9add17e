#include "casmap/rig/config_violation.hpp"

#include <sstream>

#include "casmap/core/input_error.hpp"

namespace casmap::rig {

void ThrowIfViolated(const std::optional<ConfigViolation>& violation, const std::string& where) {
    if (violation) {
        throw MakeInputError(where, violation->field, violation->value, violation->rule);
    }
}

std::string FormatNumber(double value) {
    std::ostringstream out;
    out.precision(10);
    out << value;
    return out.str();
}

}  // namespace casmap::rig
