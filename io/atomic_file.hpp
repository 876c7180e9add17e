#pragma once

#include <filesystem>
#include <functional>
#include <string>

namespace casmap::io {

/// Writes `path` atomically: `write(tmp_path)` fills a temporary file beside it, which is then
/// renamed over `path`. If `write` throws, the temporary file is removed and `path` is left as
/// it was. Throws InputError if the directory is missing or not writable.
void WriteAtomically(const std::filesystem::path& path,
                     const std::function<void(const std::filesystem::path& tmp_path)>& write);

/// Writes a text file atomically.
void WriteTextAtomically(const std::filesystem::path& path, const std::string& text);

/// Creates `dir` (and parents) or throws InputError naming it.
void EnsureDirectory(const std::filesystem::path& dir);

}  // namespace casmap::io
