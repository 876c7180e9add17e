#include "casmap/view/site.hpp"

#include <algorithm>
#include <bit>
#include <chrono>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <nlohmann/json.hpp>
#include <optional>
#include <sstream>
#include <system_error>

#include "casmap/core/input_error.hpp"
#include "casmap/io/image.hpp"
#include "casmap/io/run_file.hpp"
#include "casmap/view/safe_path.hpp"

namespace casmap::view {
namespace {
namespace fs = std::filesystem;

/// A file time as nanoseconds since 1970 (the file clock's own epoch is not Unix's: libstdc++'s
/// lies in 2174, which made every mtime_ns negative).
std::int64_t UnixNanoseconds(fs::file_time_type t) {
    return std::chrono::duration_cast<std::chrono::nanoseconds>(
               std::chrono::file_clock::to_sys(t).time_since_epoch())
        .count();
}

using nlohmann::json;

Response Status(int status, const std::string& text) {
    return Response{status, "text/plain; charset=utf-8", text + "\n"};
}

Response Json(const json& value) { return Response{200, "application/json", value.dump()}; }

/// The status a refused path gets, or 0 when it resolved.
Response Refusal(PathVerdict verdict) {
    switch (verdict) {
        case PathVerdict::kBadPath:
            return Status(400, "bad path");
        case PathVerdict::kOutside:
            return Status(403, "outside the served folder");
        case PathVerdict::kMissing:
        case PathVerdict::kOk:
            break;
    }
    return Status(404, "not found");
}

std::string QueryValue(const Request& request, const std::string& key) {
    const auto it = request.query.find(key);
    return it == request.query.end() ? std::string() : it->second;
}

void PutU32(std::string& out, std::uint32_t v) {
    for (int i = 0; i < 4; ++i) {
        out += static_cast<char>((v >> (8 * i)) & 0xFFU);
    }
}

/// One layer of a run file's maps by its /maps name (the CAS classes as floats), if present.
std::optional<core::MapF> Layer(const io::RunMaps& maps, const std::string& layer) {
    if (layer == "elevation_m") return maps.elevation_m;
    if (layer == "certainty") return maps.certainty;
    if (layer == "truth_m") return maps.truth_m;
    if (layer == "cas_classes" && maps.cas_classes) {
        core::MapF out(maps.cas_classes->rows, maps.cas_classes->cols);
        for (std::size_t i = 0; i < out.data.size(); ++i) {
            out.data[i] = static_cast<float>(maps.cas_classes->data[i]);
        }
        return out;
    }
    const std::string prefix = "filtered/";
    if (layer.starts_with(prefix)) {
        const auto it = maps.filtered.find(layer.substr(prefix.size()));
        if (it != maps.filtered.end()) return it->second;
    }
    return std::nullopt;
}

}  // namespace

std::string EncodeMap(const core::MapF& map) {
    std::string out = "CMF1";
    PutU32(out, static_cast<std::uint32_t>(map.rows));
    PutU32(out, static_cast<std::uint32_t>(map.cols));
    const std::size_t head = out.size();
    out.resize(head + map.data.size() * sizeof(float));
    static_assert(std::endian::native == std::endian::little, "EncodeMap writes native floats");
    std::memcpy(out.data() + head, map.data.data(), map.data.size() * sizeof(float));
    return out;
}

std::string ContentType(const fs::path& path) {
    static const std::map<std::string, std::string> kTypes = {
        {".html", "text/html; charset=utf-8"},
        {".js", "text/javascript; charset=utf-8"},
        {".css", "text/css; charset=utf-8"},
        {".json", "application/json"},
        {".jsonl", "text/plain; charset=utf-8"},
        {".md", "text/plain; charset=utf-8"},
        {".txt", "text/plain; charset=utf-8"},
        {".yaml", "text/plain; charset=utf-8"},
        {".csv", "text/plain; charset=utf-8"},
        {".png", "image/png"},
        {".svg", "image/svg+xml"},
        {".tif", "image/tiff"},
        {".tiff", "image/tiff"},
    };
    const auto it = kTypes.find(path.extension().string());
    return it == kTypes.end() ? "application/octet-stream" : it->second;
}

Site::Site(const SiteOptions& options) : max_file_bytes_(options.max_file_bytes) {
    kind_ = options.kind ? *options.kind : ClassifyFolder(options.dir);
    std::error_code ec;
    if (!fs::is_directory(options.dir, ec)) {
        throw MakeInputError(options.dir.string(), "DIR", options.dir.string(), "not a directory");
    }
    root_ = fs::canonical(options.dir);
    if (!fs::is_regular_file(options.web_dir / "index.html", ec)) {
        throw MakeInputError(options.web_dir.string(), "web files", options.web_dir.string(),
                             "must hold index.html");
    }
    web_ = fs::canonical(options.web_dir);
}

Response Site::Handle(const Request& request) const {
    if (request.method != "GET" && request.method != "HEAD") {
        return Status(405, "read-only: GET and HEAD only");
    }
    const std::string& p = request.path;
    if (p == "/" || p == "/index.html") {
        return ServeFile(web_, "index.html");
    }
    if (p.starts_with("/web/")) {
        return ServeFile(web_, p.substr(5));
    }
    if (p.starts_with("/files/")) {
        return ServeFile(root_, p.substr(7));
    }
    if (p == "/api/info") {
        return Info();
    }
    if (p == "/api/list") {
        return List(QueryValue(request, "path"));
    }
    if (p == "/api/map") {
        return Map(QueryValue(request, "path"));
    }
    if (p == "/api/run") {
        return RunInfo(QueryValue(request, "path"));
    }
    if (p == "/api/runmap") {
        return RunMap(QueryValue(request, "path"), QueryValue(request, "layer"));
    }
    return Status(404, "not found");
}

Response Site::ServeFile(const fs::path& base, const std::string& relative) const {
    if (relative.empty()) {
        return Status(400, "bad path");
    }
    const ResolvedPath resolved = ResolveUnder(base, relative);
    if (resolved.verdict != PathVerdict::kOk) {
        return Refusal(resolved.verdict);
    }
    std::error_code ec;
    if (!fs::is_regular_file(resolved.path, ec)) {
        return Status(404, "not a file");
    }
    if (fs::file_size(resolved.path, ec) > max_file_bytes_) {
        return Status(413, "file too large to serve");
    }
    std::ifstream in(resolved.path, std::ios::binary);
    std::ostringstream body;
    body << in.rdbuf();
    if (!in) {
        return Status(404, "unreadable");
    }
    return Response{200, ContentType(resolved.path), body.str()};
}

Response Site::Info() const {
    return Json({{"kind", ToString(kind_)}, {"name", root_.filename().string()}});
}

Response Site::List(const std::string& relative) const {
    const ResolvedPath resolved = ResolveUnder(root_, relative);
    if (resolved.verdict != PathVerdict::kOk) {
        return Refusal(resolved.verdict);
    }
    std::error_code ec;
    if (!fs::is_directory(resolved.path, ec)) {
        return Status(404, "not a folder");
    }
    json entries = json::array();
    std::vector<fs::directory_entry> items;
    for (const fs::directory_entry& e : fs::directory_iterator(resolved.path, ec)) {
        items.push_back(e);
    }
    std::sort(items.begin(), items.end(), [](const auto& a, const auto& b) {
        return a.path().filename() < b.path().filename();
    });
    for (const fs::directory_entry& e : items) {
        const std::string name = e.path().filename().string();
        const std::string rel = relative.empty() ? name : relative + "/" + name;
        const ResolvedPath inner = ResolveUnder(root_, rel);
        if (inner.verdict != PathVerdict::kOk || name.starts_with(".")) {
            continue;  // symlinks out of DIR, dangling links and hidden (temporary) files
        }
        const bool dir = fs::is_directory(inner.path, ec);
        const auto mtime = fs::last_write_time(inner.path, ec);
        entries.push_back({{"name", name},
                           {"dir", dir},
                           {"bytes", dir ? 0 : fs::file_size(inner.path, ec)},
                           {"mtime_ns", UnixNanoseconds(mtime)}});
    }
    return Json({{"path", relative}, {"entries", entries}});
}

Response Site::Map(const std::string& relative) const {
    const ResolvedPath resolved = ResolveUnder(root_, relative);
    if (relative.empty() || resolved.verdict != PathVerdict::kOk) {
        return Refusal(relative.empty() ? PathVerdict::kBadPath : resolved.verdict);
    }
    try {
        return Response{200, "application/octet-stream", EncodeMap(io::ReadMapTiff(resolved.path))};
    } catch (const InputError& e) {
        return Status(422, e.what());
    }
}

Response Site::RunInfo(const std::string& relative) const {
    const ResolvedPath resolved = ResolveUnder(root_, relative);
    if (relative.empty() || resolved.verdict != PathVerdict::kOk) {
        return Refusal(relative.empty() ? PathVerdict::kBadPath : resolved.verdict);
    }
    try {
        const io::RunMaps maps = io::ReadRunMaps(resolved.path);
        json layers = json::array();
        for (const auto& [name, present] : {std::pair{"elevation_m", maps.elevation_m.has_value()},
                                            std::pair{"truth_m", maps.truth_m.has_value()}}) {
            if (present) {
                layers.push_back(name);
            }
        }
        for (const auto& [name, map] : maps.filtered) {
            layers.push_back("filtered/" + name);
        }
        if (maps.certainty) {
            layers.push_back("certainty");
        }
        if (maps.cas_classes) {
            layers.push_back("cas_classes");
        }
        json grid = nullptr;
        if (maps.grid) {
            grid = {{"x0_m", maps.grid->x0_m},
                    {"y0_m", maps.grid->y0_m},
                    {"cell_m", maps.grid->cell_m},
                    {"rows", maps.grid->rows},
                    {"cols", maps.grid->cols}};
        }
        return Json({{"grid", grid}, {"layers", layers}});
    } catch (const InputError& e) {
        return Status(422, e.what());
    }
}

Response Site::RunMap(const std::string& relative, const std::string& layer) const {
    const ResolvedPath resolved = ResolveUnder(root_, relative);
    if (relative.empty() || resolved.verdict != PathVerdict::kOk) {
        return Refusal(relative.empty() ? PathVerdict::kBadPath : resolved.verdict);
    }
    try {
        const io::RunMaps maps = io::ReadRunMaps(resolved.path);
        const std::optional<core::MapF> map = Layer(maps, layer);
        if (!map) {
            return Status(404, "no layer '" + layer + "' in " + relative);
        }
        return Response{200, "application/octet-stream", EncodeMap(*map)};
    } catch (const InputError& e) {
        return Status(422, e.what());
    }
}

}  // namespace casmap::view
