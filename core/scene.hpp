#pragma once

#include <Eigen/Core>
#include <string>
#include <variant>
#include <vector>

#include "casmap/core/pose.hpp"

namespace casmap::core {

/// Axis-aligned box in its own frame, centred on its pose (like URDF/SDF).
struct BoxShape {
    Eigen::Vector3d size_m = Eigen::Vector3d::Ones();
};

/// Cylinder with its axis along its own z, centred on its pose.
struct CylinderShape {
    double radius_m = 0.5;
    double height_m = 1.0;
};

/// Triangle mesh in its own frame, already scaled to metres.
struct MeshShape {
    std::string source_path;  // where it came from, for messages
    std::vector<Eigen::Vector3f> vertices;
    std::vector<Eigen::Vector3i> triangles;
};

using Shape = std::variant<BoxShape, CylinderShape, MeshShape>;

struct SceneObject {
    std::string name;
    Shape shape;
    Pose world_T_object;
    double reflectivity = 0.5;  // diffuse reflectance at 905 nm, 0..1
    bool terrain = false;       // drivable ground for the vehicle rig
    /// A retro-reflector (prismatic or glass-bead sheeting, corner cubes): returns light back
    /// towards the scanner, `reflectivity` x the sensor's retro_gain times a white diffuser's
    /// echo (docs/scenes.md "Materials").
    bool retro_reflective = false;
};

/// A scene as plain data: what io loads from YAML and sim turns into an Embree world.
struct Scene {
    std::string source_path;
    std::vector<SceneObject> objects;

    /// Throws InputError "<source_path>: objects[i].<field> = <value> (<rule>)" for the first
    /// broken rule: at least one object; names non-empty and unique; box sizes, cylinder radius
    /// and height in (0, limits::kMaxSceneExtentM]; a mesh with triangles on its vertices; the
    /// pose finite with its position within +-kMaxSceneExtentM; reflectivity in 0..1.
    /// io::LoadScene calls it and names the offending key's line:column instead.
    void Validate() const;
};

}  // namespace casmap::core
