// The one file that talks to Embree 3 (sim/world.hpp is the contract).
// Boxes: 12 triangles. Cylinders: exact analytic user geometry (side and both caps solved in
// closed form, in double precision), so a 2.5 mm pole is round and a range to it is exact.
// Meshes: triangles. Everything is transformed to the world frame at build time (no instancing),
// geometry id = object index in the Scene.
#include "casmap/sim/world.hpp"

#include <embree3/rtcore.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <cassert>
#include <cmath>
#include <cstring>
#include <limits>
#include <memory>
#include <mutex>
#include <stdexcept>
#include <string>
#include <variant>
#include <vector>

#include "casmap/core/input_error.hpp"
#include "casmap/sim/box_shape.hpp"

namespace casmap::sim {
namespace {

using DevicePtr = std::unique_ptr<RTCDeviceTy, decltype(&rtcReleaseDevice)>;
using ScenePtr = std::unique_ptr<RTCSceneTy, decltype(&rtcReleaseScene)>;

// Embree reports errors through a C callback, where throwing is not allowed: the callback
// records the first error and Check() turns it into an exception at the call site.
struct ErrorSink {
    std::mutex mutex;
    RTCError code = RTC_ERROR_NONE;
    std::string message;

    void Check(const std::string& context) {
        const std::lock_guard<std::mutex> lock(mutex);
        if (code != RTC_ERROR_NONE) {
            const std::string text = "embree error " + std::to_string(static_cast<int>(code)) +
                                     " (" + message + ") while " + context;
            code = RTC_ERROR_NONE;
            throw std::runtime_error(text);
        }
    }
};

void OnEmbreeError(void* user, RTCError code, const char* str) {
    auto* sink = static_cast<ErrorSink*>(user);
    const std::lock_guard<std::mutex> lock(sink->mutex);
    if (sink->code == RTC_ERROR_NONE) {
        sink->code = code;
        sink->message = str != nullptr ? str : "";
    }
}

// A cylinder of radius r, axis along its own z, centred on its pose.
struct Cylinder {
    Eigen::Matrix3d world_R_object;
    Eigen::Vector3d center_world;
    double radius_m = 0.0;
    double half_height_m = 0.0;
};

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

// World-frame triangles of a shape that is built from triangles.
struct TriangleSoup {
    std::vector<Eigen::Vector3f> vertices;
    std::vector<Eigen::Vector3i> triangles;
};

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

template <int N>
struct Packet;
template <>
struct Packet<4> {
    using RayHit = RTCRayHit4;
    static void Intersect(const int* v, RTCScene s, RTCIntersectContext* c, RayHit* rh) {
        rtcIntersect4(v, s, c, rh);
    }
};
template <>
struct Packet<8> {
    using RayHit = RTCRayHit8;
    static void Intersect(const int* v, RTCScene s, RTCIntersectContext* c, RayHit* rh) {
        rtcIntersect8(v, s, c, rh);
    }
};
template <>
struct Packet<16> {
    using RayHit = RTCRayHit16;
    static void Intersect(const int* v, RTCScene s, RTCIntersectContext* c, RayHit* rh) {
        rtcIntersect16(v, s, c, rh);
    }
};

}  // namespace

struct World::Impl {
    // Members are destroyed bottom-up: the scene goes first, then the device, and only then
    // the cylinders it points to and the error sink its callback writes to.
    ErrorSink errors;
    std::vector<std::unique_ptr<Cylinder>> cylinders;  // user data, stable addresses
    std::vector<float> reflectivity;                   // per geometry id = object index
    std::vector<std::uint8_t> retro;                   // per geometry id: retro-reflector
    DevicePtr device{nullptr, &rtcReleaseDevice};
    ScenePtr scene{nullptr, &rtcReleaseScene};

    void AddTriangles(const TriangleSoup& soup, unsigned int id, const std::string& name);
    void AddCylinder(const core::CylinderShape& shape,
                     const core::Pose& pose,
                     unsigned int id,
                     const std::string& name);
    Hit MakeHit(unsigned int geom_id,
                float tfar,
                const Eigen::Vector3f& ng,
                const Eigen::Vector3f& dir) const;
};

void World::Impl::AddTriangles(const TriangleSoup& soup, unsigned int id, const std::string& name) {
    RTCGeometry geom = rtcNewGeometry(device.get(), RTC_GEOMETRY_TYPE_TRIANGLE);
    errors.Check("creating triangles of object " + name);
    auto* v = static_cast<float*>(rtcSetNewGeometryBuffer(geom, RTC_BUFFER_TYPE_VERTEX, 0,
                                                          RTC_FORMAT_FLOAT3, 3 * sizeof(float),
                                                          soup.vertices.size()));
    auto* t = static_cast<unsigned int*>(
        rtcSetNewGeometryBuffer(geom, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3,
                                3 * sizeof(unsigned int), soup.triangles.size()));
    if (v == nullptr || t == nullptr) {
        rtcReleaseGeometry(geom);
        errors.Check("allocating buffers of object " + name);
        throw std::runtime_error("embree: cannot allocate buffers of object " + name);
    }
    for (std::size_t i = 0; i < soup.vertices.size(); ++i) {
        std::copy_n(soup.vertices[i].data(), 3, v + 3 * i);
    }
    for (std::size_t i = 0; i < soup.triangles.size(); ++i) {
        for (int k = 0; k < 3; ++k) {
            t[3 * i + static_cast<std::size_t>(k)] =
                static_cast<unsigned int>(soup.triangles[i][k]);
        }
    }
    rtcCommitGeometry(geom);
    rtcAttachGeometryByID(scene.get(), geom, id);
    rtcReleaseGeometry(geom);  // the scene holds the reference now
    errors.Check("attaching object " + name);
}

void World::Impl::AddCylinder(const core::CylinderShape& shape,
                              const core::Pose& pose,
                              unsigned int id,
                              const std::string& name) {
    auto cyl = std::make_unique<Cylinder>();
    cyl->world_R_object = pose.rotation.normalized().toRotationMatrix();
    cyl->center_world = pose.translation;
    cyl->radius_m = shape.radius_m;
    cyl->half_height_m = 0.5 * shape.height_m;
    cylinders.push_back(std::move(cyl));  // owned before Embree holds a pointer to it
    RTCGeometry geom = rtcNewGeometry(device.get(), RTC_GEOMETRY_TYPE_USER);
    errors.Check("creating cylinder " + name);
    rtcSetGeometryUserPrimitiveCount(geom, 1);
    rtcSetGeometryUserData(geom, cylinders.back().get());
    rtcSetGeometryBoundsFunction(geom, &CylinderBounds, nullptr);
    rtcSetGeometryIntersectFunction(geom, &CylinderIntersect);
    rtcSetGeometryOccludedFunction(geom, &CylinderOccluded);
    rtcCommitGeometry(geom);
    rtcAttachGeometryByID(scene.get(), geom, id);
    rtcReleaseGeometry(geom);
    errors.Check("attaching cylinder " + name);
}

Hit World::Impl::MakeHit(unsigned int geom_id,
                         float tfar,
                         const Eigen::Vector3f& ng,
                         const Eigen::Vector3f& dir) const {
    Hit hit;
    if (geom_id == RTC_INVALID_GEOMETRY_ID) {
        return hit;
    }
    hit.distance_m = tfar;  // directions are unit length, so t is the distance
    const float norm = ng.norm();
    hit.normal = norm > 0.0F ? Eigen::Vector3f(ng / norm) : Eigen::Vector3f::Zero();
    if (hit.normal.dot(dir) > 0.0F) {
        hit.normal = -hit.normal;  // face the ray
    }
    hit.reflectivity = reflectivity[geom_id];
    hit.retro_reflective = retro[geom_id] != 0;
    hit.object_id = geom_id;
    return hit;
}

World::World(const core::Scene& scene) : impl_(std::make_unique<Impl>()) {
    // One build thread: BVH construction is deterministic and our scenes are small.
    impl_->device.reset(rtcNewDevice("threads=1"));
    if (!impl_->device) {
        throw std::runtime_error("embree: cannot create a device (error " +
                                 std::to_string(static_cast<int>(rtcGetDeviceError(nullptr))) +
                                 ")");
    }
    rtcSetDeviceErrorFunction(impl_->device.get(), &OnEmbreeError, &impl_->errors);
    impl_->scene.reset(rtcNewScene(impl_->device.get()));
    impl_->errors.Check("creating the scene");
    // Robust traversal: watertight triangle tests, no rays slipping through shared edges.
    rtcSetSceneFlags(impl_->scene.get(), RTC_SCENE_FLAG_ROBUST);
    rtcSetSceneBuildQuality(impl_->scene.get(), RTC_BUILD_QUALITY_HIGH);
    for (std::size_t i = 0; i < scene.objects.size(); ++i) {
        const core::SceneObject& object = scene.objects[i];
        CheckObject(object);
        const auto id = static_cast<unsigned int>(i);
        impl_->reflectivity.push_back(static_cast<float>(object.reflectivity));
        impl_->retro.push_back(object.retro_reflective ? 1 : 0);
        if (const auto* box = std::get_if<core::BoxShape>(&object.shape)) {
            impl_->AddTriangles(BoxTriangles(*box, object.world_T_object), id, object.name);
        } else if (const auto* cyl = std::get_if<core::CylinderShape>(&object.shape)) {
            impl_->AddCylinder(*cyl, object.world_T_object, id, object.name);
        } else {
            const auto& mesh = std::get<core::MeshShape>(object.shape);
            impl_->AddTriangles(MeshTriangles(object, mesh), id, object.name);
        }
    }
    rtcCommitScene(impl_->scene.get());
    impl_->errors.Check("building the scene " + scene.source_path);
}

World::~World() = default;
World::World(World&&) noexcept = default;
World& World::operator=(World&&) noexcept = default;

Hit World::CastOne(const Ray& ray) const {
    assert(std::abs(ray.direction.norm() - 1.0F) < 1e-4F);
    RTCIntersectContext context;
    rtcInitIntersectContext(&context);
    RTCRayHit rh{};
    rh.ray.org_x = ray.origin.x();
    rh.ray.org_y = ray.origin.y();
    rh.ray.org_z = ray.origin.z();
    rh.ray.dir_x = ray.direction.x();
    rh.ray.dir_y = ray.direction.y();
    rh.ray.dir_z = ray.direction.z();
    rh.ray.tnear = 0.0F;
    rh.ray.tfar = ray.tmax_m;
    rh.ray.mask = 0xFFFFFFFFU;
    rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
    rh.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
    rtcIntersect1(impl_->scene.get(), &context, &rh);
    return impl_->MakeHit(rh.hit.geomID, rh.ray.tfar,
                          Eigen::Vector3f(rh.hit.Ng_x, rh.hit.Ng_y, rh.hit.Ng_z), ray.direction);
}

void World::CastPacket(std::span<const Ray> rays, std::span<Hit> hits) const {
    assert(rays.size() == hits.size());
    RTCIntersectContext context;
    rtcInitIntersectContext(&context);
    context.flags = RTC_INTERSECT_CONTEXT_FLAG_COHERENT;  // a pulse's sub-rays are coherent
    const auto trace = [&]<int N>(std::size_t first, std::size_t n) {
        alignas(64) int valid[N];
        alignas(64) typename Packet<N>::RayHit rh;
        for (std::size_t k = 0; k < static_cast<std::size_t>(N); ++k) {
            const bool on = k < n;
            const Ray& r = rays[first + (on ? k : 0)];
            valid[k] = on ? -1 : 0;
            rh.ray.org_x[k] = r.origin.x();
            rh.ray.org_y[k] = r.origin.y();
            rh.ray.org_z[k] = r.origin.z();
            rh.ray.dir_x[k] = r.direction.x();
            rh.ray.dir_y[k] = r.direction.y();
            rh.ray.dir_z[k] = r.direction.z();
            rh.ray.tnear[k] = 0.0F;
            rh.ray.tfar[k] = r.tmax_m;
            rh.ray.time[k] = 0.0F;
            rh.ray.mask[k] = 0xFFFFFFFFU;
            rh.ray.id[k] = static_cast<unsigned int>(k);
            rh.ray.flags[k] = 0U;
            rh.hit.geomID[k] = RTC_INVALID_GEOMETRY_ID;
            rh.hit.instID[0][k] = RTC_INVALID_GEOMETRY_ID;
        }
        Packet<N>::Intersect(valid, impl_->scene.get(), &context, &rh);
        for (std::size_t k = 0; k < n; ++k) {
            hits[first + k] =
                impl_->MakeHit(rh.hit.geomID[k], rh.ray.tfar[k],
                               Eigen::Vector3f(rh.hit.Ng_x[k], rh.hit.Ng_y[k], rh.hit.Ng_z[k]),
                               rays[first + k].direction);
        }
    };
    for (std::size_t first = 0; first < rays.size(); first += 16) {
        const std::size_t n = std::min<std::size_t>(16, rays.size() - first);
        if (n <= 4) {
            trace.template operator()<4>(first, n);
        } else if (n <= 8) {
            trace.template operator()<8>(first, n);
        } else {
            trace.template operator()<16>(first, n);
        }
    }
}

void RayBatch::Resize(std::size_t n) {
    for (std::vector<float>* v : {&ox, &oy, &oz, &dx, &dy, &dz}) {
        v->resize(n);
    }
}

namespace {

void ResizeHits(HitBatch& hits, std::size_t n) {
    hits.distance_m.resize(n);
    hits.cos_incidence.resize(n);
    hits.reflectivity.resize(n);
    hits.retro_reflective.resize(n);
    hits.object_id.resize(n);
}

}  // namespace

void World::CastBatch(const RayBatch& rays, HitBatch& hits) const {
    const std::size_t n = rays.size();
    ResizeHits(hits, n);
    RTCIntersectContext context;
    rtcInitIntersectContext(&context);
    context.flags = RTC_INTERSECT_CONTEXT_FLAG_COHERENT;
    alignas(64) int valid[16];
    alignas(64) RTCRayHit16 rh;
    // Fields Embree only reads, once.
    for (std::size_t k = 0; k < 16; ++k) {
        rh.ray.tnear[k] = 0.0F;
        rh.ray.time[k] = 0.0F;
        rh.ray.mask[k] = 0xFFFFFFFFU;
        rh.ray.id[k] = static_cast<unsigned int>(k);
        rh.ray.flags[k] = 0U;
        // Normals of lanes no ray has hit yet: the |cos| loop reads every lane.
        rh.hit.Ng_x[k] = 0.0F;
        rh.hit.Ng_y[k] = 0.0F;
        rh.hit.Ng_z[k] = 0.0F;
    }
    const float* __restrict reflectivity = impl_->reflectivity.data();
    const std::uint8_t* __restrict retro = impl_->retro.data();
    float* __restrict out_distance = hits.distance_m.data();
    float* __restrict out_cos = hits.cos_incidence.data();
    float* __restrict out_reflectivity = hits.reflectivity.data();
    std::uint8_t* __restrict out_retro = hits.retro_reflective.data();
    std::uint32_t* __restrict out_id = hits.object_id.data();
    for (std::size_t first = 0; first < n; first += 16) {
        const std::size_t m = std::min<std::size_t>(16, n - first);
        if (m == 16) {
            // Fixed-size copies (inlined; std::copy_n here became six memmove calls).
            std::memcpy(rh.ray.org_x, rays.ox.data() + first, sizeof(rh.ray.org_x));
            std::memcpy(rh.ray.org_y, rays.oy.data() + first, sizeof(rh.ray.org_y));
            std::memcpy(rh.ray.org_z, rays.oz.data() + first, sizeof(rh.ray.org_z));
            std::memcpy(rh.ray.dir_x, rays.dx.data() + first, sizeof(rh.ray.dir_x));
            std::memcpy(rh.ray.dir_y, rays.dy.data() + first, sizeof(rh.ray.dir_y));
            std::memcpy(rh.ray.dir_z, rays.dz.data() + first, sizeof(rh.ray.dir_z));
        } else {
            for (std::size_t k = 0; k < 16; ++k) {
                const std::size_t j = first + (k < m ? k : 0);
                rh.ray.org_x[k] = rays.ox[j];
                rh.ray.org_y[k] = rays.oy[j];
                rh.ray.org_z[k] = rays.oz[j];
                rh.ray.dir_x[k] = rays.dx[j];
                rh.ray.dir_y[k] = rays.dy[j];
                rh.ray.dir_z[k] = rays.dz[j];
            }
        }
        // One field at a time: plain fills the compiler turns into vector stores.
        for (std::size_t k = 0; k < 16; ++k) {
            valid[k] = k < m ? -1 : 0;
        }
        for (std::size_t k = 0; k < 16; ++k) {
            rh.ray.tfar[k] = rays.tmax_m;
        }
        for (std::size_t k = 0; k < 16; ++k) {
            rh.hit.geomID[k] = RTC_INVALID_GEOMETRY_ID;
        }
        for (std::size_t k = 0; k < 16; ++k) {
            rh.hit.instID[0][k] = RTC_INVALID_GEOMETRY_ID;
        }
        rtcIntersect16(valid, impl_->scene.get(), &context, &rh);
        // |cos| of all 16 lanes at once (branch-free, so the compiler vectorises it), with the
        // float operations of MakeHit + Hit::normal.dot(direction) in the same order, so batch
        // and single-ray hits agree bit for bit. A degenerate normal (norm 0) gives cos 0.
        alignas(64) float norm_lane[16];
        alignas(64) float cos_lane[16];
        for (std::size_t k = 0; k < 16; ++k) {
            const float nx = rh.hit.Ng_x[k];
            const float ny = rh.hit.Ng_y[k];
            const float nz = rh.hit.Ng_z[k];
            const float norm = std::sqrt(nx * nx + ny * ny + nz * nz);
            norm_lane[k] = norm;
            cos_lane[k] = std::abs(nx / norm * rh.ray.dir_x[k] + ny / norm * rh.ray.dir_y[k] +
                                   nz / norm * rh.ray.dir_z[k]);
        }
        for (std::size_t k = 0; k < m; ++k) {
            const std::size_t j = first + k;
            const unsigned int id = rh.hit.geomID[k];
            if (id == RTC_INVALID_GEOMETRY_ID) {
                out_distance[j] = std::numeric_limits<float>::infinity();
                continue;
            }
            out_distance[j] = rh.ray.tfar[k];
            out_cos[j] = norm_lane[k] > 0.0F ? cos_lane[k] : 0.0F;
            out_reflectivity[j] = reflectivity[id];
            out_retro[j] = retro[id];
            out_id[j] = id;
        }
    }
}

void World::CastBatchSingly(const RayBatch& rays, HitBatch& hits) const {
    const std::size_t n = rays.size();
    ResizeHits(hits, n);
    for (std::size_t j = 0; j < n; ++j) {
        const Eigen::Vector3f dir(rays.dx[j], rays.dy[j], rays.dz[j]);
        const Hit h =
            CastOne(Ray{Eigen::Vector3f(rays.ox[j], rays.oy[j], rays.oz[j]), dir, rays.tmax_m});
        hits.distance_m[j] = h.distance_m;
        if (h.valid()) {
            hits.cos_incidence[j] = std::abs(h.normal.dot(dir));
            hits.reflectivity[j] = h.reflectivity;
            hits.retro_reflective[j] = h.retro_reflective ? 1 : 0;
            hits.object_id[j] = h.object_id;
        }
    }
}

}  // namespace casmap::sim
