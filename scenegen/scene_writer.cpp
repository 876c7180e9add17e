#include "casmap/scenegen/scene_writer.hpp"

#include <bit>
#include <cmath>
#include <cstring>
#include <sstream>

namespace casmap::scenegen {
namespace {

std::string Vec(const Eigen::Vector3d& v) {
    return "[" + FormatNumber(v.x()) + ", " + FormatNumber(v.y()) + ", " + FormatNumber(v.z()) +
           "]";
}

std::string Pose(const GenObject& o) {
    return "    pose: {xyz_m: " + Vec(o.xyz_m) + ", rpy_deg: " + Vec(o.rpy_deg) + "}\n";
}

std::string ObjectYaml(const GenObject& o, const std::vector<std::string>& rock_files) {
    std::string y = "  - name: " + o.name + "\n";
    switch (o.kind) {
        case ObjectKind::kDrum:
        case ObjectKind::kPole:
            y += "    cylinder: {radius_m: " + FormatNumber(o.radius_m) +
                 ", height_m: " + FormatNumber(o.height_m) + "}\n";
            break;
        case ObjectKind::kRock:
            y += "    mesh: " + rock_files.at(static_cast<std::size_t>(o.rock_mesh)) + "\n";
            y += "    scale: " + Vec(o.scale) + "\n";
            break;
        default:
            y += "    box: {size_m: " + Vec(o.box_size_m) + "}\n";
    }
    y += Pose(o);
    y += "    reflectivity: " + FormatNumber(o.reflectivity) + "\n";
    if (o.retro_reflective) {
        y += "    retro_reflective: true\n";
    }
    return y;
}

template <typename T>
void Append(std::string& out, T value) {
    static_assert(std::endian::native == std::endian::little, "PLY writer assumes little endian");
    char bytes[sizeof(T)];
    std::memcpy(bytes, &value, sizeof(T));
    out.append(bytes, sizeof(T));
}

}  // namespace

std::string SceneYaml(const GeneratedScene& scene,
                      const std::string& ground_mesh,
                      const std::vector<std::string>& rock_files,
                      const std::string& comment) {
    std::string y;
    std::stringstream in(comment);
    for (std::string line; std::getline(in, line);) {
        y += "# " + line + "\n";
    }
    y += "objects:\n";
    y += "  - name: ground\n    mesh: " + ground_mesh + "\n";
    y += "    pose: {xyz_m: [0, 0, 0], rpy_deg: [0, 0, 0]}\n";
    y += "    reflectivity: " + FormatNumber(scene.ground_reflectivity) + "\n";
    y += "    terrain: true\n";
    for (const GenObject& o : scene.objects) {
        y += ObjectYaml(o, rock_files);
    }
    return y;
}

std::string PlyBinary(const core::MeshShape& mesh) {
    std::string out = "ply\nformat binary_little_endian 1.0\n";
    out += "comment casmap generated ground (scenegen), metres, world frame\n";
    out += "element vertex " + std::to_string(mesh.vertices.size()) + "\n";
    out += "property float x\nproperty float y\nproperty float z\n";
    out += "element face " + std::to_string(mesh.triangles.size()) + "\n";
    out += "property list uchar int vertex_indices\nend_header\n";
    out.reserve(out.size() + mesh.vertices.size() * 12 + mesh.triangles.size() * 13);
    for (const Eigen::Vector3f& v : mesh.vertices) {
        Append(out, v.x());
        Append(out, v.y());
        Append(out, v.z());
    }
    for (const Eigen::Vector3i& t : mesh.triangles) {
        Append(out, static_cast<std::uint8_t>(3));
        Append(out, static_cast<std::int32_t>(t.x()));
        Append(out, static_cast<std::int32_t>(t.y()));
        Append(out, static_cast<std::int32_t>(t.z()));
    }
    return out;
}

}  // namespace casmap::scenegen
