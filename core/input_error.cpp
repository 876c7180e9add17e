#include "casmap/core/input_error.hpp"

namespace casmap {

InputError MakeInputError(const std::string& where,
                          const std::string& field,
                          const std::string& value,
                          const std::string& rule) {
    std::string message = where.empty() ? std::string() : where + ": ";
    message += field;
    if (!value.empty()) {
        message += " = " + value;
    }
    message += " (" + rule + ")";
    return InputError(message);
}

}  // namespace casmap
