#pragma once

// The scene's shapes as Embree geometry (sim/world.cpp builds its scene from them): boxes and
// meshes as world-frame triangles, cylinders as exact analytic user geometry (side and both caps
// solved in closed form, in double precision). Private to sim (names Embree; not installed).

#include <embree3/rtcore.h>

#include <Eigen/Core>
#include <vector>

#include "casmap/core/pose.hpp"
#include "casmap/core/scene.hpp"

namespace casmap::sim::detail {

// A cylinder of radius r, axis along its own z, centred on its pose.
struct Cylinder {
    Eigen::Matrix3d world_R_object;
    Eigen::Vector3d center_world;
    double radius_m = 0.0;
    double half_height_m = 0.0;
};

/// Embree user-geometry callbacks of a Cylinder (the geometry's user pointer).
void CylinderBounds(const RTCBoundsFunctionArguments* args);
void CylinderIntersect(const RTCIntersectFunctionNArguments* args);
void CylinderOccluded(const RTCOccludedFunctionNArguments* args);

// World-frame triangles of a shape that is built from triangles.
struct TriangleSoup {
    std::vector<Eigen::Vector3f> vertices;
    std::vector<Eigen::Vector3i> triangles;
};

/// A box's 12 triangles at `pose` (box_shape.hpp).
[[nodiscard]] TriangleSoup BoxTriangles(const core::BoxShape& box, const core::Pose& pose);
/// A mesh's triangles in the world frame; InputError naming the object for no triangle, a
/// vertex that is not finite or an index out of range.
[[nodiscard]] TriangleSoup MeshTriangles(const core::SceneObject& object,
                                         const core::MeshShape& mesh);
/// InputError naming the object for a reflectivity outside 0..1, a pose that is not finite, or
/// a box or cylinder size that is not > 0.
void CheckObject(const core::SceneObject& object);

}  // namespace casmap::sim::detail
