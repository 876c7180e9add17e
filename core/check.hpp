#pragma once

// The one validation mechanism of casmap's options structs (the Ceres style): every struct keeps
// its defaults inline and has a `Validate()` that states its rules through a Check, which throws
// the first broken one as an InputError "<where>: <prefix><field> = <value> (<rule>)", numbers
// written by core::FormatNumber. A loader that knows the file passes it as `where`.

#include <concepts>
#include <string>
#include <string_view>

#include "casmap/core/input_error.hpp"

namespace casmap::core {

class Check {
public:
    /// `where` opens each message ("" for an options struct, the file for a loader, or a
    /// component name such as "mapper"); `prefix` goes before each field ("lms200.").
    explicit Check(std::string where = "", std::string prefix = "");

    /// The error for `field` = `value` breaking `rule` (for code that throws it later).
    [[nodiscard]] InputError Error(std::string_view field,
                                   std::string_view value,
                                   std::string_view rule) const;
    /// Throws Error(field, value, rule).
    [[noreturn]] void Fail(std::string_view field,
                           std::string_view value,
                           std::string_view rule) const;

    /// Throws unless `ok`; the number is shown as FormatNumber writes it.
    void That(bool ok, std::string_view field, double value, std::string_view rule) const;
    /// Throws unless `ok`; an integer is shown with all its digits ("500000", not "5e+05").
    template <std::integral T>
    void That(bool ok, std::string_view field, T value, std::string_view rule) const {
        if (!ok) {
            Fail(field, std::to_string(value), rule);
        }
    }
    /// Throws unless `ok`; the value is shown as given.
    void That(bool ok, std::string_view field, std::string_view value, std::string_view rule) const;
    void That(bool ok, std::string_view field, const char* value, std::string_view rule) const {
        That(ok, field, std::string_view(value), rule);
    }

    /// `value` finite and > 0, else "must be > 0" (or `rule` when given).
    void Positive(std::string_view field, double value, std::string_view rule = {}) const;
    /// `value` finite and >= 0, else "must be >= 0" (or `rule` when given).
    void NonNegative(std::string_view field, double value, std::string_view rule = {}) const;
    /// `value` finite, else "must be finite".
    void Finite(std::string_view field, double value) const;
    /// `value` finite and in [lo, hi], else "allowed: LO..HI".
    void InRange(std::string_view field, double value, double lo, double hi) const;
    /// InRange(field, value, 0, 1).
    void Probability(std::string_view field, double value) const;

    [[nodiscard]] const std::string& where() const { return where_; }

private:
    std::string where_;
    std::string prefix_;
};

}  // namespace casmap::core
