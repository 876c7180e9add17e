#pragma once

// The pipeline names the fields of its option structs in errors ("courses"); the CLI user
// typed flags ("--courses"). This maps one to the other at the command boundary.

#include <functional>
#include <map>
#include <string>

namespace casmap::app {

/// Options field -> flag, e.g. {"courses", "--courses"}.
using FlagNames = std::map<std::string, std::string>;

/// Runs `body`; an InputError about the options struct itself (no file or position: empty
/// `where()`) whose field is (or starts with "<name> " / "<name>[") a mapped options field is
/// rethrown naming the flag instead. Other errors pass unchanged: an error inside a file
/// ("rig.yaml:3:3: speed_m_s (duplicate key)") keeps the file's field name.
void WithFlagNames(const FlagNames& names, const std::function<void()>& body);

/// As WithFlagNames, for libraries that write rules in terms of their fields: a `where()`-less
/// InputError whose field, or each " / "-separated part of it, is a mapped options field is
/// rethrown as "command line: <flags> = <value> (<rule>)", every mapped field name standing as
/// a word in the rule replaced by its flag ("scene and motion go together" -> "--scene and
/// --motion go together") except the error's own single field ("baud = 7 (... 500000 baud)").
/// Other errors pass unchanged.
void WithCommandLineFlags(const FlagNames& names, const std::function<void()>& body);

/// Runs `body`; an InputError whose where() is `where` (a library's name for a settings list,
/// e.g. mapper::FilterParams' "filter parameters") is rethrown with `flag` in its place
/// ("filter parameters: k = 9 (...)" -> "--set: k = 9 (...)"). Other errors pass unchanged.
void WithWhereAsFlag(const std::string& where,
                     const std::string& flag,
                     const std::function<void()>& body);

/// WithWhereAsFlag for mapper::FilterParams' errors, which the CLI takes as --set NAME=VALUE.
inline void WithSetFlag(const std::function<void()>& body) {
    WithWhereAsFlag("filter parameters", "--set", body);
}

}  // namespace casmap::app
