#include "casmap/core/input_error.hpp"

namespace casmap {
namespace {

// A bad value is quoted with at most this many characters: a hostile file cannot turn an
// error message into megabytes, and a message stays one readable line.
constexpr std::size_t kMaxQuotedChars = 48;

std::string Quote(const std::string& value) {
    std::string text;
    for (const char c : value.substr(0, kMaxQuotedChars)) {
        const auto u = static_cast<unsigned char>(c);
        text += (u < 0x20 || u == 0x7f) ? '?' : c;  // keep the message on one line
    }
    if (value.size() > kMaxQuotedChars) {
        text += "... (" + std::to_string(value.size()) + " characters)";
    }
    return text;
}

std::string Message(const std::string& where,
                    const std::string& field,
                    const std::string& value,
                    const std::string& rule) {
    std::string message = where.empty() ? std::string() : where + ": ";
    message += field;
    if (!value.empty()) {
        message += " = " + Quote(value);
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
