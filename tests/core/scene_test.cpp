#include "casmap/core/scene.hpp"

#include <gtest/gtest.h>

#include <string>

#include "casmap/core/input_error.hpp"

namespace casmap::core {
namespace {

Scene OneBox() {
    Scene scene;
    scene.source_path = "course.yaml";
    SceneObject box;
    box.name = "block";
    box.shape = BoxShape{Eigen::Vector3d(0.2, 0.3, 0.1)};
    scene.objects.push_back(box);
    return scene;
}

std::string ErrorOf(const Scene& scene) {
    try {
        scene.Validate();
    } catch (const InputError& e) {
        return e.what();
    }
    return "(no error)";
}

TEST(Scene, AValidScenePasses) {
    Scene scene = OneBox();
    SceneObject post;
    post.name = "post";
    post.shape = CylinderShape{};
    post.world_T_object.translation = Eigen::Vector3d(3.0, -1.0, 0.5);
    scene.objects.push_back(post);
    EXPECT_NO_THROW(scene.Validate());
}

TEST(Scene, EachRuleNamesTheFileTheObjectFieldAndTheValue) {
    EXPECT_EQ(ErrorOf(Scene{"course.yaml", {}}),
              "course.yaml: objects = [] (must be a non-empty list)");
    Scene s = OneBox();
    s.objects[0].name.clear();
    EXPECT_EQ(ErrorOf(s), "course.yaml: objects[0].name (must not be empty)");
    s = OneBox();
    s.objects.push_back(s.objects[0]);
    EXPECT_EQ(ErrorOf(s), "course.yaml: objects[1].name = block (duplicate name)");
    s = OneBox();
    s.objects[0].shape = BoxShape{Eigen::Vector3d(1.0, -0.5, 1.0)};
    EXPECT_EQ(ErrorOf(s),
              "course.yaml: objects[0].box.size_m[1] = -0.5 (allowed: 0 < size <= 10000 m, see "
              "docs/limits.md)");
    s = OneBox();
    s.objects[0].shape = CylinderShape{0.5, 0.0};
    EXPECT_EQ(ErrorOf(s),
              "course.yaml: objects[0].cylinder.height_m = 0 (allowed: 0 < size <= 10000 m, see "
              "docs/limits.md)");
    s = OneBox();
    s.objects[0].world_T_object.translation.z() = 2e4;
    EXPECT_EQ(ErrorOf(s),
              "course.yaml: objects[0].pose = [0, 0, 20000] (position within +-10000 m, see "
              "docs/limits.md)");
    s = OneBox();
    s.objects[0].reflectivity = 1.4;
    EXPECT_EQ(ErrorOf(s), "course.yaml: objects[0].reflectivity = 1.4 (allowed: 0..1)");
}

TEST(Scene, AMeshNeedsTrianglesOnItsVertices) {
    Scene s = OneBox();
    MeshShape mesh;
    mesh.source_path = "rock.stl";
    s.objects[0].shape = mesh;
    EXPECT_EQ(ErrorOf(s), "course.yaml: objects[0].mesh = rock.stl (has no triangles)");
    mesh.vertices = {Eigen::Vector3f::Zero(), Eigen::Vector3f::UnitX(), Eigen::Vector3f::UnitY()};
    mesh.triangles = {Eigen::Vector3i(0, 1, 3)};
    s.objects[0].shape = mesh;
    EXPECT_EQ(ErrorOf(s),
              "course.yaml: objects[0].mesh = rock.stl (a triangle names a vertex that does not "
              "exist)");
    mesh.triangles = {Eigen::Vector3i(0, 1, 2)};
    s.objects[0].shape = mesh;
    EXPECT_NO_THROW(s.Validate());
}

}  // namespace
}  // namespace casmap::core
