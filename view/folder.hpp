#pragma once

// What a served folder holds, told by the file that each casmap command writes at its top:
// bench.json (casmap bench), sweep.json (casmap sweep), manifest.jsonl (casmap dataset),
// status.json (casmap live).

#include <filesystem>
#include <string>

namespace casmap::view {

enum class FolderKind { kBench, kSweep, kDataset, kLive };

/// "bench", "sweep", "dataset", "live".
[[nodiscard]] std::string ToString(FolderKind kind);

/// The kind of `dir` from its marker file. Throws InputError naming `dir` when it is not a
/// directory or holds none of bench.json, sweep.json, manifest.jsonl, status.json.
[[nodiscard]] FolderKind ClassifyFolder(const std::filesystem::path& dir);

/// The page's static files (index.html, app.js, ...): $CASMAP_WEB_DIR if set, else
/// <prefix>/share/casmap/web beside the running executable (<prefix>/bin/casmap), else the
/// source tree's view/web. Throws InputError when the chosen folder has no index.html.
[[nodiscard]] std::filesystem::path FindWebDir();

}  // namespace casmap::view
