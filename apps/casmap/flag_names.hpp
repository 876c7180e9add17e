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

}  // namespace casmap::app
