#include "casmap/core/text.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <cstdlib>

namespace casmap::core {

std::vector<std::string> SplitList(std::string_view text, char separator) {
    std::vector<std::string> parts;
    std::size_t start = 0;
    while (start < text.size()) {
        const std::size_t end = text.find(separator, start);
        if (end == std::string_view::npos) {
            parts.emplace_back(text.substr(start));
            break;
        }
        parts.emplace_back(text.substr(start, end - start));
        start = end + 1;
    }
    return parts;
}

std::optional<double> ParseFiniteDouble(std::string_view text) {
    double v = 0.0;
    const char* last = text.data() + text.size();
    const auto [ptr, ec] = std::from_chars(text.data(), last, v);
    if (text.empty() || ec != std::errc() || ptr != last || !std::isfinite(v)) {
        return std::nullopt;
    }
    return v;
}

std::optional<int> ParseWholeInt(std::string_view text) {
    int v = 0;
    const char* last = text.data() + text.size();
    const auto [ptr, ec] = std::from_chars(text.data(), last, v);
    if (text.empty() || ec != std::errc() || ptr != last) {
        return std::nullopt;
    }
    return v;
}

std::optional<std::vector<double>> ParseNumberList(std::string_view text, std::size_t count) {
    if (!text.empty() && text.back() == ',') {
        return std::nullopt;
    }
    std::vector<double> out;
    for (const std::string& part : SplitList(text)) {
        const std::optional<double> v = ParseFiniteDouble(part);
        if (!v) {
            return std::nullopt;
        }
        out.push_back(*v);
    }
    if (out.size() != count) {
        return std::nullopt;
    }
    return out;
}

std::string FormatNumber(double value) {
    if (std::isnan(value)) {
        return ".nan";
    }
    if (std::isinf(value)) {
        return value > 0 ? ".inf" : "-.inf";
    }
    if (value == 0.0) {
        return "0";  // also for -0: one spelling for zero
    }
    char buffer[32];  // the longest shortest double ("-2.2250738585072014e-308") is 24
    const auto [end, error] = std::to_chars(buffer, buffer + sizeof(buffer), value);
    return error == std::errc() ? std::string(buffer, end) : std::string(".nan");
}

std::string FormatNumber(double value, int significant_digits) {
    if (!std::isfinite(value) || value == 0.0) {
        return FormatNumber(value);
    }
    char buffer[48];
    std::snprintf(buffer, sizeof(buffer), "%.*e", std::max(0, significant_digits - 1), value);
    return FormatNumber(std::strtod(buffer, nullptr));
}

}  // namespace casmap::core
