#pragma once

// CLI11 validators for flags whose plain conversion would silently accept nonsense
// (issue #13, item 6): CLI11 wraps "-1" into a 64-bit unsigned seed and truncates "1.5";
// NonNegativeNumber prints a 309-digit range. Each check names the rule in a short message.

#include <CLI/CLI.hpp>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>

namespace casmap::app {

/// A seed: a whole number 0..2^64-1 written in decimal digits (no sign, point or exponent).
inline CLI::Validator SeedCheck() {
    return CLI::Validator(
        [](std::string& text) -> std::string {
            const std::string rule = "must be a whole number 0..18446744073709551615";
            if (text.empty() || text.size() > 20 ||
                text.find_first_not_of("0123456789") != std::string::npos) {
                return rule;
            }
            errno = 0;
            (void)std::strtoull(text.c_str(), nullptr, 10);
            return errno == ERANGE ? rule : std::string();
        },
        "SEED", "seed");
}

/// A whole number in [lo, hi], written in decimal digits (an optional leading '-').
inline CLI::Validator WholeNumberCheck(long long lo, long long hi) {
    return CLI::Validator(
        [lo, hi](std::string& text) -> std::string {
            const std::string rule =
                "must be a whole number " + std::to_string(lo) + ".." + std::to_string(hi);
            const std::size_t digits = text.size() > 0 && text[0] == '-' ? 1 : 0;
            if (text.size() <= digits || text.size() > 19 ||
                text.find_first_not_of("0123456789", digits) != std::string::npos) {
                return rule;
            }
            const long long v = std::strtoll(text.c_str(), nullptr, 10);
            return v < lo || v > hi ? rule : std::string();
        },
        "INT", "whole number");
}

/// A finite number in [lo, hi] (rejects nan and inf, which compare false with everything).
inline CLI::Validator FiniteRangeCheck(double lo, double hi) {
    return CLI::Validator(
        [lo, hi](std::string& text) -> std::string {
            char* end = nullptr;
            const double v = std::strtod(text.c_str(), &end);
            if (text.empty() || end == nullptr || *end != '\0' || !std::isfinite(v) || v < lo ||
                v > hi) {
                char rule[96];
                std::snprintf(rule, sizeof(rule), "must be a finite number %g..%g", lo, hi);
                return rule;
            }
            return std::string();
        },
        "NUMBER", "finite number");
}

/// A file name ending in `extension` (e.g. ".png"): the writer encodes that format only.
inline CLI::Validator ExtensionCheck(const std::string& extension) {
    return CLI::Validator(
        [extension](std::string& text) -> std::string {
            const bool ok =
                text.size() > extension.size() &&
                text.compare(text.size() - extension.size(), extension.size(), extension) == 0;
            return ok ? std::string()
                      : "must end in " + extension + " (it is written as " + extension.substr(1) +
                            ")";
        },
        "FILE" + extension, extension + " file");
}

/// --threads: 0 (all cores) or 1..1024.
inline CLI::Validator ThreadsCheck() {
    CLI::Validator check = WholeNumberCheck(0, 1024);
    return check.description("0 (all cores) or 1..1024");
}

/// Adds the checks above to every subcommand's flags of these names, so a new command gets
/// them too: --seed (SeedCheck), --png (ExtensionCheck(".png")), --scans (1..10^9),
/// --duration (finite, 0..10^6 s), --step (finite, 1e-6..10^3).
inline void AddFlagChecks(CLI::App& app) {
    for (CLI::App* sub : app.get_subcommands([](CLI::App*) { return true; })) {
        const auto check = [sub](const char* name, const CLI::Validator& validator) {
            if (CLI::Option* option = sub->get_option_no_throw(name)) {
                option->check(validator);
            }
        };
        check("--seed", SeedCheck());
        check("--png", ExtensionCheck(".png"));
        check("--scans", WholeNumberCheck(1, 1000000000));
        check("--duration", FiniteRangeCheck(0.0, 1e6));
        check("--step", FiniteRangeCheck(1e-6, 1e3));
    }
}

}  // namespace casmap::app
