#include "casmap/io/scene_file.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <unistd.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <string>
#include <variant>
#include <vector>

#include "casmap/core/input_error.hpp"
#include "casmap/io/mesh_import.hpp"

namespace casmap::io {
namespace {

namespace fs = std::filesystem;

const fs::path kMeshDir = fs::path(CASMAP_SOURCE_DIR) / "tests/data/meshes";

// A fresh directory per test holding scene.yaml (and copies of meshes when asked).
class SceneFileTest : public ::testing::Test {
protected:
    void SetUp() override {
        const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
        dir_ = fs::temp_directory_path() /
               ("casmap_scene_" + std::to_string(getpid()) + "_" + info->name());
        fs::remove_all(dir_);
        fs::create_directories(dir_ / "meshes");
        for (const char* name : {"box.stl", "cylinder.obj", "plane.ply"}) {
            fs::copy_file(kMeshDir / name, dir_ / "meshes" / name);
        }
    }
    void TearDown() override { fs::remove_all(dir_); }

    std::string Write(const std::string& yaml) {
        const fs::path path = dir_ / "scene.yaml";
        std::ofstream(path) << yaml;
        return path.string();
    }
    // Loads `yaml` expecting an InputError and returns its message.
    std::string ErrorOf(const std::string& yaml) {
        const std::string path = Write(yaml);
        try {
            (void)LoadScene(path);
        } catch (const InputError& e) {
            return e.what();
        }
        ADD_FAILURE() << "no InputError for:\n" << yaml;
        return "";
    }

    fs::path dir_;
};

TEST_F(SceneFileTest, LoadsShapesPosesAndDefaults) {
    const core::Scene scene = LoadScene(Write(R"(objects:
  - name: floor
    box: {size_m: [8.0, 6.0, 0.02]}
    pose: {xyz_m: [2.0, 0.0, -0.01], rpy_deg: [0, 0, 0]}
    reflectivity: 0.4
    terrain: true
  - name: pole1
    cylinder: {radius_m: 0.012, height_m: 0.914}
    pose: [3.0, 0.5, 0.457, 0, 0, 90]
  - name: rock
    mesh: meshes/box.stl
    scale: 0.001
    pose: {xyz_m: [2.5, -0.4, 0.0]}
)"));
    ASSERT_EQ(scene.objects.size(), 3U);
    const core::SceneObject& floor = scene.objects[0];
    EXPECT_EQ(floor.name, "floor");
    EXPECT_TRUE(floor.terrain);
    EXPECT_DOUBLE_EQ(floor.reflectivity, 0.4);
    EXPECT_TRUE(std::get<core::BoxShape>(floor.shape).size_m.isApprox(Eigen::Vector3d(8, 6, 0.02)));
    EXPECT_DOUBLE_EQ(floor.world_T_object.translation.z(), -0.01);

    const core::SceneObject& pole = scene.objects[1];
    EXPECT_FALSE(pole.terrain);
    EXPECT_DOUBLE_EQ(pole.reflectivity, 0.5);  // the documented default
    EXPECT_DOUBLE_EQ(std::get<core::CylinderShape>(pole.shape).radius_m, 0.012);
    // yaw 90 deg maps object +x to world +y
    const Eigen::Vector3d x_world = pole.world_T_object.rotation * Eigen::Vector3d::UnitX();
    EXPECT_NEAR(x_world.y(), 1.0, 1e-12);

    const auto& mesh = std::get<core::MeshShape>(scene.objects[2].shape);
    EXPECT_EQ(mesh.triangles.size(), 12U);
    EXPECT_NEAR(mesh.vertices[0].cwiseAbs().maxCoeff(), 0.2, 1e-6);  // 200 mm -> 0.2 m
    EXPECT_TRUE(scene.objects[2].world_T_object.rotation.isApprox(Eigen::Quaterniond::Identity()));
}

TEST_F(SceneFileTest, PerAxisScale) {
    const core::Scene scene = LoadScene(Write(R"(objects:
  - name: box
    mesh: meshes/box.stl
    scale: [0.001, 0.002, 0.003]
)"));
    const auto& mesh = std::get<core::MeshShape>(scene.objects[0].shape);
    Eigen::Vector3f max = Eigen::Vector3f::Constant(-1e9F);
    for (const Eigen::Vector3f& v : mesh.vertices) {
        max = max.cwiseMax(v);
    }
    EXPECT_TRUE(max.isApprox(Eigen::Vector3f(0.2F, 0.3F, 0.3F), 1e-6F)) << max.transpose();
}

TEST(MeshImport, ReadsStlObjPlyWithTheSameTriangles) {
    struct Case {
        const char* stem;
        std::size_t triangles;
    };
    for (const Case c : {Case{"plane", 2}, Case{"box", 12}, Case{"cylinder", 384}}) {
        for (const char* ext : {".stl", ".obj", ".ply"}) {
            const fs::path path = kMeshDir / (std::string(c.stem) + ext);
            const core::MeshShape mesh = ImportMesh(path, Eigen::Vector3d::Constant(0.001));
            EXPECT_EQ(mesh.triangles.size(), c.triangles) << path;
            for (const Eigen::Vector3i& t : mesh.triangles) {
                ASSERT_TRUE((t.array() >= 0).all() &&
                            (t.array() < static_cast<int>(mesh.vertices.size())).all());
            }
        }
    }
    EXPECT_EQ(ImportMesh(kMeshDir / "box_ascii.stl", Eigen::Vector3d::Ones()).triangles.size(),
              12U);
}

TEST_F(SceneFileTest, RejectsReflectivityOutsideZeroToOneWithLineAndField) {
    const std::string message = ErrorOf(R"(objects:
  - name: a
    box: {size_m: [1, 1, 1]}
  - name: b
    box: {size_m: [1, 1, 1]}
  - name: c
    box: {size_m: [1, 1, 1]}
    reflectivity: 1.4
)");
    EXPECT_EQ(message, (dir_ / "scene.yaml").string() +
                           ":8:19: objects[2].reflectivity = 1.4 (allowed: 0..1)");
}

// The value rules are core::Scene::Validate()'s; the loader names the key's line:column and
// quotes the value as the file writes it.
TEST_F(SceneFileTest, SceneRulesNameTheKeysPlaceAndItsText) {
    const std::string file = (dir_ / "scene.yaml").string();
    EXPECT_EQ(ErrorOf("objects:\n  - name: a\n    box: {size_m: [1, 1, 1]}\n"
                      "  - name: a\n    cylinder: {radius_m: 1, height_m: 1}\n"),
              file + ":4:11: objects[1].name = a (duplicate name)");
    EXPECT_EQ(ErrorOf("objects:\n  - name: a\n    box: {size_m: [1, 1, 1]}\n"
                      "    pose: {xyz_m: [0, 0, 2.0e4]}\n"),
              file +
                  ":4:11: objects[0].pose = [0, 0, 20000] (position within +-10000 m, see "
                  "docs/limits.md)");
    EXPECT_EQ(ErrorOf("objects:\n  - name: a\n    box: {size_m: [1, 1, 1]}\n"
                      "    reflectivity: 1.40\n"),
              file + ":4:19: objects[0].reflectivity = 1.40 (allowed: 0..1)");
    EXPECT_EQ(ErrorOf("objects: []\n"), file + ":1:10: objects = [] (must be a non-empty list)");
}

TEST_F(SceneFileTest, RejectsUnknownKeys) {
    EXPECT_THAT(ErrorOf("objects:\n  - name: a\n    box: {size_m: [1, 1, 1]}\n    colour: red\n"),
                ::testing::HasSubstr("scene.yaml:4:5: objects[0].colour (unknown key"));
    EXPECT_THAT(ErrorOf("objects:\n  - name: a\n    box: {size_m: [1, 1, 1], sise: 2}\n"),
                ::testing::HasSubstr("objects[0].box.sise (unknown key"));
    EXPECT_THAT(ErrorOf("object:\n  - name: a\n"),
                ::testing::HasSubstr("scene.yaml:1:1: object (unknown key"));
    EXPECT_THAT(ErrorOf("objects:\n  - name: a\n    box: {size_m: [1, 1, 1]}\n"
                        "    pose: {xyz: [0, 0, 0]}\n"),
                ::testing::HasSubstr("objects[0].pose.xyz (unknown key"));
}

TEST_F(SceneFileTest, RejectsBadMeshes) {
    EXPECT_THAT(ErrorOf("objects:\n  - name: m\n    mesh: meshes/nothere.stl\n"),
                ::testing::HasSubstr("scene.yaml:3:11: objects[0].mesh = meshes/nothere.stl "
                                     "(file not found"));
    fs::copy_file(kMeshDir / "empty.stl", dir_ / "meshes/empty.stl");
    fs::copy_file(kMeshDir / "garbage.ply", dir_ / "meshes/garbage.ply");
    EXPECT_THAT(ErrorOf("objects:\n  - name: m\n    mesh: meshes/empty.stl\n"),
                ::testing::HasSubstr("scene.yaml:3:11: objects[0].mesh = meshes/empty.stl"));
    EXPECT_THAT(ErrorOf("objects:\n  - name: m\n    mesh: meshes/garbage.ply\n"),
                ::testing::HasSubstr("scene.yaml:3:11: objects[0].mesh = meshes/garbage.ply"));
    EXPECT_THAT(ErrorOf("objects:\n  - name: m\n    mesh: meshes/box.stl\n    scale: -1\n"),
                ::testing::HasSubstr("scene.yaml:4:12: objects[0].scale = -1 (allowed: > 0)"));
}

TEST_F(SceneFileTest, RejectsNonPositiveSizes) {
    EXPECT_THAT(
        ErrorOf("objects:\n  - name: a\n    box: {size_m: [1, -2, 1]}\n"),
        ::testing::HasSubstr(
            "scene.yaml:3:23: objects[0].box.size_m[1] = -2 (allowed: 0 < size <= 10000 m"));
    EXPECT_THAT(
        ErrorOf("objects:\n  - name: a\n    cylinder: {radius_m: 0, height_m: 1}\n"),
        ::testing::HasSubstr("objects[0].cylinder.radius_m = 0 (allowed: 0 < size <= 10000 m"));
    EXPECT_THAT(ErrorOf("objects:\n  - name: a\n    cylinder: {radius_m: 1}\n"),
                ::testing::HasSubstr("objects[0].cylinder.height_m (required key is missing)"));
    EXPECT_THAT(ErrorOf("objects:\n  - name: a\n    box: {size_m: [1, 1]}\n"),
                ::testing::HasSubstr("objects[0].box.size_m = [1, 1] (must be a list of 3"));
    EXPECT_THAT(ErrorOf("objects:\n  - name: a\n    box: {size_m: [1, .nan, 1]}\n"),
                ::testing::HasSubstr("objects[0].box.size_m[1] = .nan (must be finite)"));
}

TEST_F(SceneFileTest, RejectsPosesThatAreNotSixNumbers) {
    const std::string box = "objects:\n  - name: a\n    box: {size_m: [1, 1, 1]}\n";
    EXPECT_THAT(ErrorOf(box + "    pose: [1, 2, 3, 4, 5]\n"),
                ::testing::HasSubstr(
                    "scene.yaml:4:11: objects[0].pose = [1, 2, 3, 4, 5] (must be a list of 6"));
    EXPECT_THAT(ErrorOf(box + "    pose: {xyz_m: [1, 2, 3], rpy_deg: [0, 0]}\n"),
                ::testing::HasSubstr("objects[0].pose.rpy_deg = [0, 0] (must be a list of 3"));
    EXPECT_THAT(ErrorOf(box + "    pose: {xyz_m: [1, x, 3]}\n"),
                ::testing::HasSubstr("objects[0].pose.xyz_m[1] = x (must be a number)"));
    EXPECT_THAT(ErrorOf(box + "    pose: 3\n"), ::testing::HasSubstr("objects[0].pose = 3"));
}

TEST_F(SceneFileTest, RejectsStructuralMistakes) {
    EXPECT_THAT(ErrorOf("objects:\n  - name: a\n    box: {size_m: [1, 1, 1]}\n"
                        "    cylinder: {radius_m: 1, height_m: 1}\n"),
                ::testing::HasSubstr("objects[0] = a (needs exactly one of box, cylinder, mesh)"));
    EXPECT_THAT(ErrorOf("objects:\n  - box: {size_m: [1, 1, 1]}\n"),
                ::testing::HasSubstr("objects[0].name (required key is missing)"));
    EXPECT_THAT(ErrorOf("objects:\n  - name: a\n    box: {size_m: [1, 1, 1]}\n"
                        "  - name: a\n    box: {size_m: [1, 1, 1]}\n"),
                ::testing::HasSubstr("scene.yaml:4:11: objects[1].name = a (duplicate name)"));
    EXPECT_THAT(ErrorOf("objects:\n  - name: a\n    box: {size_m: [1, 1, 1]}\n    scale: 2\n"),
                ::testing::HasSubstr("objects[0].scale = 2 (only allowed with mesh)"));
    EXPECT_THAT(ErrorOf("objects:\n  - name: a\n    box: {size_m: [1, 1, 1]}\n    terrain: 3\n"),
                ::testing::HasSubstr("objects[0].terrain = 3 (wrong type)"));
    EXPECT_THAT(ErrorOf("objects: []\n"),
                ::testing::HasSubstr("objects = [] (must be a non-empty"));
    EXPECT_THAT(ErrorOf("objects:\n  - name: a\n    box: [1, 1, 1]\n"),
                ::testing::HasSubstr("objects[0].box (must be a mapping)"));
}

TEST_F(SceneFileTest, RetroReflectiveIsABooleanDefaultingToFalse) {
    const core::Scene scene = LoadScene(Write(R"(objects:
  - name: sign
    box: {size_m: [0.02, 0.6, 0.6]}
    reflectivity: 0.8
    retro_reflective: true
  - name: wall
    box: {size_m: [0.2, 4, 2]}
)"));
    ASSERT_EQ(scene.objects.size(), 2U);
    EXPECT_TRUE(scene.objects[0].retro_reflective);
    EXPECT_DOUBLE_EQ(scene.objects[0].reflectivity, 0.8);
    EXPECT_FALSE(scene.objects[1].retro_reflective);
    const std::string message = ErrorOf(R"(objects:
  - name: a
    box: {size_m: [1, 1, 1]}
  - name: sign
    box: {size_m: [1, 1, 1]}
    retro_reflective: very
)");
    EXPECT_THAT(message, ::testing::HasSubstr((dir_ / "scene.yaml").string() + ":6:23: "));
    EXPECT_THAT(message, ::testing::HasSubstr("objects[1].retro_reflective = very (wrong type)"));
}

TEST(SceneFile, MissingFileIsAnInputError) {
    EXPECT_THROW((void)LoadScene("/nonexistent/scene.yaml"), InputError);
}

}  // namespace
}  // namespace casmap::io

namespace casmap::io {
namespace {

// Table I of Ye & Borenstein, independent of scripts/make_scenes.py: object names per course.
TEST(CommittedScenes, CoursesHoldTableIObjectsWithPrintedDimensions) {
    const std::map<int, std::vector<std::string>> table = {
        {1,
         {"parallelepiped2", "parallelepiped3", "pole1", "pole2", "pole3", "pole4", "pole5",
          "pole7", "pole9"}},
        {2,
         {"parallelepiped3", "pole1", "pole2", "pole3", "pole4", "pole5", "pole6", "pole7",
          "pole9"}},
        {3, {"pole1", "pole2", "pole3", "pole4", "pole5", "pole6", "pole7", "pole9"}},
        {4, {"parallelepiped2", "parallelepiped4", "cylinder", "pole1", "pole2", "pole4", "pole6"}},
        {5, {"parallelepiped1", "parallelepiped2", "pole1", "pole2", "pole3", "pole4", "pole6"}},
        {6,
         {"parallelepiped1", "parallelepiped2", "cylinder", "pole1", "pole2", "pole3", "pole4",
          "pole6"}},
        {7,
         {"parallelepiped1", "parallelepiped2", "cylinder", "pole1", "pole2", "pole3", "pole4",
          "pole5", "pole6", "pole7"}},
        {8,
         {"parallelepiped2", "parallelepiped4", "cylinder", "pole1", "pole2", "pole3", "pole4",
          "pole5", "pole6", "pole7", "pole8", "pole9"}},
        {9,
         {"parallelepiped2", "parallelepiped4", "pole1", "pole2", "pole3", "pole4", "pole5",
          "pole6", "pole7", "pole8", "pole9"}},
        {10,
         {"parallelepiped2", "parallelepiped3", "parallelepiped4", "pole1", "pole2", "pole3",
          "pole4", "pole5", "pole7", "pole9"}},
        {11,
         {"parallelepiped1", "parallelepiped2", "parallelepiped3", "pole1", "pole2", "pole3",
          "pole4", "pole5", "pole7", "pole9"}},
        {12,
         {"parallelepiped2", "parallelepiped4", "pole1", "pole2", "pole3", "pole4", "pole5",
          "pole7", "pole9"}},
        {13,
         {"parallelepiped2", "parallelepiped3", "pole1", "pole2", "pole3", "pole4", "pole5",
          "pole6", "pole7", "pole9"}},
        {14, {"parallelepiped1", "parallelepiped2", "parallelepiped3"}},
        {15, {"parallelepiped2", "parallelepiped3", "parallelepiped4"}},
        {16, {"parallelepiped2", "parallelepiped3"}},
    };
    const std::map<std::string, Eigen::Vector3d> boxes = {
        {"parallelepiped1", {0.530, 0.559, 0.462}},
        {"parallelepiped2", {0.413, 0.456, 0.414}},
        {"parallelepiped3", {0.400, 0.343, 0.213}},
        {"parallelepiped4", {0.514, 0.540, 0.327}}};
    const double pole_diameter_mm[] = {24, 21, 19, 15, 11, 9, 6, 4.5, 2.5};
    for (const auto& [course, names] : table) {
        char file[64];
        std::snprintf(file, sizeof(file), "/scenes/courses/course%02d.yaml", course);
        const core::Scene scene = LoadScene(std::string(CASMAP_SOURCE_DIR) + file);
        ASSERT_EQ(scene.objects.size(), names.size() + 1) << file;
        EXPECT_EQ(scene.objects[0].name, "floor");
        const auto& floor = std::get<core::BoxShape>(scene.objects[0].shape);
        EXPECT_NEAR(scene.objects[0].world_T_object.translation.z() + floor.size_m.z() / 2, 0.0,
                    1e-12);
        for (std::size_t i = 0; i < names.size(); ++i) {
            const core::SceneObject& o = scene.objects[i + 1];
            ASSERT_EQ(o.name, names[i]) << file;
            const Eigen::Vector3d& p = o.world_T_object.translation;
            if (boxes.count(o.name) != 0) {
                const auto& b = std::get<core::BoxShape>(o.shape);
                EXPECT_TRUE(b.size_m.isApprox(boxes.at(o.name), 1e-12)) << file << " " << o.name;
                EXPECT_NEAR(p.z(), b.size_m.z() / 2, 1e-12);  // resting on the floor
            } else {
                const auto& c = std::get<core::CylinderShape>(o.shape);
                const bool pole = o.name != "cylinder";
                const double diameter =
                    pole ? pole_diameter_mm[o.name.back() - '1'] / 1000.0 : 0.411;
                EXPECT_NEAR(2 * c.radius_m, diameter, 1e-12) << file << " " << o.name;
                EXPECT_NEAR(c.height_m, pole ? 0.914 : 0.459, 1e-12);
                EXPECT_NEAR(p.z(), c.height_m / 2, 1e-12);
            }
            // Inside the map region x in [1, 6), y in [-1, 1).
            EXPECT_TRUE(p.x() > 1.0 && p.x() < 6.0 && p.y() > -1.0 && p.y() < 1.0) << o.name;
        }
    }
}

TEST(CommittedScenes, IndoorAndOutdoorLoad) {
    const core::Scene indoor = LoadScene(std::string(CASMAP_SOURCE_DIR) + "/scenes/indoor.yaml");
    EXPECT_GT(indoor.objects.size(), 8U);
    const core::Scene outdoor = LoadScene(std::string(CASMAP_SOURCE_DIR) + "/scenes/outdoor.yaml");
    int terrain = 0;
    for (const core::SceneObject& o : outdoor.objects) {
        if (o.terrain) {
            ++terrain;
            EXPECT_EQ(o.name, "ground");
            EXPECT_GT(std::get<core::MeshShape>(o.shape).triangles.size(), 1000U);
        }
    }
    EXPECT_EQ(terrain, 1);
}

}  // namespace
}  // namespace casmap::io
