#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <limits>
#include <memory>
#include <span>
#include <vector>

#include "casmap/core/scene.hpp"

namespace casmap::sim {

/// One ray in world coordinates. `direction` must be unit length.
struct Ray {
    Eigen::Vector3f origin = Eigen::Vector3f::Zero();
    Eigen::Vector3f direction = Eigen::Vector3f::UnitX();
    float tmax_m = std::numeric_limits<float>::infinity();
};

/// What one ray hit. `distance_m` is +inf for a miss (then the other fields are unset).
struct Hit {
    float distance_m = std::numeric_limits<float>::infinity();
    Eigen::Vector3f normal = Eigen::Vector3f::Zero();  // unit, world frame, facing the ray
    float reflectivity = 0.0F;                         // of the object hit, 0..1
    bool retro_reflective = false;                     // the object is a retro-reflector
    std::uint32_t object_id = std::numeric_limits<std::uint32_t>::max();  // index in Scene

    [[nodiscard]] bool valid() const { return distance_m < std::numeric_limits<float>::infinity(); }
};

/// Rays in structure-of-arrays layout (the layout of Embree's packets), one tmax for all.
/// `direction`s must be unit length.
struct RayBatch {
    std::vector<float> ox, oy, oz, dx, dy, dz;
    float tmax_m = std::numeric_limits<float>::infinity();

    [[nodiscard]] std::size_t size() const { return ox.size(); }
    /// n rays, all at the origin until Set.
    void Resize(std::size_t n);
    void Set(std::size_t j, const Eigen::Vector3f& origin, const Eigen::Vector3f& direction) {
        ox[j] = origin.x();
        oy[j] = origin.y();
        oz[j] = origin.z();
        dx[j] = direction.x();
        dy[j] = direction.y();
        dz[j] = direction.z();
    }
};

/// What each ray of a RayBatch hit: distance (+inf for a miss, then the rest is unset), |cos|
/// of the angle between ray and surface normal, the object (index in the Scene), its
/// reflectivity and whether it is a retro-reflector.
struct HitBatch {
    std::vector<float> distance_m;
    std::vector<float> cos_incidence;
    std::vector<float> reflectivity;
    std::vector<std::uint8_t> retro_reflective;  // 1 for a retro-reflector
    std::vector<std::uint32_t> object_id;
};

/// An Embree 3 scene built from a core::Scene (boxes and cylinders tessellated or as exact
/// geometry, meshes as triangles). Embree appears only in world*.cpp and the private world_*.hpp.
/// Thread-safe for concurrent casts after construction.
class World {
public:
    /// Throws InputError naming the object if a shape cannot be built.
    explicit World(const core::Scene& scene);
    ~World();
    World(World&&) noexcept;
    World& operator=(World&&) noexcept;
    World(const World&) = delete;
    World& operator=(const World&) = delete;

    /// Casts rays.size() rays (hits.size() must equal it) as Embree packets of up to 16 rays.
    void CastPacket(std::span<const Ray> rays, std::span<Hit> hits) const;
    /// Casts every ray of `rays` in order as Embree packets of 16 (consecutive rays share a
    /// packet, so coherent runs of rays, e.g. a scan's pulses, trace together); fills `hits`.
    void CastBatch(const RayBatch& rays, HitBatch& hits) const;
    /// The same with one rtcIntersect1 call per ray.
    void CastBatchSingly(const RayBatch& rays, HitBatch& hits) const;
    /// Casts one ray with rtcIntersect1 (the reference for benchmarks and tests).
    [[nodiscard]] Hit CastOne(const Ray& ray) const;

private:
    struct Impl;
    std::unique_ptr<Impl> impl_;
};

}  // namespace casmap::sim
