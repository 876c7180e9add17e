// The Embree 3 world (sim/world.hpp is the contract; with world_shapes.cpp, world_batch.cpp and
// the private world_impl.hpp the only files that talk to Embree): building the scene, single
// rays and packets. Boxes: 12 triangles. Cylinders: exact analytic user geometry (side and both
// caps solved in closed form, in double precision), so a 2.5 mm pole is round and a range to it is
// exact. Meshes: triangles. Everything is transformed to the world frame at build time (no
// instancing), geometry id = object index in the Scene.
#include "casmap/sim/world.hpp"

#include <embree3/rtcore.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <cassert>
#include <cmath>
#include <memory>
#include <mutex>
#include <stdexcept>
#include <string>
#include <variant>
#include <vector>

#include "casmap/sim/world_impl.hpp"

namespace casmap::sim {
namespace {

void OnEmbreeError(void* user, RTCError code, const char* str) {
    auto* sink = static_cast<detail::ErrorSink*>(user);
    const std::lock_guard<std::mutex> lock(sink->mutex);
    if (sink->code == RTC_ERROR_NONE) {
        sink->code = code;
        sink->message = str != nullptr ? str : "";
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

void World::Impl::AddTriangles(const detail::TriangleSoup& soup,
                               unsigned int id,
                               const std::string& name) {
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
    auto cyl = std::make_unique<detail::Cylinder>();
    cyl->world_R_object = pose.rotation.normalized().toRotationMatrix();
    cyl->center_world = pose.translation;
    cyl->radius_m = shape.radius_m;
    cyl->half_height_m = 0.5 * shape.height_m;
    cylinders.push_back(std::move(cyl));  // owned before Embree holds a pointer to it
    RTCGeometry geom = rtcNewGeometry(device.get(), RTC_GEOMETRY_TYPE_USER);
    errors.Check("creating cylinder " + name);
    rtcSetGeometryUserPrimitiveCount(geom, 1);
    rtcSetGeometryUserData(geom, cylinders.back().get());
    rtcSetGeometryBoundsFunction(geom, &detail::CylinderBounds, nullptr);
    rtcSetGeometryIntersectFunction(geom, &detail::CylinderIntersect);
    rtcSetGeometryOccludedFunction(geom, &detail::CylinderOccluded);
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
        detail::CheckObject(object);
        const auto id = static_cast<unsigned int>(i);
        impl_->reflectivity.push_back(static_cast<float>(object.reflectivity));
        impl_->retro.push_back(object.retro_reflective ? 1 : 0);
        if (const auto* box = std::get_if<core::BoxShape>(&object.shape)) {
            impl_->AddTriangles(detail::BoxTriangles(*box, object.world_T_object), id, object.name);
        } else if (const auto* cyl = std::get_if<core::CylinderShape>(&object.shape)) {
            impl_->AddCylinder(*cyl, object.world_T_object, id, object.name);
        } else {
            const auto& mesh = std::get<core::MeshShape>(object.shape);
            impl_->AddTriangles(detail::MeshTriangles(object, mesh), id, object.name);
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

}  // namespace casmap::sim
