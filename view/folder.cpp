#include "casmap/view/folder.hpp"

#include <array>
#include <cstdlib>
#include <system_error>
#include <utility>

#include "casmap/core/input_error.hpp"

#ifndef CASMAP_VIEW_SOURCE_WEB_DIR
#define CASMAP_VIEW_SOURCE_WEB_DIR ""
#endif

namespace casmap::view {
namespace fs = std::filesystem;

std::string ToString(FolderKind kind) {
    switch (kind) {
        case FolderKind::kBench:
            return "bench";
        case FolderKind::kSweep:
            return "sweep";
        case FolderKind::kDataset:
            return "dataset";
        case FolderKind::kLive:
            return "live";
    }
    return "bench";
}

FolderKind ClassifyFolder(const fs::path& dir) {
    std::error_code ec;
    if (!fs::is_directory(dir, ec)) {
        throw MakeInputError(dir.string(), "DIR", dir.string(), "not a directory");
    }
    static const std::array<std::pair<const char*, FolderKind>, 4> kMarkers = {{
        {"bench.json", FolderKind::kBench},
        {"sweep.json", FolderKind::kSweep},
        {"manifest.jsonl", FolderKind::kDataset},
        {"status.json", FolderKind::kLive},
    }};
    for (const auto& [file, kind] : kMarkers) {
        if (fs::is_regular_file(dir / file, ec)) {
            return kind;
        }
    }
    throw MakeInputError(dir.string(), "DIR", dir.string(),
                         "holds none of bench.json (casmap bench), sweep.json (casmap sweep), "
                         "manifest.jsonl (casmap dataset), status.json (casmap live)");
}

namespace {
fs::path ExecutableDir() {
    std::error_code ec;
    const fs::path exe = fs::read_symlink("/proc/self/exe", ec);
    return ec ? fs::path() : exe.parent_path();
}
}  // namespace

fs::path FindWebDir() {
    std::error_code ec;
    if (const char* env = std::getenv("CASMAP_WEB_DIR"); env != nullptr && *env != '\0') {
        if (!fs::is_regular_file(fs::path(env) / "index.html", ec)) {
            throw MakeInputError("", "CASMAP_WEB_DIR", env, "must be a folder with index.html");
        }
        return fs::canonical(env);
    }
    const fs::path exe_dir = ExecutableDir();
    for (const fs::path& dir :
         {exe_dir.empty() ? fs::path() : exe_dir.parent_path() / "share" / "casmap" / "web",
          fs::path(CASMAP_VIEW_SOURCE_WEB_DIR)}) {
        if (!dir.empty() && fs::is_regular_file(dir / "index.html", ec)) {
            return fs::canonical(dir);
        }
    }
    throw MakeInputError("", "web files", "share/casmap/web",
                         "index.html not found beside the executable or in the source tree; "
                         "set CASMAP_WEB_DIR");
}

}  // namespace casmap::view
