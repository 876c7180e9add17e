#include "casmap/io/dataset_spec_file.hpp"

#include <set>

#include "casmap/io/yaml_emit.hpp"
#include "casmap/io/yaml_util.hpp"
#include "casmap/scenegen/scene_writer.hpp"

namespace casmap::io {
namespace {

using core::FormatNumber;
using scenegen::Range;
using scenegen::RangeField;

std::string Text(const YAML::Node& node) {
    return node.IsScalar() ? node.Scalar() : (node.IsSequence() ? "<sequence>" : "<map>");
}

double Number(const std::string& file, const YAML::Node& node, const std::string& field) {
    try {
        if (node.IsScalar()) {
            return node.as<double>();
        }
    } catch (const YAML::Exception&) {
    }
    throw MakeInputError(Where(file, node), field, Text(node), "must be a number");
}

// A range is a number (fixed) or [min, max].
Range ReadRange(const std::string& file, const YAML::Node& node, const std::string& field) {
    if (node.IsScalar()) {
        const double v = Number(file, node, field);
        return {v, v};
    }
    if (!node.IsSequence() || node.size() != 2) {
        throw MakeInputError(Where(file, node), field, Text(node),
                             "must be a number or a list [min, max]");
    }
    return {Number(file, node[0], field + "[0]"), Number(file, node[1], field + "[1]")};
}

// Reads `section` (a map) whose keys are the range fields plus `extra` keys handled by `other`.
template <typename Other>
void ReadSection(const std::string& file,
                 const YAML::Node& section,
                 const std::string& path,
                 std::vector<RangeField> ranges,
                 const std::set<std::string>& extra,
                 Other other) {
    if (!section) {
        return;
    }
    if (!section.IsMap()) {
        throw MakeInputError(Where(file, section), path, Text(section), "must be a mapping");
    }
    for (const auto& entry : section) {
        const std::string key = entry.first.as<std::string>();
        const std::string field = path + "." + key;
        bool done = false;
        for (const RangeField& f : ranges) {
            if (key == f.key) {
                *f.range = ReadRange(file, entry.second, field);
                done = true;
            }
        }
        if (done) {
            continue;
        }
        if (extra.count(key) == 0) {
            std::string allowed;
            for (const RangeField& f : ranges) {
                allowed += std::string(allowed.empty() ? "" : ", ") + f.key;
            }
            for (const std::string& e : extra) {
                allowed += ", " + e;
            }
            throw MakeInputError(Where(file, entry.first), field, key,
                                 "unknown key; allowed: " + allowed);
        }
        other(key, entry.second, field);
    }
}

template <std::size_t N>
void ReadWeights(const std::string& file,
                 const YAML::Node& node,
                 const std::string& field,
                 const std::array<const char*, N>& names,
                 std::array<double, N>& out) {
    if (!node.IsMap()) {
        throw MakeInputError(Where(file, node), field, Text(node),
                             "must be a mapping NAME: weight");
    }
    for (const auto& entry : node) {
        const std::string key = entry.first.as<std::string>();
        std::size_t i = 0;
        while (i < N && key != names[i]) {
            ++i;
        }
        if (i == N) {
            std::string allowed;
            for (const char* n : names) {
                allowed += std::string(allowed.empty() ? "" : ", ") + n;
            }
            throw MakeInputError(Where(file, entry.first), field + "." + key, key,
                                 "unknown key; allowed: " + allowed);
        }
        out[i] = Number(file, entry.second, field + "." + key);
    }
}

constexpr std::array<const char*, scenegen::kObjectKinds> kKindNames = {
    "box", "drum", "pole", "ramp", "curb", "step", "rock"};

void ReadScene(const std::string& file, const YAML::Node& node, scenegen::SceneGenConfig& s) {
    ReadSection(
        file, node, "scene", s.Ranges(),
        {"terrain_probability", "ground_cell_m", "noise_octaves", "max_slope_deg", "kind_weights",
         "terrain_rock_weight_factor", "min_gap_m", "p_dark", "p_bright", "p_retro"},
        [&](const std::string& key, const YAML::Node& v, const std::string& field) {
            if (key == "kind_weights") {
                ReadWeights(file, v, field, kKindNames, s.kind_weights);
            } else if (key == "noise_octaves") {
                s.noise_octaves = static_cast<int>(Number(file, v, field));
            } else {
                double* targets[] = {&s.terrain_probability,
                                     &s.ground_cell_m,
                                     &s.max_slope_deg,
                                     &s.terrain_rock_weight_factor,
                                     &s.min_gap_m,
                                     &s.p_dark,
                                     &s.p_bright,
                                     &s.p_retro};
                const char* names[] = {"terrain_probability",
                                       "ground_cell_m",
                                       "max_slope_deg",
                                       "terrain_rock_weight_factor",
                                       "min_gap_m",
                                       "p_dark",
                                       "p_bright",
                                       "p_retro"};
                for (std::size_t i = 0; i < std::size(names); ++i) {
                    if (key == names[i]) {
                        *targets[i] = Number(file, v, field);
                    }
                }
            }
        });
}

template <typename T>
std::vector<T> ReadList(const std::string& file, const YAML::Node& node, const std::string& field) {
    if (!node.IsSequence()) {
        throw MakeInputError(Where(file, node), field, Text(node), "must be a list");
    }
    std::vector<T> out;
    for (std::size_t i = 0; i < node.size(); ++i) {
        try {
            out.push_back(node[i].as<T>());
        } catch (const YAML::Exception&) {
            throw MakeInputError(Where(file, node[i]), field + "[" + std::to_string(i) + "]",
                                 Text(node[i]), "wrong type");
        }
    }
    return out;
}

void ReadDomain(const std::string& file, const YAML::Node& node, scenegen::DomainConfig& d) {
    ReadSection(file, node, "domain", d.Ranges(),
                {"motion_weights", "angular_resolutions_deg", "range_modes",
                 "pose_error_probability", "triangle_probability"},
                [&](const std::string& key, const YAML::Node& v, const std::string& field) {
                    if (key == "motion_weights") {
                        ReadWeights(file, v, field, scenegen::kMotionNames, d.motion_weights);
                    } else if (key == "angular_resolutions_deg") {
                        d.angular_resolutions_deg = ReadList<double>(file, v, field);
                    } else if (key == "range_modes") {
                        d.range_modes = ReadList<std::string>(file, v, field);
                    } else if (key == "triangle_probability") {
                        d.triangle_probability = Number(file, v, field);
                    } else {
                        d.pose_error_probability = Number(file, v, field);
                    }
                });
}

void ReadTop(const std::string& file, const YAML::Node& root, scenegen::DatasetSpec& spec) {
    RejectUnknownKeys(file, root, "",
                      {"name", "count", "seed", "splits", "region", "scene", "domain", "outputs"});
    ReadOptional(file, root, "", "name", spec.name);
    ReadOptional(file, root, "", "count", spec.count);
    ReadOptional(file, root, "", "seed", spec.seed);
    if (const YAML::Node s = root["splits"]) {
        RejectUnknownKeys(file, s, "splits", {"train", "val"});
        ReadOptional(file, s, "splits", "train", spec.train_fraction);
        ReadOptional(file, s, "splits", "val", spec.val_fraction);
    }
    if (const YAML::Node r = root["region"]) {
        RejectUnknownKeys(file, r, "region", {"start_x_m", "length_m", "width_m", "cell_m"});
        ReadOptional(file, r, "region", "start_x_m", spec.region_start_x_m);
        ReadOptional(file, r, "region", "length_m", spec.region_length_m);
        ReadOptional(file, r, "region", "width_m", spec.region_width_m);
        ReadOptional(file, r, "region", "cell_m", spec.cell_m);
    }
    if (const YAML::Node o = root["outputs"]) {
        RejectUnknownKeys(file, o, "outputs", {"filtered", "cas_classes", "pose_decimation"});
        ReadOptional(file, o, "outputs", "filtered", spec.outputs.filtered);
        ReadOptional(file, o, "outputs", "cas_classes", spec.outputs.cas_classes);
        ReadOptional(file, o, "outputs", "pose_decimation", spec.outputs.pose_decimation);
    }
}

void EmitRanges(YAML::Emitter& out, const std::vector<RangeField>& ranges) {
    for (const RangeField& f : ranges) {
        out << YAML::Key << f.key << YAML::Value << YAML::Flow << YAML::BeginSeq
            << FormatNumber(f.range->min) << FormatNumber(f.range->max) << YAML::EndSeq;
    }
}

template <std::size_t N>
void EmitWeights(YAML::Emitter& out,
                 const char* key,
                 const std::array<const char*, N>& names,
                 const std::array<double, N>& w) {
    out << YAML::Key << key << YAML::Value << YAML::Flow << YAML::BeginMap;
    for (std::size_t i = 0; i < N; ++i) {
        EmitNumber(out, names[i], w[i]);
    }
    out << YAML::EndMap;
}

}  // namespace

scenegen::DatasetSpec LoadDatasetSpec(const std::string& path) {
    const YAML::Node root = LoadYamlFile(path);
    scenegen::DatasetSpec spec;
    if (root.IsNull()) {
        spec.Validate(path);
        return spec;
    }
    if (!root.IsMap()) {
        throw MakeInputError(Where(path, root), "spec", Text(root), "must be a mapping");
    }
    ReadTop(path, root, spec);
    ReadScene(path, root["scene"], spec.scene);
    ReadDomain(path, root["domain"], spec.domain);
    spec.Validate(path);
    return spec;
}

void EmitDatasetSpec(YAML::Emitter& out, const scenegen::DatasetSpec& spec_in) {
    scenegen::DatasetSpec spec = spec_in;  // Ranges() needs a mutable object
    out << YAML::Key << "name" << YAML::Value << YAML::DoubleQuoted << spec.name;
    out << YAML::Key << "count" << YAML::Value << spec.count;
    out << YAML::Key << "seed" << YAML::Value << spec.seed;
    out << YAML::Key << "splits" << YAML::Value << YAML::Flow << YAML::BeginMap;
    EmitNumber(out, "train", spec.train_fraction);
    EmitNumber(out, "val", spec.val_fraction);
    out << YAML::EndMap;
    out << YAML::Key << "region" << YAML::Value << YAML::Flow << YAML::BeginMap;
    EmitNumber(out, "start_x_m", spec.region_start_x_m);
    EmitNumber(out, "length_m", spec.region_length_m);
    EmitNumber(out, "width_m", spec.region_width_m);
    EmitNumber(out, "cell_m", spec.cell_m);
    out << YAML::EndMap;
    const scenegen::SceneGenConfig& s = spec.scene;
    out << YAML::Key << "scene" << YAML::Value << YAML::BeginMap;
    EmitNumber(out, "terrain_probability", s.terrain_probability);
    EmitNumber(out, "ground_cell_m", s.ground_cell_m);
    out << YAML::Key << "noise_octaves" << YAML::Value << s.noise_octaves;
    EmitNumber(out, "max_slope_deg", s.max_slope_deg);
    EmitWeights(out, "kind_weights", kKindNames, s.kind_weights);
    EmitNumber(out, "terrain_rock_weight_factor", s.terrain_rock_weight_factor);
    EmitNumber(out, "min_gap_m", s.min_gap_m);
    EmitNumber(out, "p_dark", s.p_dark);
    EmitNumber(out, "p_bright", s.p_bright);
    EmitNumber(out, "p_retro", s.p_retro);
    EmitRanges(out, spec.scene.Ranges());
    out << YAML::EndMap;
    const scenegen::DomainConfig& d = spec.domain;
    out << YAML::Key << "domain" << YAML::Value << YAML::BeginMap;
    EmitWeights(out, "motion_weights", scenegen::kMotionNames, d.motion_weights);
    out << YAML::Key << "angular_resolutions_deg" << YAML::Value << YAML::Flow << YAML::BeginSeq;
    for (const double r : d.angular_resolutions_deg) {
        out << FormatNumber(r);
    }
    out << YAML::EndSeq;
    out << YAML::Key << "range_modes" << YAML::Value << YAML::Flow << d.range_modes;
    EmitNumber(out, "pose_error_probability", d.pose_error_probability);
    EmitNumber(out, "triangle_probability", d.triangle_probability);
    EmitRanges(out, spec.domain.Ranges());
    out << YAML::EndMap;
    out << YAML::Key << "outputs" << YAML::Value << YAML::Flow << YAML::BeginMap;
    out << YAML::Key << "filtered" << YAML::Value << (spec.outputs.filtered ? "true" : "false");
    out << YAML::Key << "cas_classes" << YAML::Value
        << (spec.outputs.cas_classes ? "true" : "false");
    out << YAML::Key << "pose_decimation" << YAML::Value << spec.outputs.pose_decimation;
    out << YAML::EndMap;
}

std::string DatasetSpecToYaml(const scenegen::DatasetSpec& spec) {
    YAML::Emitter out;
    out << YAML::BeginMap;
    EmitDatasetSpec(out, spec);
    out << YAML::EndMap;
    return EmittedText(out);
}

}  // namespace casmap::io
