#pragma once

// The routes of `casmap view`, free of any socket: a request (method, decoded path, query)
// in, a response out. The HTTP server (server.hpp) only forwards to Site::Handle, so every
// route and every refusal is unit-tested here.
//
//   GET /                      the page (web/index.html)
//   GET /web/<file>            the page's static files
//   GET /api/info              {"kind": "bench"|"sweep"|"dataset"|"live", "name": ...}
//   GET /api/list?path=<dir>   the entries of a folder under DIR (name, dir, bytes, mtime_ns)
//   GET /files/<path>          a file under DIR as it is
//   GET /api/map?path=<tif>    a float TIFF under DIR as a float map (EncodeMap)
//   GET /api/run?path=<h5>     a run file's map grid and layer names (JSON)
//   GET /api/runmap?path=<h5>&layer=<name>  one map layer of a run file (EncodeMap):
//                              elevation_m, truth_m, filtered/<method>, certainty, cas_classes
// Only GET and HEAD: every other method is 405.

#include <cstdint>
#include <filesystem>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "casmap/core/grid.hpp"
#include "casmap/view/folder.hpp"

namespace casmap::view {

struct Request {
    std::string method = "GET";
    std::string path = "/";                    // percent-decoded, without the query
    std::map<std::string, std::string> query;  // decoded
};

struct Response {
    int status = 200;
    std::string content_type = "text/plain; charset=utf-8";
    std::string body;
};

struct SiteOptions {
    std::filesystem::path dir;                  // the folder to serve
    std::filesystem::path web_dir;              // the page's static files (FindWebDir())
    std::optional<FolderKind> kind;             // default: ClassifyFolder(dir)
    std::uint64_t max_file_bytes = 1ULL << 30;  // larger files are refused (413)
};

/// A float map as the page reads it: "CMF1", rows and cols as little-endian uint32, then
/// rows * cols little-endian float32 in row-major order (NaN kept).
[[nodiscard]] std::string EncodeMap(const core::MapF& map);

class Site {
public:
    /// Throws InputError naming DIR (not a directory, unknown kind) or the web folder.
    explicit Site(const SiteOptions& options);

    [[nodiscard]] Response Handle(const Request& request) const;
    [[nodiscard]] FolderKind kind() const { return kind_; }
    [[nodiscard]] const std::filesystem::path& root() const { return root_; }

private:
    [[nodiscard]] Response ServeFile(const std::filesystem::path& base,
                                     const std::string& relative) const;
    [[nodiscard]] Response Info() const;
    [[nodiscard]] Response List(const std::string& relative) const;
    [[nodiscard]] Response Map(const std::string& relative) const;
    [[nodiscard]] Response RunInfo(const std::string& relative) const;
    [[nodiscard]] Response RunMap(const std::string& relative, const std::string& layer) const;

    std::filesystem::path root_;
    std::filesystem::path web_;
    FolderKind kind_ = FolderKind::kBench;
    std::uint64_t max_file_bytes_ = 0;
};

/// Content type by file extension ("text/html; charset=utf-8", "image/png", ...).
[[nodiscard]] std::string ContentType(const std::filesystem::path& path);

}  // namespace casmap::view
