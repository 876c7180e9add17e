#pragma once

// Maps a URL path onto a file below the served folder, refusing anything that could leave it:
// "..", absolute paths, NUL bytes, backslashes, and symlinks whose target lies outside.

#include <filesystem>
#include <string>
#include <string_view>

namespace casmap::view {

/// Why a path was refused (maps to an HTTP status in the site).
enum class PathVerdict {
    kOk,
    kBadPath,  // "..", empty or absolute, NUL, backslash, too long: 400
    kOutside,  // resolves (through a symlink) outside the root: 403
    kMissing,  // does not exist: 404
};

struct ResolvedPath {
    PathVerdict verdict = PathVerdict::kMissing;
    std::filesystem::path path;  // canonical, set when verdict == kOk
};

/// Longest relative path accepted (bytes).
inline constexpr std::size_t kMaxPathBytes = 1024;

/// Resolves `relative` ("runs/course04_T/raw.tif", already percent-decoded; "" = the root
/// itself) below `root`, which must be canonical (std::filesystem::canonical). The result is
/// canonical and inside `root` (or `root` itself), following symlinks only while they stay
/// inside.
[[nodiscard]] ResolvedPath ResolveUnder(const std::filesystem::path& root,
                                        std::string_view relative);

/// True when canonical `path` is `root` or below it (component-wise, not a string prefix).
[[nodiscard]] bool IsInside(const std::filesystem::path& root, const std::filesystem::path& path);

}  // namespace casmap::view
