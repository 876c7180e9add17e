#include "casmap/io/scene_file.hpp"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <numbers>
#include <string>
#include <vector>

#include "casmap/core/input_error.hpp"
#include "casmap/core/limits.hpp"
#include "casmap/core/pose.hpp"
#include "casmap/io/mesh_import.hpp"
#include "casmap/io/yaml_util.hpp"

namespace casmap::io {
namespace {

// A node's text for messages: its scalar, or its elements as "[a, b, c]".
std::string Describe(const YAML::Node& node) {
    if (node.IsScalar()) {
        return node.Scalar();
    }
    if (node.IsSequence()) {
        std::string text = "[";
        for (std::size_t i = 0; i < node.size() && text.size() < 64; ++i) {
            text += (i == 0 ? "" : ", ") + Describe(node[i]);
        }
        return text + "]";
    }
    return node.IsMap() ? "<map>" : "<null>";
}

// Reads a finite number; `field` is the full path used in the message.
double ReadNumber(const std::string& file, const YAML::Node& node, const std::string& field) {
    double value = 0.0;
    try {
        if (!node.IsScalar()) {
            throw YAML::Exception(node.Mark(), "not a scalar");
        }
        value = node.as<double>();
    } catch (const YAML::Exception&) {
        throw MakeInputError(Where(file, node), field, Describe(node), "must be a number");
    }
    if (!std::isfinite(value)) {
        throw MakeInputError(Where(file, node), field, Describe(node), "must be finite");
    }
    return value;
}

// Reads a list of exactly n finite numbers.
std::vector<double> ReadNumbers(const std::string& file,
                                const YAML::Node& node,
                                const std::string& field,
                                std::size_t n) {
    if (!node.IsSequence() || node.size() != n) {
        throw MakeInputError(Where(file, node), field, Describe(node),
                             "must be a list of " + std::to_string(n) + " numbers");
    }
    std::vector<double> values;
    for (std::size_t i = 0; i < n; ++i) {
        values.push_back(ReadNumber(file, node[i], field + "[" + std::to_string(i) + "]"));
    }
    return values;
}

Eigen::Vector3d ReadVector3(const std::string& file,
                            const YAML::Node& node,
                            const std::string& field) {
    const std::vector<double> v = ReadNumbers(file, node, field, 3);
    return {v[0], v[1], v[2]};
}

core::Shape ReadBox(const std::string& file, const YAML::Node& node, const std::string& field) {
    RejectUnknownKeys(file, node, field, {"size_m"});
    if (!node["size_m"]) {
        throw MakeInputError(Where(file, node), field + ".size_m", "", "required key is missing");
    }
    return core::BoxShape{ReadVector3(file, node["size_m"], field + ".size_m")};
}

core::Shape ReadCylinder(const std::string& file,
                         const YAML::Node& node,
                         const std::string& field) {
    RejectUnknownKeys(file, node, field, {"radius_m", "height_m"});
    core::CylinderShape cylinder;
    for (const char* key : {"radius_m", "height_m"}) {
        if (!node[key]) {
            throw MakeInputError(Where(file, node), field + "." + key, "",
                                 "required key is missing");
        }
    }
    cylinder.radius_m = ReadNumber(file, node["radius_m"], field + ".radius_m");
    cylinder.height_m = ReadNumber(file, node["height_m"], field + ".height_m");
    return cylinder;
}

core::Shape ReadMesh(const std::string& file, const YAML::Node& object, const std::string& field) {
    const YAML::Node node = object["mesh"];
    if (!node.IsScalar() || node.Scalar().empty()) {
        throw MakeInputError(Where(file, node), field + ".mesh", Describe(node),
                             "must be a file path");
    }
    Eigen::Vector3d scale = Eigen::Vector3d::Ones();
    if (const YAML::Node s = object["scale"]) {
        scale = s.IsSequence() ? ReadVector3(file, s, field + ".scale")
                               : Eigen::Vector3d::Constant(ReadNumber(file, s, field + ".scale"));
        for (int i = 0; i < 3; ++i) {
            if (!(scale[i] > 0.0)) {
                throw MakeInputError(Where(file, s), field + ".scale", Describe(s), "allowed: > 0");
            }
        }
    }
    std::filesystem::path mesh_path(node.Scalar());
    if (mesh_path.is_relative()) {
        mesh_path = std::filesystem::path(file).parent_path() / mesh_path;
    }
    if (!std::filesystem::is_regular_file(mesh_path)) {
        throw MakeInputError(Where(file, node), field + ".mesh", node.Scalar(),
                             "file not found: " + mesh_path.string());
    }
    try {
        return ImportMesh(mesh_path, scale);
    } catch (const InputError& e) {
        throw MakeInputError(Where(file, node), field + ".mesh", node.Scalar(), e.what());
    }
}

core::Pose ReadPose(const std::string& file, const YAML::Node& node, const std::string& field) {
    Eigen::Vector3d xyz = Eigen::Vector3d::Zero();
    Eigen::Vector3d rpy_deg = Eigen::Vector3d::Zero();
    if (node.IsSequence()) {  // compact form: [x, y, z, roll_deg, pitch_deg, yaw_deg]
        const std::vector<double> v = ReadNumbers(file, node, field, 6);
        xyz = {v[0], v[1], v[2]};
        rpy_deg = {v[3], v[4], v[5]};
    } else if (node.IsMap()) {
        RejectUnknownKeys(file, node, field, {"xyz_m", "rpy_deg"});
        if (node["xyz_m"]) {
            xyz = ReadVector3(file, node["xyz_m"], field + ".xyz_m");
        }
        if (node["rpy_deg"]) {
            rpy_deg = ReadVector3(file, node["rpy_deg"], field + ".rpy_deg");
        }
    } else {
        throw MakeInputError(Where(file, node), field, Describe(node),
                             "must be {xyz_m: [3], rpy_deg: [3]} or a list of 6 numbers");
    }
    return core::PoseFromXyzRpy(xyz, rpy_deg * (std::numbers::pi / 180.0));
}

core::SceneObject ReadObject(const std::string& file,
                             const YAML::Node& node,
                             const std::string& field) {
    RejectUnknownKeys(file, node, field,
                      {"name", "box", "cylinder", "mesh", "scale", "pose", "reflectivity",
                       "terrain", "retro_reflective"});
    core::SceneObject object;
    ReadRequired(file, node, field, "name", object.name);
    const int shapes = (node["box"] ? 1 : 0) + (node["cylinder"] ? 1 : 0) + (node["mesh"] ? 1 : 0);
    if (shapes != 1) {
        throw MakeInputError(Where(file, node), field, object.name,
                             "needs exactly one of box, cylinder, mesh");
    }
    if (node["scale"] && !node["mesh"]) {
        throw MakeInputError(Where(file, node["scale"]), field + ".scale", Describe(node["scale"]),
                             "only allowed with mesh");
    }
    if (node["box"]) {
        object.shape = ReadBox(file, node["box"], field + ".box");
    } else if (node["cylinder"]) {
        object.shape = ReadCylinder(file, node["cylinder"], field + ".cylinder");
    } else {
        object.shape = ReadMesh(file, node, field);
    }
    if (node["pose"]) {
        object.world_T_object = ReadPose(file, node["pose"], field + ".pose");
    }
    if (const YAML::Node r = node["reflectivity"]) {
        object.reflectivity = ReadNumber(file, r, field + ".reflectivity");
    }
    ReadOptional(file, node, field, "terrain", object.terrain);
    ReadOptional(file, node, field, "retro_reflective", object.retro_reflective);
    return object;
}

// The node a field path such as "objects[2].box.size_m[1]" names, or the deepest of its
// parents the file holds (a default value has no node of its own).
YAML::Node NodeOf(const YAML::Node& root, const std::string& field) {
    YAML::Node node = root;
    std::size_t at = 0;
    while (at < field.size()) {
        const YAML::Node& here = node;  // const access: looking up never adds a key
        YAML::Node next;
        if (field[at] == '[') {
            const std::size_t close = field.find(']', at);
            const std::size_t index = std::stoul(field.substr(at + 1, close - at - 1));
            if (!here.IsSequence() || index >= here.size()) {
                break;
            }
            next = here[index];
            at = close + 1;
        } else {
            at += field[at] == '.' ? 1 : 0;
            const std::size_t end = std::min(field.find_first_of(".[", at), field.size());
            const std::string key = field.substr(at, end - at);
            if (!here.IsMap() || !here[key]) {
                break;
            }
            next = here[key];
            at = end;
        }
        node.reset(next);
    }
    return node;
}

}  // namespace

core::Scene LoadScene(const std::string& path) {
    const YAML::Node root = LoadYamlFile(path);
    RejectUnknownKeys(path, root, "", {"objects"});
    const YAML::Node objects = root["objects"];
    if (!objects) {
        throw MakeInputError(Where(path, root), "objects", "", "required key is missing");
    }
    if (!objects.IsSequence()) {
        throw MakeInputError(Where(path, objects), "objects", Describe(objects),
                             "must be a non-empty list");
    }
    core::Scene scene;
    scene.source_path = path;
    for (std::size_t i = 0; i < objects.size(); ++i) {
        scene.objects.push_back(ReadObject(path, objects[i], "objects[" + std::to_string(i) + "]"));
    }
    try {  // the scene's own rules; the message names the key's line:column and its text
        scene.Validate();
    } catch (const InputError& e) {
        const YAML::Node node = NodeOf(root, e.field());
        const bool exact = node.IsScalar() || node.IsSequence();
        throw MakeInputError(Where(path, node), e.field(), exact ? Describe(node) : e.value(),
                             e.rule());
    }
    return scene;
}

}  // namespace casmap::io
