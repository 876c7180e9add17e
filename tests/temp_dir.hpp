#pragma once

// A fresh temporary folder for a test, removed with its contents when the object goes out of
// scope. The name is unique (mkdtemp), so two test runs at once (two build trees, two ctest
// invocations, ctest -j) never share a folder, as fixed names under /tmp did.
#include <stdlib.h>  // mkdtemp (POSIX)

#include <cerrno>
#include <deque>
#include <filesystem>
#include <string>
#include <system_error>
#include <utility>

namespace casmap::test {

class TempDir {
public:
    /// Makes `<temp_directory_path()>/casmap_<prefix>_XXXXXX` (TMPDIR is respected).
    explicit TempDir(const std::string& prefix) {
        const std::filesystem::path root = std::filesystem::temp_directory_path();
        std::string name = (root / ("casmap_" + prefix + "_XXXXXX")).string();
        if (::mkdtemp(name.data()) == nullptr) {
            throw std::system_error(errno, std::generic_category(), "mkdtemp " + name);
        }
        path_ = name;
    }
    TempDir(TempDir&& other) noexcept : path_(std::exchange(other.path_, {})) {}
    TempDir(const TempDir&) = delete;
    TempDir& operator=(const TempDir&) = delete;
    TempDir& operator=(TempDir&&) = delete;
    ~TempDir() {
        if (!path_.empty()) {
            std::error_code ignored;
            std::filesystem::remove_all(path_, ignored);
        }
    }

    /// The folder (absolute).
    [[nodiscard]] const std::filesystem::path& Path() const { return path_; }
    /// `Path() / name`.
    [[nodiscard]] std::filesystem::path operator/(const std::filesystem::path& name) const {
        return path_ / name;
    }

private:
    std::filesystem::path path_;
};

/// A fresh TempDir kept until the test process exits (ctest runs each test in its own process):
/// for helpers that hand out a folder's path rather than the owning object.
inline std::filesystem::path MakeTempDir(const std::string& prefix) {
    static std::deque<TempDir> made;  // a deque never moves its elements
    return made.emplace_back(prefix).Path();
}

}  // namespace casmap::test
