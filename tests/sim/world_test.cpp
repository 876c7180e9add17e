#include "casmap/sim/world.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <numbers>
#include <optional>
#include <random>
#include <string>
#include <vector>

#include "casmap/core/input_error.hpp"
#include "casmap/core/pose.hpp"
#include "casmap/io/mesh_import.hpp"

namespace casmap::sim {
namespace {

constexpr double kTol = 1e-3;  // 1 mm, the bound for ideal ranges
constexpr double kDeg = std::numbers::pi / 180.0;
const std::string kMeshDir = std::string(CASMAP_SOURCE_DIR) + "/tests/data/meshes/";

core::Pose MakePose(
    double x, double y, double z, double roll_deg, double pitch_deg, double yaw_deg) {
    return core::PoseFromXyzRpy({x, y, z}, Eigen::Vector3d(roll_deg, pitch_deg, yaw_deg) * kDeg);
}

core::SceneObject Object(const std::string& name, core::Shape shape, const core::Pose& pose) {
    core::SceneObject o;
    o.name = name;
    o.shape = std::move(shape);
    o.world_T_object = pose;
    return o;
}

Ray RayTo(const Eigen::Vector3d& origin, const Eigen::Vector3d& target) {
    return Ray{origin.cast<float>(), (target - origin).normalized().cast<float>()};
}

// Closed form: distance along a unit ray to an oriented box (slab method in the box frame).
std::optional<double> BoxRange(const Ray& ray,
                               const core::Pose& pose,
                               const Eigen::Vector3d& size) {
    const Eigen::Vector3d o = pose.Inverse() * ray.origin.cast<double>();
    const Eigen::Vector3d d = pose.rotation.conjugate() * ray.direction.cast<double>();
    double t0 = 0.0;
    double t1 = 1e30;
    for (int i = 0; i < 3; ++i) {
        const double h = size[i] / 2;
        if (std::abs(d[i]) < 1e-15) {
            if (std::abs(o[i]) > h) {
                return std::nullopt;
            }
            continue;
        }
        double a = (-h - o[i]) / d[i];
        double b = (h - o[i]) / d[i];
        if (a > b) {
            std::swap(a, b);
        }
        t0 = std::max(t0, a);
        t1 = std::min(t1, b);
    }
    return t0 <= t1 ? std::optional<double>(t0) : std::nullopt;
}

// Closed form: distance to a finite cylinder (axis = pose z, centred), outside origin.
std::optional<double> CylinderRange(const Ray& ray, const core::Pose& pose, double r, double h) {
    const Eigen::Vector3d o = pose.Inverse() * ray.origin.cast<double>();
    const Eigen::Vector3d d = pose.rotation.conjugate() * ray.direction.cast<double>();
    std::optional<double> best;
    const auto keep = [&](double t) {
        if (t >= 0 && (!best || t < *best)) {
            best = t;
        }
    };
    const double a = d.x() * d.x() + d.y() * d.y();
    const double b = o.x() * d.x() + o.y() * d.y();
    const double c = o.x() * o.x() + o.y() * o.y() - r * r;
    if (a > 0 && b * b - a * c >= 0) {
        for (const double s : {-1.0, 1.0}) {
            const double t = (-b + s * std::sqrt(b * b - a * c)) / a;
            if (std::abs(o.z() + t * d.z()) <= h / 2) {
                keep(t);
            }
        }
    }
    for (const double z : {-h / 2, h / 2}) {
        if (d.z() != 0) {
            const double t = (z - o.z()) / d.z();
            const Eigen::Vector3d p = o + t * d;
            if (p.x() * p.x() + p.y() * p.y() <= r * r) {
                keep(t);
            }
        }
    }
    return best;
}

// Casts every ray singly and as one packet call; checks both against the expected ranges
// (nullopt = miss) and that every hit normal faces its ray.
void ExpectRanges(const World& world,
                  const std::vector<Ray>& rays,
                  const std::vector<std::optional<double>>& expected,
                  double tol = kTol) {
    ASSERT_EQ(rays.size(), expected.size());
    std::vector<Hit> packet(rays.size());
    world.CastPacket(rays, packet);
    for (std::size_t i = 0; i < rays.size(); ++i) {
        const Hit one = world.CastOne(rays[i]);
        for (const Hit& hit : {one, packet[i]}) {
            if (!expected[i]) {
                EXPECT_FALSE(hit.valid()) << "ray " << i << " hit at " << hit.distance_m;
                continue;
            }
            ASSERT_TRUE(hit.valid()) << "ray " << i << " expected " << *expected[i];
            EXPECT_NEAR(hit.distance_m, *expected[i], tol) << "ray " << i;
            EXPECT_NEAR(hit.normal.norm(), 1.0F, 1e-5F);
            EXPECT_LT(hit.normal.dot(rays[i].direction), 0.0F) << "ray " << i;
        }
    }
}

TEST(World, TiltedPlanesMatchClosedForm) {
    for (const double roll : {-20.0, 0.0, 15.0, 30.0}) {
        for (const double pitch : {-25.0, 0.0, 10.0, 40.0}) {
            const core::Pose pose = MakePose(1.0, 0.5, 0.0, roll, pitch, 0.0);
            core::Scene scene;
            scene.objects.push_back(Object("plane", core::BoxShape{{20.0, 20.0, 0.02}}, pose));
            const World world(scene);
            // Top face: point c + R (0, 0, 0.01), normal R z.
            const Eigen::Vector3d n = pose.rotation * Eigen::Vector3d::UnitZ();
            const Eigen::Vector3d p0 = pose * Eigen::Vector3d(0, 0, 0.01);
            const Eigen::Vector3d origin(0.0, 0.0, 3.0);
            ASSERT_GT(n.dot(origin - p0), 0.5);  // the origin sees the top face
            std::vector<Ray> rays;
            std::vector<std::optional<double>> expected;
            for (int k = 0; k < 9; ++k) {
                // Aim at points of the top face up to 3 m from its centre.
                const Eigen::Vector3d local(-3.0 + 0.75 * k, 2.5 - 0.6 * k, 0.01);
                rays.push_back(RayTo(origin, pose * local));
                const Eigen::Vector3d d = rays.back().direction.cast<double>();
                expected.push_back(n.dot(p0 - origin) / n.dot(d));
            }
            SCOPED_TRACE("roll " + std::to_string(roll) + " pitch " + std::to_string(pitch));
            ExpectRanges(world, rays, expected);
            const Hit hit = world.CastOne(rays[0]);
            EXPECT_NEAR(std::abs(hit.normal.cast<double>().dot(n)), 1.0, 1e-5);
        }
    }
}

TEST(World, BoxFacesMatchClosedForm) {
    const Eigen::Vector3d size(0.53, 0.559, 0.462);
    const core::Pose pose = MakePose(2.0, 0.3, 0.231, 0.0, 0.0, 30.0);
    core::Scene scene;
    scene.objects.push_back(Object("box", core::BoxShape{size}, pose));
    const World world(scene);
    std::vector<Ray> rays;
    std::vector<std::optional<double>> expected;
    // For each face: rays from 1.5 m outside along the face normal, aimed at points on the face.
    for (int axis = 0; axis < 3; ++axis) {
        for (const double sign : {-1.0, 1.0}) {
            Eigen::Vector3d n = Eigen::Vector3d::Zero();
            n[axis] = sign;
            for (const Eigen::Vector3d& offset :
                 {Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(0.1, -0.08, 0.05)}) {
                Eigen::Vector3d target = offset;
                target[axis] = sign * size[axis] / 2;
                const Eigen::Vector3d origin_obj =
                    target + 1.5 * n + Eigen::Vector3d(0.2, 0.1, 0.3);
                rays.push_back(RayTo(pose * origin_obj, pose * target));
                expected.push_back(BoxRange(rays.back(), pose, size));
                ASSERT_TRUE(expected.back().has_value());
            }
        }
    }
    rays.push_back(RayTo({0, 0, 0.2}, {0, 5, 0.2}));  // passes beside the box
    expected.push_back(std::nullopt);
    ExpectRanges(world, rays, expected);
    // Head-on at the -x face centre of an axis-aligned box: D - L/2.
    core::Scene aligned;
    aligned.objects.push_back(
        Object("box", core::BoxShape{size}, MakePose(2.0, 0.0, 0.231, 0, 0, 0)));
    ExpectRanges(World(aligned), {RayTo({0, 0, 0.2}, {1, 0, 0.2})}, {2.0 - 0.265});
}

TEST(World, VerticalCylinderMatchesClosedForm) {
    const double r = 0.2055;
    const double h = 0.459;
    core::Scene scene;
    scene.objects.push_back(
        Object("cyl", core::CylinderShape{r, h}, MakePose(3.0, 0.0, h / 2, 0, 0, 0)));
    scene.objects.push_back(
        Object("pole9", core::CylinderShape{0.00125, 0.914}, MakePose(3.0, 1.0, 0.457, 0, 0, 0)));
    const World world(scene);
    std::vector<Ray> rays;
    std::vector<std::optional<double>> expected;
    for (const double e : {0.0, 0.05, 0.1, 0.15, 0.2, 0.205, 0.21}) {  // lateral offset
        rays.push_back(
            Ray{Eigen::Vector3f(0.0F, static_cast<float>(e), 0.2F), Eigen::Vector3f::UnitX()});
        expected.push_back(e < r ? std::optional<double>(3.0 - std::sqrt(r * r - e * e))
                                 : std::nullopt);
    }
    // Straight down onto the cap: 1.0 - h.
    rays.push_back(Ray{Eigen::Vector3f(3.1F, 0.05F, 1.0F), -Eigen::Vector3f::UnitZ()});
    expected.push_back(1.0 - h);
    // The 2.5 mm pole, hit 1 mm off its axis and missed 1.5 mm off it.
    for (const double e : {0.0, 0.001, 0.0015}) {
        rays.push_back(Ray{Eigen::Vector3f(0.0F, static_cast<float>(1.0 + e), 0.5F),
                           Eigen::Vector3f::UnitX()});
        expected.push_back(e < 0.00125
                               ? std::optional<double>(3.0 - std::sqrt(0.00125 * 0.00125 - e * e))
                               : std::nullopt);
    }
    ExpectRanges(world, rays, expected);
    const Hit side = world.CastOne(rays[0]);
    EXPECT_NEAR(side.normal.x(), -1.0F, 1e-6F);
    EXPECT_EQ(side.object_id, 0U);
    EXPECT_EQ(world.CastOne(rays[8]).object_id, 1U);
}

TEST(World, TiltedCylinderMatchesClosedForm) {
    const core::Pose pose = MakePose(2.0, -0.5, 0.5, 35.0, -20.0, 10.0);
    core::Scene scene;
    scene.objects.push_back(Object("cyl", core::CylinderShape{0.15, 0.6}, pose));
    const World world(scene);
    std::mt19937 rng(12345);  // seed 12345
    std::uniform_real_distribution<double> u(-0.4, 0.4);
    std::vector<Ray> rays;
    std::vector<std::optional<double>> expected;
    int hits = 0;
    for (int i = 0; i < 200; ++i) {
        rays.push_back(
            RayTo({0.0, 0.0, 1.2}, pose.translation + Eigen::Vector3d(u(rng), u(rng), u(rng))));
        expected.push_back(CylinderRange(rays.back(), pose, 0.15, 0.6));
        hits += expected.back() ? 1 : 0;
    }
    EXPECT_GT(hits, 50);
    ExpectRanges(world, rays, expected);
}

// One mesh file loaded with scale 0.001 (mm -> m) and a rotated pose.
struct MeshCase {
    std::string file;
};

class MeshFormats : public ::testing::TestWithParam<std::string> {};

TEST_P(MeshFormats, PlaneMatchesClosedForm) {
    const core::Pose pose = MakePose(1.5, 0.0, 0.2, 12.0, -18.0, 25.0);
    core::Scene scene;
    scene.objects.push_back(Object(
        "plane", io::ImportMesh(kMeshDir + "plane." + GetParam(), Eigen::Vector3d::Constant(0.001)),
        pose));
    const World world(scene);
    const Eigen::Vector3d n = pose.rotation * Eigen::Vector3d::UnitZ();
    const Eigen::Vector3d origin(0.2, 0.1, 2.0);
    std::vector<Ray> rays;
    std::vector<std::optional<double>> expected;
    for (const Eigen::Vector3d& local :
         {Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(0.5, -0.7, 0), Eigen::Vector3d(-0.9, 0.9, 0)}) {
        rays.push_back(RayTo(origin, pose * local));
        const Eigen::Vector3d d = rays.back().direction.cast<double>();
        expected.push_back(n.dot(pose.translation - origin) / n.dot(d));
    }
    rays.push_back(RayTo(origin, pose * Eigen::Vector3d(1.2, 0, 0)));  // beyond the 2 m square
    expected.push_back(std::nullopt);
    ExpectRanges(World(scene), rays, expected);
}

TEST_P(MeshFormats, BoxMatchesClosedForm) {
    const core::Pose pose = MakePose(2.0, 0.4, 0.3, 20.0, 0.0, -35.0);
    const Eigen::Vector3d size(0.4, 0.3, 0.2);
    core::Scene scene;
    scene.objects.push_back(Object(
        "box", io::ImportMesh(kMeshDir + "box." + GetParam(), Eigen::Vector3d::Constant(0.001)),
        pose));
    const World world(scene);
    std::mt19937 rng(777);  // seed 777
    std::uniform_real_distribution<double> u(-0.25, 0.25);
    std::vector<Ray> rays;
    std::vector<std::optional<double>> expected;
    for (int i = 0; i < 100; ++i) {
        rays.push_back(
            RayTo({0.0, 0.0, 1.0}, pose.translation + Eigen::Vector3d(u(rng), u(rng), u(rng))));
        expected.push_back(BoxRange(rays.back(), pose, size));
    }
    ExpectRanges(world, rays, expected);
}

TEST_P(MeshFormats, CylinderMatchesClosedForm) {
    // 96 segments of radius 200 mm: sagitta 0.107 mm, inside the 1 mm bound.
    for (const core::Pose& pose :
         {MakePose(3.0, 0.0, 0.25, 0, 0, 17.0), MakePose(3.0, 0.2, 0.4, 30.0, 15.0, 0.0)}) {
        core::Scene scene;
        scene.objects.push_back(Object(
            "cyl",
            io::ImportMesh(kMeshDir + "cylinder." + GetParam(), Eigen::Vector3d::Constant(0.001)),
            pose));
        const World world(scene);
        std::vector<Ray> rays;
        std::vector<std::optional<double>> expected;
        for (int i = 0; i < 41; ++i) {
            const double e = -0.195 + 0.39 * i / 40.0;
            rays.push_back(
                RayTo({0.0, e + pose.translation.y(), 0.3}, {1.0, e + pose.translation.y(), 0.3}));
            expected.push_back(CylinderRange(rays.back(), pose, 0.2, 0.5));
        }
        rays.push_back(RayTo({3.05, 0.0, 2.0}, {3.05, 0.0, 0.0}));  // onto the cap
        expected.push_back(CylinderRange(rays.back(), pose, 0.2, 0.5));
        ExpectRanges(world, rays, expected);
    }
}

INSTANTIATE_TEST_SUITE_P(StlObjPly, MeshFormats, ::testing::Values("stl", "obj", "ply"));

TEST(World, PacketAndSingleRaysAgree) {
    core::Scene scene;
    scene.objects.push_back(
        Object("floor", core::BoxShape{{12.0, 8.0, 0.02}}, MakePose(3, 0, -0.01, 0, 0, 0)));
    scene.objects.push_back(
        Object("box", core::BoxShape{{0.5, 0.5, 0.4}}, MakePose(2.5, 0.4, 0.2, 0, 0, 20)));
    scene.objects.push_back(
        Object("cyl", core::CylinderShape{0.2, 0.46}, MakePose(4.0, -0.3, 0.23, 0, 0, 0)));
    scene.objects.push_back(
        Object("pole", core::CylinderShape{0.005, 0.914}, MakePose(3.0, 0.0, 0.457, 0, 0, 0)));
    scene.objects.push_back(
        Object("mesh", io::ImportMesh(kMeshDir + "cylinder.obj", Eigen::Vector3d::Constant(0.001)),
               MakePose(2.0, -0.6, 0.25, 0, 0, 0)));
    const World world(scene);
    const unsigned seed = 2024;
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> az(-1.5F, 1.5F);
    std::uniform_real_distribution<float> el(0.05F, 0.8F);
    std::vector<Ray> rays;
    for (int i = 0; i < 1000; ++i) {
        const float a = az(rng);
        const float e = el(rng);
        rays.push_back(Ray{
            Eigen::Vector3f(0.0F, 0.0F, 0.8F),
            Eigen::Vector3f(std::cos(e) * std::cos(a), std::cos(e) * std::sin(a), -std::sin(e))});
    }
    for (int i = 0; i < 20; ++i) {  // aimed at the thin pole, across its width
        rays.push_back(RayTo({0.0, 0.0, 0.8}, {3.0, -0.0057 + 0.0006 * i, 0.3}));
    }
    rays.back().tmax_m = 0.5F;  // too short to reach anything
    // Packets of every width 1..37 exercise rtcIntersect4/8/16 and masked lanes.
    std::vector<Hit> packet(rays.size());
    std::size_t first = 0;
    for (std::size_t width = 1; first < rays.size(); width = width % 37 + 1) {
        const std::size_t n = std::min(width, rays.size() - first);
        world.CastPacket(std::span<const Ray>(rays).subspan(first, n),
                         std::span<Hit>(packet).subspan(first, n));
        first += n;
    }
    std::vector<int> per_object(scene.objects.size(), 0);
    for (std::size_t i = 0; i < rays.size(); ++i) {
        const Hit one = world.CastOne(rays[i]);
        ASSERT_EQ(one.valid(), packet[i].valid()) << "seed " << seed << " ray " << i;
        if (!one.valid()) {
            continue;
        }
        EXPECT_EQ(one.object_id, packet[i].object_id) << "seed " << seed << " ray " << i;
        EXPECT_NEAR(one.distance_m, packet[i].distance_m, 1e-5F) << "seed " << seed << " ray " << i;
        EXPECT_LT((one.normal - packet[i].normal).norm(), 1e-4F);
        ++per_object[one.object_id];
    }
    EXPECT_FALSE(world.CastOne(rays.back()).valid());
    for (std::size_t k = 0; k < per_object.size(); ++k) {
        EXPECT_GT(per_object[k], 0) << scene.objects[k].name << " never hit (seed " << seed << ")";
    }
    // The same rays as one batch (16-wide packets across the whole list, a partial last one)
    // and one by one through the batch interface.
    RayBatch batch;
    batch.Resize(rays.size() - 1);
    batch.tmax_m = rays.front().tmax_m;
    for (std::size_t i = 0; i + 1 < rays.size(); ++i) {
        batch.Set(i, rays[i].origin, rays[i].direction);
    }
    HitBatch packed;
    HitBatch single;
    world.CastBatch(batch, packed);
    world.CastBatchSingly(batch, single);
    ASSERT_EQ(packed.distance_m.size(), batch.size());
    for (std::size_t i = 0; i < batch.size(); ++i) {
        const Hit one = world.CastOne(rays[i]);
        ASSERT_EQ(one.valid(), packed.distance_m[i] < std::numeric_limits<float>::infinity())
            << "ray " << i;
        ASSERT_EQ(one.distance_m, single.distance_m[i]) << "ray " << i;
        if (!one.valid()) {
            continue;
        }
        EXPECT_EQ(one.object_id, packed.object_id[i]) << "ray " << i;
        EXPECT_EQ(one.object_id, single.object_id[i]) << "ray " << i;
        EXPECT_NEAR(one.distance_m, packed.distance_m[i], 1e-5F) << "ray " << i;
        const float cos_one = std::abs(one.normal.dot(rays[i].direction));
        EXPECT_EQ(cos_one, single.cos_incidence[i]) << "ray " << i;
        EXPECT_NEAR(cos_one, packed.cos_incidence[i], 1e-4F) << "ray " << i;
        EXPECT_EQ(one.reflectivity, packed.reflectivity[i]) << "ray " << i;
        EXPECT_EQ(one.reflectivity, single.reflectivity[i]) << "ray " << i;
    }
}

TEST(World, ReportsReflectivityObjectAndNormalFacingTheRay) {
    core::Scene scene;
    scene.objects.push_back(
        Object("floor", core::BoxShape{{4.0, 4.0, 0.02}}, MakePose(0, 0, -0.01, 0, 0, 0)));
    scene.objects.back().reflectivity = 0.3;
    scene.objects.push_back(
        Object("slab", core::BoxShape{{1.0, 1.0, 0.1}}, MakePose(0, 0, 1.0, 0, 0, 0)));
    scene.objects.back().reflectivity = 0.8;
    const World world(scene);
    // From between floor and slab, looking up: the slab's bottom face, normal pointing down.
    const Hit up = world.CastOne(Ray{Eigen::Vector3f(0, 0, 0.5F), Eigen::Vector3f::UnitZ()});
    ASSERT_TRUE(up.valid());
    EXPECT_NEAR(up.distance_m, 0.45F, 1e-6F);
    EXPECT_EQ(up.object_id, 1U);
    EXPECT_FLOAT_EQ(up.reflectivity, 0.8F);
    EXPECT_NEAR(up.normal.z(), -1.0F, 1e-6F);
    const Hit down = world.CastOne(Ray{Eigen::Vector3f(0, 0, 0.5F), -Eigen::Vector3f::UnitZ()});
    EXPECT_NEAR(down.distance_m, 0.5F, 1e-6F);
    EXPECT_EQ(down.object_id, 0U);
    EXPECT_FLOAT_EQ(down.reflectivity, 0.3F);
    EXPECT_NEAR(down.normal.z(), 1.0F, 1e-6F);
    // tmax_m limits the search; a miss is +inf.
    const Hit miss =
        world.CastOne(Ray{Eigen::Vector3f(0, 0, 0.5F), -Eigen::Vector3f::UnitZ(), 0.4F});
    EXPECT_FALSE(miss.valid());
    EXPECT_TRUE(std::isinf(miss.distance_m));
}

TEST(World, EmptySceneMissesEverything) {
    const World world(core::Scene{});
    EXPECT_FALSE(world.CastOne(Ray{}).valid());
}

TEST(World, RejectsShapesThatCannotBeBuilt) {
    core::Scene scene;
    scene.objects.push_back(Object("bad_box", core::BoxShape{{1.0, -1.0, 1.0}}, core::Pose{}));
    try {
        const World world(scene);
        FAIL() << "no InputError";
    } catch (const InputError& e) {
        EXPECT_NE(std::string(e.what()).find("bad_box"), std::string::npos) << e.what();
    }
    core::MeshShape mesh;
    mesh.vertices = {Eigen::Vector3f::Zero(), Eigen::Vector3f::UnitX(), Eigen::Vector3f::UnitY()};
    mesh.triangles = {Eigen::Vector3i(0, 1, 3)};
    scene.objects = {Object("bad_mesh", mesh, core::Pose{})};
    EXPECT_THROW(World{scene}, InputError);
    scene.objects = {Object("thin", core::CylinderShape{0.0, 1.0}, core::Pose{})};
    EXPECT_THROW(World{scene}, InputError);
}

}  // namespace
}  // namespace casmap::sim
