#include "casmap/core/input_error.hpp"

namespace casmap {
namespace {
std::string Message(const std::string& where,
                    const std::string& field,
                    const std::string& value,
                    const std::string& rule) {
    std::string message = where.empty() ? std::string() : where + ": ";
    message += field;
    if (!value.empty()) {
        message += " = " + value;
    }
    message += " (" + rule + ")";
    return message;
}
}  // namespace

InputError::InputError(std::string where, std::string field, std::string value, std::string rule)
    : std::runtime_error(Message(where, field, value, rule)),
      where_(std::move(where)),
      field_(std::move(field)),
      value_(std::move(value)),
      rule_(std::move(rule)) {}

InputError InputError::WithField(const std::string& field) const {
    if (field_.empty() && where_.empty() && rule_.empty()) {
        return *this;  // built from a plain message: nothing to rename
    }
    return InputError(where_, field, value_, rule_);
}

InputError MakeInputError(const std::string& where,
                          const std::string& field,
                          const std::string& value,
                          const std::string& rule) {
    return InputError(where, field, value, rule);
}

}  // namespace casmap
