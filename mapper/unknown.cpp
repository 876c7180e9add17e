#include "casmap/mapper/unknown.hpp"

#include "casmap/core/input_error.hpp"

namespace casmap::mapper {

Unknown ParseUnknown(std::string_view value, const std::string& where, const std::string& field) {
    if (value == "zero") {
        return Unknown::kZero;
    }
    if (value == "nan") {
        return Unknown::kNaN;
    }
    throw MakeInputError(where, field, std::string(value), "allowed: zero|nan");
}

std::string_view ToString(Unknown unknown) { return unknown == Unknown::kNaN ? "nan" : "zero"; }

}  // namespace casmap::mapper
