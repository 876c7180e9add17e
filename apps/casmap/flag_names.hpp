#pragma once

// The pipeline names the fields of its option structs in errors ("courses"); the CLI user
// typed flags ("--courses"). This maps one to the other at the command boundary.

#include <functional>
#include <map>
#include <string>

namespace casmap::app {

/// Options field -> flag, e.g. {"courses", "--courses"}.
using FlagNames = std::map<std::string, std::string>;

/// Options field -> the path the user gave for it, e.g. {"poses_out", "/tmp/p.txt"}: a library
/// names such a path as the error's where ("/tmp/p.txt: poses_out (folder ... does not exist)").
using FlagPaths = std::map<std::string, std::string>;

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
/// An error whose where() is the path `paths` holds for its (mapped) field, or a file in that
/// folder, keeps its where and names the flag ("/tmp/p.txt: --poses-out (...)"). Other errors
/// pass unchanged.
void WithCommandLineFlags(const FlagNames& names,
                          const std::function<void()>& body,
                          const FlagPaths& paths = {});

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
