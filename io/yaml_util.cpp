#include "casmap/io/yaml_util.hpp"

#include <filesystem>
#include <string>

namespace casmap::io {

std::string Where(const std::string& file, const YAML::Node& node) {
    const YAML::Mark mark = node.Mark();
    if (mark.line < 0) {
        return file;
    }
    return file + ":" + std::to_string(mark.line + 1) + ":" + std::to_string(mark.column + 1);
}

YAML::Node LoadYamlFile(const std::string& file) {
    if (!std::filesystem::is_regular_file(file)) {
        throw MakeInputError(file, "file", "", "does not exist or is not a regular file");
    }
    try {
        return YAML::LoadFile(file);
    } catch (const YAML::ParserException& e) {
        throw MakeInputError(
            file + ":" + std::to_string(e.mark.line + 1) + ":" + std::to_string(e.mark.column + 1),
            "yaml", "", "syntax error: " + e.msg);
    } catch (const YAML::Exception& e) {
        throw MakeInputError(file, "yaml", "", std::string("cannot be read: ") + e.what());
    }
}

void RejectUnknownKeys(const std::string& file,
                       const YAML::Node& map,
                       const std::string& path,
                       std::initializer_list<std::string_view> allowed) {
    if (!map.IsMap()) {
        throw MakeInputError(Where(file, map), path, "", "must be a mapping");
    }
    for (const auto& entry : map) {
        const std::string key = entry.first.as<std::string>();
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
