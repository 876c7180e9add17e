// The scene's shapes as Embree geometry (world_shapes.hpp): the cylinder's closed-form
// intersection and its Embree callbacks, box and mesh triangles, the checks of an object.
#include "casmap/sim/world_shapes.hpp"

#include <Eigen/Geometry>
#include <cmath>
#include <string>
#include <variant>

#include "casmap/core/input_error.hpp"
#include "casmap/sim/box_shape.hpp"

namespace casmap::sim::detail {
namespace {

// Nearest intersection with t in [tnear, tfar) in closed form; world normal (unnormalised
// direction is fine, Hit normalises). Returns false for a miss.
bool IntersectCylinder(const Cylinder& c,
                       const Eigen::Vector3d& origin_w,
                       const Eigen::Vector3d& dir_w,
                       double tnear,
                       double& t_inout,
                       Eigen::Vector3d& normal_w) {
    const Eigen::Vector3d o = c.world_R_object.transpose() * (origin_w - c.center_world);
    const Eigen::Vector3d d = c.world_R_object.transpose() * dir_w;
    const double r2 = c.radius_m * c.radius_m;
    bool found = false;
    Eigen::Vector3d n_obj = Eigen::Vector3d::Zero();
    const auto consider = [&](double t, const Eigen::Vector3d& n) {
        if (t >= tnear && t < t_inout) {
            t_inout = t;
            n_obj = n;
            found = true;
        }
    };
    // Side: (ox + t dx)^2 + (oy + t dy)^2 = r^2, |z| <= h/2 (numerically stable roots).
    const double a = d.x() * d.x() + d.y() * d.y();
    if (a > 0.0) {
        const double b = 2.0 * (o.x() * d.x() + o.y() * d.y());
        const double cc = o.x() * o.x() + o.y() * o.y() - r2;
        const double disc = b * b - 4.0 * a * cc;
        if (disc >= 0.0) {
            const double q = -0.5 * (b + std::copysign(std::sqrt(disc), b));
            for (const double t : {q / a, q != 0.0 ? cc / q : q / a}) {
                const Eigen::Vector3d p = o + t * d;
                if (std::abs(p.z()) <= c.half_height_m) {
                    consider(t, Eigen::Vector3d(p.x(), p.y(), 0.0));
                }
            }
        }
    }
    // Caps: z = +-h/2 with x^2 + y^2 <= r^2.
    if (d.z() != 0.0) {
        for (const double z_cap : {-c.half_height_m, c.half_height_m}) {
            const double t = (z_cap - o.z()) / d.z();
            const Eigen::Vector3d p = o + t * d;
            if (p.x() * p.x() + p.y() * p.y() <= r2) {
                consider(t, Eigen::Vector3d(0.0, 0.0, z_cap));
            }
        }
    }
    if (found) {
        normal_w = c.world_R_object * n_obj;
    }
    return found;
}

}  // namespace

void CylinderBounds(const RTCBoundsFunctionArguments* args) {
    const auto& c = *static_cast<const Cylinder*>(args->geometryUserPtr);
    const Eigen::Vector3d axis = c.world_R_object.col(2);
    Eigen::Vector3d extent;
    for (int i = 0; i < 3; ++i) {
        extent[i] = std::abs(axis[i]) * c.half_height_m +
                    c.radius_m * std::sqrt(std::max(0.0, 1.0 - axis[i] * axis[i]));
    }
    extent = extent * (1.0 + 1e-6) + Eigen::Vector3d::Constant(1e-6);  // float rounding margin
    const Eigen::Vector3d lo = c.center_world - extent;
    const Eigen::Vector3d hi = c.center_world + extent;
    RTCBounds* b = args->bounds_o;
    b->lower_x = static_cast<float>(lo.x());
    b->lower_y = static_cast<float>(lo.y());
    b->lower_z = static_cast<float>(lo.z());
    b->upper_x = static_cast<float>(hi.x());
    b->upper_y = static_cast<float>(hi.y());
    b->upper_z = static_cast<float>(hi.z());
}

void CylinderIntersect(const RTCIntersectFunctionNArguments* args) {
    const auto& c = *static_cast<const Cylinder*>(args->geometryUserPtr);
    const unsigned int n = args->N;
    RTCRayN* ray = RTCRayHitN_RayN(args->rayhit, n);
    RTCHitN* hit = RTCRayHitN_HitN(args->rayhit, n);
    for (unsigned int i = 0; i < n; ++i) {
        if (args->valid[i] == 0) {
            continue;
        }
        const Eigen::Vector3d o(RTCRayN_org_x(ray, n, i), RTCRayN_org_y(ray, n, i),
                                RTCRayN_org_z(ray, n, i));
        const Eigen::Vector3d d(RTCRayN_dir_x(ray, n, i), RTCRayN_dir_y(ray, n, i),
                                RTCRayN_dir_z(ray, n, i));
        double t = RTCRayN_tfar(ray, n, i);
        Eigen::Vector3d normal;
        if (!IntersectCylinder(c, o, d, RTCRayN_tnear(ray, n, i), t, normal)) {
            continue;
        }
        RTCRayN_tfar(ray, n, i) = static_cast<float>(t);
        RTCHitN_Ng_x(hit, n, i) = static_cast<float>(normal.x());
        RTCHitN_Ng_y(hit, n, i) = static_cast<float>(normal.y());
        RTCHitN_Ng_z(hit, n, i) = static_cast<float>(normal.z());
        RTCHitN_u(hit, n, i) = 0.0F;
        RTCHitN_v(hit, n, i) = 0.0F;
        RTCHitN_primID(hit, n, i) = args->primID;
        RTCHitN_geomID(hit, n, i) = args->geomID;
        RTCHitN_instID(hit, n, i, 0) = args->context->instID[0];
    }
}

void CylinderOccluded(const RTCOccludedFunctionNArguments* args) {
    const auto& c = *static_cast<const Cylinder*>(args->geometryUserPtr);
    const unsigned int n = args->N;
    for (unsigned int i = 0; i < n; ++i) {
        if (args->valid[i] == 0) {
            continue;
        }
        const Eigen::Vector3d o(RTCRayN_org_x(args->ray, n, i), RTCRayN_org_y(args->ray, n, i),
                                RTCRayN_org_z(args->ray, n, i));
        const Eigen::Vector3d d(RTCRayN_dir_x(args->ray, n, i), RTCRayN_dir_y(args->ray, n, i),
                                RTCRayN_dir_z(args->ray, n, i));
        double t = RTCRayN_tfar(args->ray, n, i);
        Eigen::Vector3d normal;
        if (IntersectCylinder(c, o, d, RTCRayN_tnear(args->ray, n, i), t, normal)) {
            RTCRayN_tfar(args->ray, n, i) = -std::numeric_limits<float>::infinity();
        }
    }
}

TriangleSoup BoxTriangles(const core::BoxShape& box, const core::Pose& pose) {
    TriangleSoup soup;
    for (const Eigen::Vector3d& corner : BoxCorners(box, pose)) {
        soup.vertices.push_back(corner.cast<float>());
    }
    for (const auto& t : kBoxTriangles) {
        soup.triangles.emplace_back(t[0], t[1], t[2]);
    }
    return soup;
}

TriangleSoup MeshTriangles(const core::SceneObject& object, const core::MeshShape& mesh) {
    const std::string field = "object " + object.name + " (mesh " + mesh.source_path + ")";
    if (mesh.triangles.empty()) {
        throw MakeInputError(field, "triangles", "", "mesh holds no triangle");
    }
    TriangleSoup soup;
    for (const Eigen::Vector3f& v : mesh.vertices) {
        if (!v.allFinite()) {
            throw MakeInputError(field, "vertices", "", "must be finite");
        }
        soup.vertices.push_back((object.world_T_object * v.cast<double>()).cast<float>());
    }
    const int count = static_cast<int>(mesh.vertices.size());
    for (const Eigen::Vector3i& t : mesh.triangles) {
        if ((t.array() < 0).any() || (t.array() >= count).any()) {
            throw MakeInputError(field, "triangles", "", "vertex index out of range");
        }
    }
    soup.triangles = mesh.triangles;
    return soup;
}

void CheckObject(const core::SceneObject& object) {
    const std::string where = "object " + object.name;
    if (!(object.reflectivity >= 0.0 && object.reflectivity <= 1.0)) {
        throw MakeInputError(where, "reflectivity", std::to_string(object.reflectivity),
                             "allowed: 0..1");
    }
    if (!object.world_T_object.translation.allFinite() ||
        !object.world_T_object.rotation.coeffs().allFinite()) {
        throw MakeInputError(where, "pose", "", "must be finite");
    }
    if (const auto* box = std::get_if<core::BoxShape>(&object.shape)) {
        if (!((box->size_m.array() > 0.0).all() && box->size_m.allFinite())) {
            throw MakeInputError(where, "box.size_m", "", "allowed: > 0");
        }
    }
    if (const auto* cyl = std::get_if<core::CylinderShape>(&object.shape)) {
        if (!(cyl->radius_m > 0.0 && cyl->height_m > 0.0 && std::isfinite(cyl->radius_m) &&
              std::isfinite(cyl->height_m))) {
            throw MakeInputError(where, "cylinder", "", "radius_m and height_m must be > 0");
        }
    }
}

}  // namespace casmap::sim::detail
