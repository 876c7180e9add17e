#pragma once

// Where casmap's data (scenes/, config/) lives at run time: an installed prefix, a directory
// named by the environment, or the source tree of an in-tree build. No path is trusted just
// because it was compiled in: an installed program finds its own prefix first.

#include <filesystem>
#include <optional>

namespace casmap::pipeline {

/// The data directory, the first of these that holds a `scenes/` folder:
/// 1. $CASMAP_DATA_DIR, when set (an InputError if it is set but has no scenes/ folder);
/// 2. <directory of the running executable>/../share/casmap (an installed casmap);
/// 3. the source tree this library was built from (in-tree builds, tests).
/// InputError naming CASMAP_DATA_DIR when none exists.
[[nodiscard]] std::filesystem::path DataDir();

/// DataDir() without throwing: nullopt when none exists.
[[nodiscard]] std::optional<std::filesystem::path> FindDataDir();

/// DataDir() / "scenes" / "courses": the sixteen obstacle courses of the paper's Table I.
[[nodiscard]] std::filesystem::path CoursesDir();

}  // namespace casmap::pipeline
