#include "casmap/pipeline/data_dir.hpp"

#include <cstdlib>
#include <system_error>

#include "casmap/core/input_error.hpp"

#ifndef CASMAP_SOURCE_DATA_DIR
#define CASMAP_SOURCE_DATA_DIR ""
#endif

namespace casmap::pipeline {
namespace {
namespace fs = std::filesystem;

bool HoldsScenes(const fs::path& dir) {
    std::error_code ec;
    return !dir.empty() && fs::is_directory(dir / "scenes", ec);
}

/// <exe dir>/../share/casmap, from /proc/self/exe (Linux); empty when unknown.
fs::path InstalledDataDir() {
    std::error_code ec;
    const fs::path exe = fs::read_symlink("/proc/self/exe", ec);
    if (ec || exe.empty()) {
        return {};
    }
    return exe.parent_path().parent_path() / "share" / "casmap";
}

}  // namespace

std::optional<fs::path> FindDataDir() {
    if (const char* env = std::getenv("CASMAP_DATA_DIR"); env != nullptr && *env != '\0') {
        if (HoldsScenes(env)) {
            return fs::path(env);
        }
        return std::nullopt;  // set but wrong: DataDir() says so rather than guessing
    }
    for (const fs::path& dir : {InstalledDataDir(), fs::path(CASMAP_SOURCE_DATA_DIR)}) {
        if (HoldsScenes(dir)) {
            return dir;
        }
    }
    return std::nullopt;
}

fs::path DataDir() {
    if (std::optional<fs::path> dir = FindDataDir()) {
        return *dir;
    }
    const char* env = std::getenv("CASMAP_DATA_DIR");
    if (env != nullptr && *env != '\0') {
        throw MakeInputError("", "CASMAP_DATA_DIR", env, "must be a directory holding scenes/");
    }
    throw MakeInputError("", "CASMAP_DATA_DIR", "",
                         "casmap's data (scenes/, config/) is neither in <prefix>/share/casmap "
                         "beside the program nor in the source tree; set CASMAP_DATA_DIR");
}

fs::path CoursesDir() { return DataDir() / "scenes" / "courses"; }

}  // namespace casmap::pipeline
