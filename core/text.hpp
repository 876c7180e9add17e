#pragma once

// The one comma-list parser and the one number formatter of casmap: every "A,B,C" value (grids,
// poses, vectors, course and test lists) is split and its numbers read here, and every number
// written as text (YAML configs, scene files, messages) is formatted here, so they all accept
// and produce the same spellings.

#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace casmap::core {

/// "a,b,c" -> {"a", "b", "c"}; "" -> {}; an empty item stays empty ("a,,b" -> 3 items) except
/// a trailing separator, which ends the list ("a,b," -> 2 items).
[[nodiscard]] std::vector<std::string> SplitList(std::string_view text, char separator = ',');

/// The whole of `text` as a finite double (std::from_chars: no spaces, no leading '+').
[[nodiscard]] std::optional<double> ParseFiniteDouble(std::string_view text);

/// The whole of `text` as an int (std::from_chars); nullopt when empty or not an integer.
[[nodiscard]] std::optional<int> ParseWholeInt(std::string_view text);

/// A comma list of exactly `count` finite numbers; nullopt otherwise (a trailing comma too).
[[nodiscard]] std::optional<std::vector<double>> ParseNumberList(std::string_view text,
                                                                 std::size_t count);

/// The shortest text that reads back to exactly `value` (std::to_chars, e.g. "0.1", "1e-05",
/// "1000"); "0" for -0; YAML's ".nan", ".inf", "-.inf" for the non-finite values.
[[nodiscard]] std::string FormatNumber(double value);

/// `value` rounded to `significant_digits` (>= 1) significant digits, then as FormatNumber
/// writes it: for labels meant to be read, not re-read (PNG legends: 1234.5 at 3 -> "1230",
/// 0.012345 -> "0.0123").
[[nodiscard]] std::string FormatNumber(double value, int significant_digits);

}  // namespace casmap::core
