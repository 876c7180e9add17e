#include "casmap/core/check.hpp"

#include <cmath>

#include "casmap/core/text.hpp"

namespace casmap::core {

Check::Check(std::string where, std::string prefix)
    : where_(std::move(where)), prefix_(std::move(prefix)) {}

InputError Check::Error(std::string_view field,
                        std::string_view value,
                        std::string_view rule) const {
    return InputError(where_, prefix_ + std::string(field), std::string(value), std::string(rule));
}

void Check::Fail(std::string_view field, std::string_view value, std::string_view rule) const {
    throw Error(field, value, rule);
}

void Check::That(bool ok, std::string_view field, double value, std::string_view rule) const {
    if (!ok) {
        Fail(field, FormatNumber(value), rule);
    }
}

void Check::That(bool ok,
                 std::string_view field,
                 std::string_view value,
                 std::string_view rule) const {
    if (!ok) {
        Fail(field, value, rule);
    }
}

void Check::Positive(std::string_view field, double value, std::string_view rule) const {
    That(std::isfinite(value) && value > 0.0, field, value, rule.empty() ? "must be > 0" : rule);
}

void Check::NonNegative(std::string_view field, double value, std::string_view rule) const {
    That(std::isfinite(value) && value >= 0.0, field, value, rule.empty() ? "must be >= 0" : rule);
}

void Check::Finite(std::string_view field, double value) const {
    That(std::isfinite(value), field, value, "must be finite");
}

void Check::InRange(std::string_view field, double value, double lo, double hi) const {
    That(std::isfinite(value) && value >= lo && value <= hi, field, value,
         "allowed: " + FormatNumber(lo) + ".." + FormatNumber(hi));
}

void Check::Probability(std::string_view field, double value) const {
    InRange(field, value, 0.0, 1.0);
}

}  // namespace casmap::core
