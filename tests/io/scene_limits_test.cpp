// Hostile small inputs for the simulator's readers: scene YAML, meshes and rig files are
// checked against core/limits.hpp before allocating (docs/limits.md), and errors name the
// file and the field.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "casmap/core/input_error.hpp"
#include "casmap/io/mesh_import.hpp"
#include "casmap/io/rig_config.hpp"
#include "casmap/io/scene_file.hpp"
#include "tests/temp_dir.hpp"

namespace casmap::io {
namespace {
namespace fs = std::filesystem;
using ::testing::HasSubstr;

fs::path Write(const std::string& dir_name, const std::string& file, const std::string& text) {
    const fs::path dir = casmap::test::MakeTempDir("scene_limits_" + dir_name);
    std::ofstream(dir / file, std::ios::binary) << text;
    return dir / file;
}

template <typename F>
std::string ErrorOf(F&& f) {
    try {
        f();
    } catch (const InputError& e) {
        return e.what();
    }
    return "no error";
}

TEST(SceneLimits, DuplicateKeyIsRejectedNotResolvedToTheFirst) {
    const fs::path path = Write("dup", "scene.yaml",
                                "objects:\n  - name: a\n    box: {size_m: [1, 1, 1]}\n"
                                "    reflectivity: 0.2\n    reflectivity: 0.9\n");
    EXPECT_THAT(ErrorOf([&] { (void)LoadScene(path.string()); }),
                HasSubstr("scene.yaml:5:5: reflectivity (duplicate key)"));
}

TEST(SceneLimits, EmptySceneNamesTheField) {
    const fs::path path = Write("empty", "scene.yaml", "");
    EXPECT_THAT(ErrorOf([&] { (void)LoadScene(path.string()); }),
                HasSubstr("scene.yaml: top level (must be a mapping, found nothing"));
}

TEST(SceneLimits, ABoxOfAMillionKilometresIsRejected) {
    const fs::path path =
        Write("huge_box", "scene.yaml", "objects:\n  - name: a\n    box: {size_m: [1e9, 1, 1]}\n");
    const std::string message = ErrorOf([&] { (void)LoadScene(path.string()); });
    EXPECT_THAT(message, HasSubstr("objects[0].box.size_m[0] = 1e9"));
    EXPECT_THAT(message, HasSubstr("10000 m"));
}

TEST(SceneLimits, AnObjectFarAwayIsRejected) {
    const fs::path path = Write("far", "scene.yaml",
                                "objects:\n  - name: a\n    box: {size_m: [1, 1, 1]}\n"
                                "    pose: [1e8, 0, 0, 0, 0, 0]\n");
    EXPECT_THAT(ErrorOf([&] { (void)LoadScene(path.string()); }), HasSubstr("objects[0].pose"));
}

TEST(SceneLimits, AliasBombInAPoseStopsWithAShortMessage) {
    std::string text = "x: &a0 [1, 2, 3, 4, 5, 6, 7, 8, 9]\n";
    for (int i = 1; i < 12; ++i) {
        const std::string prev = "*a" + std::to_string(i - 1);
        text += "x" + std::to_string(i) + ": &a" + std::to_string(i) + " [" + prev + ", " + prev +
                ", " + prev + ", " + prev + ", " + prev + ", " + prev + "]\n";
    }
    text += "objects:\n  - name: a\n    box: {size_m: [1, 1, 1]}\n    pose: *a11\n";
    const fs::path path = Write("bomb", "scene.yaml", text);
    const std::string message = ErrorOf([&] { (void)LoadScene(path.string()); });
    EXPECT_THAT(message, HasSubstr("yaml nodes"));
    EXPECT_LT(message.size(), 200U);
}

TEST(SceneLimits, PlyHeaderDeclaringFourBillionVerticesIsRejectedBeforeAssimp) {
    const fs::path path = Write("ply", "huge.ply",
                                "ply\nformat binary_little_endian 1.0\nelement vertex 4000000000\n"
                                "property float x\nproperty float y\nproperty float z\n"
                                "end_header\n");
    const std::string message = ErrorOf([&] { (void)ImportMesh(path, Eigen::Vector3d::Ones()); });
    EXPECT_THAT(message, HasSubstr("huge.ply: PLY header: element vertex = 4000000000"));
    EXPECT_THAT(message, HasSubstr("limit 10000000"));
}

TEST(SceneLimits, PlyHeaderDeclaringMoreElementsThanBytesIsRejected) {
    const std::string ply =
        "ply\nformat ascii 1.0\nelement vertex 5000000\nproperty float x\n"
        "end_header\n0\n";
    EXPECT_THAT(ErrorOf([&] {
                    (void)ImportMeshFromMemory(ply, "ply", "mem.ply", Eigen::Vector3d::Ones());
                }),
                HasSubstr("more elements than the file has bytes"));
}

TEST(SceneLimits, BinaryStlClaimingMoreTrianglesThanItHoldsIsRejected) {
    std::string stl(84, '\0');
    stl[80] = '\xff';
    stl[81] = '\xff';
    stl[82] = '\x0f';  // 1 M triangles, 50 MB, in an 84-byte file
    EXPECT_THAT(ErrorOf([&] {
                    (void)ImportMeshFromMemory(stl, "stl", "mem.stl", Eigen::Vector3d::Ones());
                }),
                HasSubstr("mem.stl: STL header: triangle count = 1048575"));
}

TEST(SceneLimits, MeshFromMemoryMatchesTheFile) {
    const fs::path ply = fs::path(CASMAP_SOURCE_DIR) / "tests/data/meshes/box.ply";
    std::ifstream in(ply, std::ios::binary);
    const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    const core::MeshShape a = ImportMesh(ply, Eigen::Vector3d::Ones());
    const core::MeshShape b =
        ImportMeshFromMemory(bytes, "ply", "box.ply", Eigen::Vector3d::Ones());
    EXPECT_EQ(a.vertices.size(), b.vertices.size());
    EXPECT_EQ(a.triangles.size(), b.triangles.size());
}

TEST(SceneLimits, MalformedPlyThatTripsAnAssimpAssertIsAnInputErrorNotAnAbort) {
    // Found by io/fuzz/mesh_fuzz: assimp's TriangulateProcess ai_assert aborted the process.
    const fs::path file =
        fs::path(CASMAP_SOURCE_DIR) / "tests/data/fuzz/mesh/regress_triangulate_assert.bin";
    std::ifstream in(file, std::ios::binary);
    const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    ASSERT_GT(bytes.size(), 1U);
    EXPECT_THAT(
        ErrorOf([&] {
            (void)ImportMeshFromMemory(bytes.substr(1), "ply", "bad.ply", Eigen::Vector3d::Ones());
        }),
        HasSubstr("bad.ply: PLY line 87 (vertex 76) = -250.?00000 (must be a finite number)"));
}

TEST(RigLimits, CoursesOfAThousandKilometresOrCrawlingSpeedsAreRejected) {
    const struct {
        const char* yaml;
        const char* expected;
    } cases[] = {
        {"table:\n  course: {end_x_m: 1e6}\n", "table.course.end_x_m = 1e+06"},
        {"table:\n  course: {width_m: 1e6}\n", "table.course.width_m = 1e+06"},
        {"table:\n  speed_m_s: 1e-6\n", "table.speed_m_s = 1e-06"},
        {"vehicle:\n  end_x_m: 1e6\n", "vehicle.end_x_m = 1e+06"},
        {"vehicle:\n  speed_m_s: 1e-6\n", "vehicle.speed_m_s = 1e-06"},
    };
    for (const auto& c : cases) {
        const fs::path path = Write("rig", "rig.yaml", c.yaml);
        const std::string message = ErrorOf([&] { (void)LoadRigConfig(path.string()); });
        EXPECT_THAT(message, HasSubstr("rig.yaml:")) << c.yaml;
        EXPECT_THAT(message, HasSubstr(c.expected)) << c.yaml;
    }
}

}  // namespace
}  // namespace casmap::io
