#include "casmap/pipeline/preset.hpp"

#include <algorithm>

#include "casmap/core/input_error.hpp"
#include "casmap/io/preset_file.hpp"
#include "casmap/mapper/filter_params.hpp"
#include "casmap/pipeline/bench_pipelines.hpp"
#include "casmap/pipeline/data_dir.hpp"

namespace casmap::pipeline {
namespace fs = std::filesystem;

fs::path PresetsDir() { return DataDir() / "config" / "presets"; }

std::vector<std::string> PresetNames() {
    std::vector<std::string> names;
    std::error_code ec;
    const fs::path dir = PresetsDir();
    for (fs::directory_iterator it(dir, ec), end; !ec && it != end; it.increment(ec)) {
        if (it->path().extension() == ".yaml") {
            names.push_back(it->path().stem().string());
        }
    }
    std::sort(names.begin(), names.end());
    return names;
}

Preset LoadPreset(const std::string& name, const std::string& field) {
    const bool is_path = name.find('/') != std::string::npos ||
                         (name.size() > 5 && name.compare(name.size() - 5, 5, ".yaml") == 0);
    fs::path path;
    if (is_path) {
        path = name;
    } else {
        const bool ok = !name.empty() && std::all_of(name.begin(), name.end(), [](char c) {
            return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') ||
                   c == '_' || c == '-';
        });
        if (!ok) {
            throw MakeInputError("", field, name,
                                 "a preset name ([A-Za-z0-9_-]+) or a path to a preset .yaml");
        }
        path = PresetsDir() / (name + ".yaml");
    }
    if (!fs::is_regular_file(path)) {
        std::string known;
        for (const std::string& n : PresetNames()) {
            known += (known.empty() ? "" : ", ") + n;
        }
        throw MakeInputError("", field, name,
                             "no such preset file " + path.string() + "; presets in " +
                                 PresetsDir().string() + ": " + (known.empty() ? "none" : known) +
                                 (name == "tuned" ? " (the tuned preset is written by the "
                                                    "training-seed sweep and is not shipped yet)"
                                                  : ""));
    }
    const io::PresetFile file = io::ReadPresetFile(path.string());
    Preset preset;
    preset.name = name;
    preset.path = path.string();
    preset.description = file.description;
    mapper::FilterParams check;
    for (const io::PresetEntry& e : file.entries) {
        try {
            check.Set(e.name, e.value);
        } catch (const InputError& error) {
            throw MakeInputError(e.where, "set." + e.name, e.value,
                                 error.rule().empty() ? error.what() : error.rule());
        }
        preset.settings.push_back(e.name + "=" + e.value);
    }
    for (std::size_t i = 0; i < file.pipelines.size(); ++i) {
        const auto& [pipeline, entries] = file.pipelines[i];
        const std::string section = "pipelines." + pipeline;
        try {
            (void)FindPipeline(pipeline, section);
        } catch (const InputError& error) {
            throw MakeInputError(file.pipeline_where[i], section, pipeline, error.rule());
        }
        std::vector<std::string>& out = preset.pipeline_settings[pipeline];
        mapper::FilterParams one = check;
        for (const io::PresetEntry& e : entries) {
            if (e.name == "unknown") {
                throw MakeInputError(e.where, section + ".unknown", e.value,
                                     "the unknown-cell convention is the run's, not one "
                                     "pipeline's (set it under set:)");
            }
            try {
                one.Set(e.name, e.value);
            } catch (const InputError& error) {
                throw MakeInputError(e.where, section + "." + e.name, e.value,
                                     error.rule().empty() ? error.what() : error.rule());
            }
            out.push_back(e.name + "=" + e.value);
        }
    }
    return preset;
}

}  // namespace casmap::pipeline
