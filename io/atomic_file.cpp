#include "casmap/io/atomic_file.hpp"

#include <unistd.h>

#include <fstream>
#include <system_error>

#include "casmap/core/input_error.hpp"
#include "casmap/io/output_set.hpp"

namespace casmap::io {
namespace fs = std::filesystem;

void EnsureDirectory(const fs::path& dir) {
    if (dir.empty()) {
        return;
    }
    std::error_code ec;
    fs::create_directories(dir, ec);
    if (ec || !fs::is_directory(dir)) {
        throw MakeInputError(dir.string(), "directory", "",
                             "cannot be created: " + (ec ? ec.message() : "not a directory"));
    }
}

void WriteAtomically(const fs::path& path, const std::function<void(const fs::path&)>& write) {
    const fs::path dir = path.has_parent_path() ? path.parent_path() : fs::path(".");
    if (!fs::is_directory(dir)) {
        throw MakeInputError(path.string(), "output path", "",
                             "directory " + dir.string() + " does not exist");
    }
    if (access(dir.c_str(), W_OK) != 0) {
        throw MakeInputError(path.string(), "output path", "",
                             "directory " + dir.string() + " is not writable");
    }
    // Hidden temporary name in the same directory, so the rename is atomic; temporaries of
    // killed processes are swept first.
    RemoveStaleTemporaries(dir);
    const fs::path tmp = TemporaryPathFor(path);
    try {
        write(tmp);
    } catch (...) {
        std::error_code ignored;
        fs::remove(tmp, ignored);
        throw;
    }
    std::error_code ec;
    fs::rename(tmp, path, ec);
    if (ec) {
        std::error_code ignored;
        fs::remove(tmp, ignored);
        throw MakeInputError(path.string(), "output path", "", "rename failed: " + ec.message());
    }
}

void WriteTextAtomically(const fs::path& path, const std::string& text) {
    WriteAtomically(path, [&](const fs::path& tmp) {
        std::ofstream out(tmp, std::ios::binary);
        out << text;
        out.close();
        if (!out) {
            throw MakeInputError(path.string(), "output path", "", "write failed");
        }
    });
}

}  // namespace casmap::io
