#include "casmap/io/preset_file.hpp"

#include "casmap/io/yaml_util.hpp"

namespace casmap::io {
namespace {

/// NAME: VALUE entries of a mapping (null = none); InputError naming `field`.<NAME>.
std::vector<PresetEntry> ReadEntries(const std::string& path,
                                     const YAML::Node& map,
                                     const std::string& field) {
    std::vector<PresetEntry> entries;
    if (map.IsNull()) {
        return entries;  // `set:` with nothing after it: no parameters
    }
    if (!map.IsMap()) {
        throw MakeInputError(Where(path, map), field, map.IsScalar() ? map.Scalar() : "",
                             "must be a mapping NAME: VALUE (names of casmap filter --set)");
    }
    for (const auto& kv : map) {
        const std::string name = kv.first.Scalar();
        if (!kv.second.IsScalar()) {
            throw MakeInputError(Where(path, kv.second), field + "." + name, "",
                                 "must be a single value (number or word)");
        }
        entries.push_back({name, kv.second.Scalar(), Where(path, kv.second)});
    }
    return entries;
}

}  // namespace

PresetFile ReadPresetFile(const std::string& path) {
    const YAML::Node root = LoadYamlFile(path);
    if (!root.IsMap()) {
        throw MakeInputError(Where(path, root), "preset", "",
                             "must be a mapping with `set:` (and optional `description:`)");
    }
    RejectUnknownKeys(path, root, "preset", {"description", "set", "pipelines"});
    PresetFile preset;
    preset.path = path;
    ReadOptional(path, root, "preset", "description", preset.description);
    const YAML::Node set = root["set"];
    if (!set) {
        throw MakeInputError(Where(path, root), "set", "",
                             "required mapping of filter parameters (may be {})");
    }
    preset.entries = ReadEntries(path, set, "set");
    const YAML::Node pipelines = root["pipelines"];
    if (!pipelines || pipelines.IsNull()) {
        return preset;
    }
    if (!pipelines.IsMap()) {
        throw MakeInputError(Where(path, pipelines), "pipelines", "",
                             "must be a mapping PIPELINE: {NAME: VALUE, ...}");
    }
    for (const auto& kv : pipelines) {
        const std::string name = kv.first.Scalar();
        preset.pipelines.emplace_back(name, ReadEntries(path, kv.second, "pipelines." + name));
        preset.pipeline_where.push_back(Where(path, kv.first));
    }
    return preset;
}

}  // namespace casmap::io
