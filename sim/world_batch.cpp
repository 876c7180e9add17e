// World's ray batches (world.hpp: CastBatch, CastBatchSingly): 16-wide Embree packets over
// structure-of-arrays rays, bit for bit the hits of single rays.
#include <embree3/rtcore.h>

#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <vector>

#include "casmap/sim/world.hpp"
#include "casmap/sim/world_impl.hpp"

namespace casmap::sim {

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
