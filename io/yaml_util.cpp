#include "casmap/io/yaml_util.hpp"

#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>
#include <string>

#include "casmap/core/limits.hpp"

namespace casmap::io {

std::string Where(const std::string& file, const YAML::Node& node) {
    const YAML::Mark mark = node.Mark();
    if (mark.line < 0) {
        return file;
    }
    return file + ":" + std::to_string(mark.line + 1) + ":" + std::to_string(mark.column + 1);
}

namespace {

// Walks the loaded tree once: counts nodes (an alias counts each time it is used, so an alias
// bomb stops at the limit instead of expanding), bounds the depth, rejects a map key that is not
// a plain scalar (`? [a, b]`, `? {a: 1}`, an empty `?`: no casmap file has one, and every reader
// takes keys as strings) and rejects duplicate keys, which yaml-cpp would otherwise resolve
// silently to the first one.
class TreeCheck {
public:
    explicit TreeCheck(const std::string& file) : file_(file) {}

    void Visit(const YAML::Node& node, int depth) {
        if (++nodes_ > core::limits::kMaxYamlNodes) {
            throw MakeInputError(Where(file_, node), "yaml nodes", "",
                                 "more than " + std::to_string(core::limits::kMaxYamlNodes) +
                                     " (aliases count each use), see docs/limits.md");
        }
        if (depth > core::limits::kMaxYamlDepth) {
            throw MakeInputError(Where(file_, node), "yaml nesting", std::to_string(depth),
                                 "deeper than " + std::to_string(core::limits::kMaxYamlDepth) +
                                     " levels, see docs/limits.md");
        }
        if (node.IsSequence()) {
            for (const YAML::Node& child : node) {
                Visit(child, depth + 1);
            }
        } else if (node.IsMap()) {
            std::set<std::string> keys;
            for (const auto& entry : node) {
                Visit(entry.first, depth + 1);
                if (!entry.first.IsScalar()) {
                    const char* kind = entry.first.IsSequence() ? "<sequence>"
                                       : entry.first.IsMap()    ? "<map>"
                                                                : "<empty>";
                    throw MakeInputError(Where(file_, entry.first), "yaml key", kind,
                                         "map keys must be plain names");
                }
                if (!keys.insert(entry.first.Scalar()).second) {
                    throw MakeInputError(Where(file_, entry.first), entry.first.Scalar(), "",
                                         "duplicate key");
                }
                Visit(entry.second, depth + 1);
            }
        }
    }

private:
    const std::string& file_;
    std::uint64_t nodes_ = 0;
};

}  // namespace

YAML::Node LoadYamlText(const std::string& text, const std::string& file) {
    core::limits::CheckLimit(file, "file size (bytes)", text.size(), core::limits::kMaxYamlBytes,
                             "YAML file");
    YAML::Node root;
    try {
        root = YAML::Load(text);
    } catch (const YAML::ParserException& e) {
        throw MakeInputError(
            file + ":" + std::to_string(e.mark.line + 1) + ":" + std::to_string(e.mark.column + 1),
            "yaml", "", "syntax error: " + e.msg);
    } catch (const YAML::Exception& e) {
        throw MakeInputError(file, "yaml", "", std::string("cannot be read: ") + e.what());
    }
    TreeCheck(file).Visit(root, 0);
    return root;
}

YAML::Node LoadYamlFile(const std::string& file) {
    std::error_code ec;
    if (!std::filesystem::is_regular_file(file, ec)) {
        throw MakeInputError(file, "file", "", "does not exist or is not a regular file");
    }
    core::limits::CheckLimit(file, "file size (bytes)", std::filesystem::file_size(file, ec),
                             core::limits::kMaxYamlBytes, "YAML file");
    std::ifstream in(file, std::ios::binary);
    if (!in.is_open()) {
        throw MakeInputError(file, "file", "", "cannot be opened");
    }
    std::ostringstream text;
    text << in.rdbuf();
    return LoadYamlText(text.str(), file);
}

void RejectUnknownKeys(const std::string& file,
                       const YAML::Node& map,
                       const std::string& path,
                       std::initializer_list<std::string_view> allowed) {
    if (!map.IsMap()) {
        throw MakeInputError(
            Where(file, map), path.empty() ? "top level" : path, "",
            map.IsNull() ? "must be a mapping, found nothing (empty?)" : "must be a mapping");
    }
    for (const auto& entry : map) {
        if (!entry.first.IsScalar()) {
            throw MakeInputError(Where(file, entry.first), path.empty() ? "top level" : path, "",
                                 "keys must be plain names");
        }
        const std::string key = entry.first.Scalar();
        bool known = false;
        std::string list;
        for (const std::string_view a : allowed) {
            known = known || a == key;
            list += (list.empty() ? "" : ", ") + std::string(a);
        }
        if (!known) {
            throw MakeInputError(Where(file, entry.first), path.empty() ? key : path + "." + key,
                                 "", "unknown key; allowed: " + list);
        }
    }
}

}  // namespace casmap::io
