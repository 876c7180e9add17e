#include "casmap/view/safe_path.hpp"

#include <system_error>

namespace casmap::view {
namespace fs = std::filesystem;

bool IsInside(const fs::path& root, const fs::path& path) {
    auto r = root.begin();
    auto p = path.begin();
    for (; r != root.end(); ++r, ++p) {
        if (r->empty()) {
            continue;  // trailing separator of "/a/b/"
        }
        if (p == path.end() || *p != *r) {
            return false;
        }
    }
    return true;
}

ResolvedPath ResolveUnder(const fs::path& root, std::string_view relative) {
    if (relative.size() > kMaxPathBytes || relative.find('\0') != std::string_view::npos ||
        relative.find('\\') != std::string_view::npos || relative.starts_with('/')) {
        return {PathVerdict::kBadPath, {}};
    }
    // Reject ".." as a component anywhere, before touching the file system: a path that
    // names a parent is refused even when it would come back inside.
    std::size_t start = 0;
    while (start <= relative.size()) {
        const std::size_t end = std::min(relative.find('/', start), relative.size());
        if (relative.substr(start, end - start) == "..") {
            return {PathVerdict::kBadPath, {}};
        }
        start = end + 1;
    }
    std::error_code ec;
    const fs::path joined = relative.empty() ? root : root / fs::path(relative);
    const fs::path real = fs::canonical(joined, ec);
    if (ec) {
        // A dangling symlink or a missing file: refuse as missing, never stat the target.
        return {PathVerdict::kMissing, {}};
    }
    if (!IsInside(root, real)) {
        return {PathVerdict::kOutside, {}};
    }
    return {PathVerdict::kOk, real};
}

}  // namespace casmap::view
