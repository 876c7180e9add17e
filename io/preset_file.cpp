#include "casmap/io/preset_file.hpp"

#include "casmap/io/yaml_util.hpp"

namespace casmap::io {

PresetFile ReadPresetFile(const std::string& path) {
    const YAML::Node root = LoadYamlFile(path);
    if (!root.IsMap()) {
        throw MakeInputError(Where(path, root), "preset", "",
                             "must be a mapping with `set:` (and optional `description:`)");
    }
    RejectUnknownKeys(path, root, "preset", {"description", "set"});
    PresetFile preset;
    preset.path = path;
    ReadOptional(path, root, "preset", "description", preset.description);
    const YAML::Node set = root["set"];
    if (!set) {
        throw MakeInputError(Where(path, root), "set", "",
                             "required mapping of filter parameters (may be {})");
    }
    if (set.IsNull()) {
        return preset;  // `set:` with nothing after it: no parameters
    }
    if (!set.IsMap()) {
        throw MakeInputError(Where(path, set), "set", set.IsScalar() ? set.Scalar() : "",
                             "must be a mapping NAME: VALUE (names of casmap filter --set)");
    }
    for (const auto& kv : set) {
        const std::string name = kv.first.Scalar();
        if (!kv.second.IsScalar()) {
            throw MakeInputError(Where(path, kv.second), "set." + name, "",
                                 "must be a single value (number or word)");
        }
        preset.entries.push_back({name, kv.second.Scalar(), Where(path, kv.second)});
    }
    return preset;
}

}  // namespace casmap::io
