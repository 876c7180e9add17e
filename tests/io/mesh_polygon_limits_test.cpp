// Slow meshes: assimp triangulates a polygon of k corners by ear clipping in time ~k^2 (an OBJ of
// 900 KB holding one 32 000-corner polygon took 20 s; fuzz finding, docs/fuzzing.md). casmap
// checks the polygons after assimp read them and before it triangulates (docs/limits.md).
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <string>

#include "casmap/core/input_error.hpp"
#include "casmap/core/limits.hpp"
#include "casmap/io/mesh_import.hpp"

namespace casmap::io {
namespace {
using ::testing::HasSubstr;

// An OBJ of `polygons` star-shaped (non-convex) polygons of `corners` corners each, side by
// side along x.
std::string StarsObj(int polygons, int corners) {
    std::string obj;
    for (int p = 0; p < polygons; ++p) {
        for (int i = 0; i < corners; ++i) {
            const double a = 2.0 * M_PI * i / corners;
            const double r = i % 2 == 0 ? 1.0 : 0.5;
            obj += "v " + std::to_string(3.0 * p + r * std::cos(a)) + " " +
                   std::to_string(r * std::sin(a)) + " 0\n";
        }
    }
    for (int p = 0; p < polygons; ++p) {
        obj += "f";
        for (int i = 1; i <= corners; ++i) {
            obj += " " + std::to_string(p * corners + i);
        }
        obj += "\n";
    }
    return obj;
}

std::string ErrorOf(const std::string& obj, double* seconds) {
    const auto start = std::chrono::steady_clock::now();
    std::string message = "no error";
    try {
        (void)ImportMeshFromMemory(obj, "obj", "star.obj", Eigen::Vector3d::Ones());
    } catch (const InputError& e) {
        message = e.what();
    }
    *seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    return message;
}

TEST(MeshPolygonLimits, APolygonOfTooManyCornersIsRejectedBeforeTriangulation) {
    // 30 000 corners: about 18 s in assimp's triangulation (its validation allows 32 767);
    // rejected after the linear read.
    double seconds = 0.0;
    const std::string message = ErrorOf(StarsObj(1, 30'000), &seconds);
    EXPECT_THAT(message, HasSubstr("star.obj: mesh polygon corners = 30000 (polygon corner limit "
                                   "1024, see docs/limits.md)"));
    EXPECT_LT(seconds, 5.0);
}

TEST(MeshPolygonLimits, ManyLargePolygonsAreRejectedByTheirTotal) {
    // 200 x 600 corners: each within the limit, 120 000 in all.
    double seconds = 0.0;
    const std::string message = ErrorOf(StarsObj(200, 600), &seconds);
    EXPECT_THAT(message, HasSubstr("star.obj: mesh corners of polygons with more than 4 = 100"));
    EXPECT_THAT(message, HasSubstr("limit 100000"));
}

TEST(MeshPolygonLimits, PolygonsWithinTheLimitsAreStillTriangulated) {
    const int corners = static_cast<int>(core::limits::kMaxPolygonCorners);
    const core::MeshShape star =
        ImportMeshFromMemory(StarsObj(1, corners), "obj", "star.obj", Eigen::Vector3d::Ones());
    EXPECT_EQ(star.triangles.size(), static_cast<std::size_t>(corners - 2));
    const core::MeshShape quads =
        ImportMeshFromMemory("v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf 1 2 3 4\n", "obj", "quad.obj",
                             Eigen::Vector3d::Ones());
    EXPECT_EQ(quads.triangles.size(), 2U);
}

// A PLY header without its end_header line (fuzz finding: 477 bytes kept assimp's PLY reader
// busy for over 10 s) is rejected before assimp reads it; a complete header still reads.
TEST(MeshPolygonLimits, APlyHeaderWithoutEndHeaderIsRejected) {
    const std::string head =
        "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
        "property float z\nelement face 1\nproperty list uchar int vertex_indices\n";
    const std::string body = "0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n";
    std::string message = "no error";
    try {
        (void)ImportMeshFromMemory(head + body, "ply", "cut.ply", Eigen::Vector3d::Ones());
    } catch (const InputError& e) {
        message = e.what();
    }
    // The body's first line is read as a header line, the first that is not one.
    EXPECT_THAT(message, HasSubstr("cut.ply: PLY line 9 = 0 0 0 (must be format, comment"));
    const core::MeshShape shape = ImportMeshFromMemory(head + "end_header\n" + body, "ply",
                                                       "whole.ply", Eigen::Vector3d::Ones());
    EXPECT_EQ(shape.triangles.size(), 1u);
}

}  // namespace
}  // namespace casmap::io
