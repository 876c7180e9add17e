#pragma once

// A command's outputs are one set (issue #13, item 4): every output path is checked before any
// work, each output is written under a hidden temporary name beside its final name, and the
// set is published at the end by renames in the declared order (the effective config first).
// A set that is not published (an error, an exception) removes its temporaries; temporaries
// left by killed processes (".<name>.tmp<PID>" whose PID no longer runs) are removed the next
// time a set or an atomic write uses the same folder.

#include <filesystem>
#include <string>
#include <vector>

namespace casmap::io {

class OutputSet {
public:
    OutputSet() = default;
    OutputSet(const OutputSet&) = delete;
    OutputSet& operator=(const OutputSet&) = delete;
    /// Removes the temporaries of an unpublished set.
    ~OutputSet();

    /// Declares an output file and returns the temporary path to write it to. Throws
    /// InputError naming `field` and `path` if the path is a folder, its folder is missing
    /// (or cannot be created when `create_parent`) or not writable, or the path was declared.
    [[nodiscard]] std::filesystem::path AddFile(const std::filesystem::path& path,
                                                const std::string& field,
                                                bool create_parent = false);

    /// Declares an output folder written as a whole: returns a fresh temporary folder to fill.
    /// On Publish it replaces `path` (an old folder of that name is removed only then).
    [[nodiscard]] std::filesystem::path AddFolder(const std::filesystem::path& path,
                                                  const std::string& field);

    /// Renames every temporary to its final name, in the order declared. Throws InputError
    /// naming the output whose rename failed (earlier ones stay published).
    void Publish();

private:
    struct Entry {
        std::filesystem::path final_path;
        std::filesystem::path tmp_path;
        std::string field;
        bool folder = false;
    };
    std::vector<Entry> entries_;
    bool published_ = false;
};

/// The hidden temporary name of `path` for this process: "<dir>/.<name>.tmp<PID>".
[[nodiscard]] std::filesystem::path TemporaryPathFor(const std::filesystem::path& path);

/// Removes ".<name>.tmp<PID>" files and folders in `dir` whose process no longer runs.
/// Returns how many were removed. Never throws.
int RemoveStaleTemporaries(const std::filesystem::path& dir) noexcept;

/// Throws InputError naming `field` unless `path` can be written: not a folder, its folder
/// exists (or is created, when `create_parent`) and is writable.
void CheckOutputPath(const std::filesystem::path& path,
                     const std::string& field,
                     bool create_parent = false);

}  // namespace casmap::io
