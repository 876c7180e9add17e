#pragma once

// Box geometry shared by the Embree world and the ground truth: one definition of the corners
// and the triangles, so both see exactly the same surface.

#include <Eigen/Core>
#include <array>

#include "casmap/core/pose.hpp"
#include "casmap/core/scene.hpp"

namespace casmap::sim {

/// The 12 triangles of a box as corner indices, wound outwards; corner k sits at
/// (+-x, +-y, +-z) half sizes with bit 0 = +x, bit 1 = +y, bit 2 = +z.
inline constexpr std::array<std::array<int, 3>, 12> kBoxTriangles = {{{0, 2, 3},
                                                                      {0, 3, 1},
                                                                      {4, 5, 7},
                                                                      {4, 7, 6},
                                                                      {0, 1, 5},
                                                                      {0, 5, 4},
                                                                      {2, 6, 7},
                                                                      {2, 7, 3},
                                                                      {0, 4, 6},
                                                                      {0, 6, 2},
                                                                      {1, 3, 7},
                                                                      {1, 7, 5}}};

/// The 8 corners of a box centred on its pose, in the world frame (m).
[[nodiscard]] inline std::array<Eigen::Vector3d, 8> BoxCorners(const core::BoxShape& box,
                                                               const core::Pose& world_T_box) {
    const Eigen::Vector3d h = 0.5 * box.size_m;
    std::array<Eigen::Vector3d, 8> corners;
    for (std::size_t k = 0; k < 8; ++k) {
        corners[k] = world_T_box * Eigen::Vector3d((k & 1U) != 0 ? h.x() : -h.x(),
                                                   (k & 2U) != 0 ? h.y() : -h.y(),
                                                   (k & 4U) != 0 ? h.z() : -h.z());
    }
    return corners;
}

}  // namespace casmap::sim
