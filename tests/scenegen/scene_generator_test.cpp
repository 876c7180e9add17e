#include "casmap/scenegen/scene_generator.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "casmap/core/input_error.hpp"
#include "casmap/scenegen/dataset_spec.hpp"
#include "casmap/scenegen/domain.hpp"
#include "casmap/scenegen/scene_writer.hpp"

namespace casmap::scenegen {
namespace {

double Radius(const GenObject& o) {
    switch (o.kind) {
        case ObjectKind::kDrum:
        case ObjectKind::kPole:
            return o.radius_m;
        case ObjectKind::kRock:
            return std::max(o.scale.x(), o.scale.y());
        default:
            return 0.5 * std::hypot(o.box_size_m.x(), o.box_size_m.y());
    }
}

TEST(SampleSeed, DependsOnlyOnDatasetSeedAndIndex) {
    EXPECT_EQ(SampleSeed(1, 5), SampleSeed(1, 5));
    EXPECT_NE(SampleSeed(1, 5), SampleSeed(1, 6));
    EXPECT_NE(SampleSeed(1, 5), SampleSeed(2, 5));
    EXPECT_NE(SampleSeed(0, 1), SampleSeed(1, 0));
}

TEST(Rng, UniformStaysInItsRangeAndPickHonoursZeroWeights) {
    Rng rng(3);
    const double weights[] = {0.0, 1.0, 0.0, 2.0};
    for (int i = 0; i < 2000; ++i) {
        const double u = rng.Draw({-2.0, 3.0});
        ASSERT_GE(u, -2.0);
        ASSERT_LE(u, 3.0);
        const std::size_t k = rng.Pick(weights, 4);
        ASSERT_TRUE(k == 1 || k == 3) << k;
        const int c = rng.Count({1.0, 3.0});
        ASSERT_GE(c, 1);
        ASSERT_LE(c, 3);
    }
}

TEST(GenerateScene, SameSeedSameSceneOtherSeedOtherScene) {
    const SceneGenConfig config;
    const std::vector<std::string> rocks = {"rock_01.ply", "rock_02.ply"};
    const std::string a = SceneYaml(GenerateScene(config, 42, 2), "g.ply", rocks, "");
    const std::string b = SceneYaml(GenerateScene(config, 42, 2), "g.ply", rocks, "");
    const std::string c = SceneYaml(GenerateScene(config, 43, 2), "g.ply", rocks, "");
    EXPECT_EQ(a, b);
    EXPECT_NE(a, c);
}

TEST(GenerateScene, ObjectsStayInsideTheRegionWithoutOverlapping) {
    SceneGenConfig config;
    config.clutter_per_m2 = {3.0, 3.0};  // crowded: placement must still hold
    for (std::uint64_t seed = 1; seed <= 20; ++seed) {
        const GeneratedScene s = GenerateScene(config, seed, 4);
        ASSERT_FALSE(s.objects.empty()) << "seed " << seed;
        for (std::size_t i = 0; i < s.objects.size(); ++i) {
            const GenObject& o = s.objects[i];
            const double r = Radius(o);
            ASSERT_GE(o.xyz_m.x() - r, config.region_min_xy_m.x() - 1e-12) << o.name;
            ASSERT_LE(o.xyz_m.x() + r, config.region_max_xy_m.x() + 1e-12) << o.name;
            ASSERT_GE(o.xyz_m.y() - r, config.region_min_xy_m.y() - 1e-12) << o.name;
            ASSERT_LE(o.xyz_m.y() + r, config.region_max_xy_m.y() + 1e-12) << o.name;
            for (std::size_t j = 0; j < i; ++j) {
                const GenObject& p = s.objects[j];
                ASSERT_GE((o.xyz_m.head<2>() - p.xyz_m.head<2>()).norm(),
                          r + Radius(p) + config.min_gap_m - 1e-12)
                    << "seed " << seed << ": " << o.name << " overlaps " << p.name;
            }
        }
    }
}

TEST(GenerateScene, PolesReachTheThinnestDiameterAndHolesGoBelowTheDatum) {
    SceneGenConfig config;
    config.terrain_probability = 0.0;
    config.kind_weights = {0, 0, 1, 0, 0, 0, 0};
    config.pole_diameter_m = {0.0025, 0.0025};
    config.holes = {2.0, 2.0};
    config.hole_depth_m = {0.2, 0.2};
    const GeneratedScene s = GenerateScene(config, 9, 0);
    ASSERT_FALSE(s.objects.empty());
    for (const GenObject& o : s.objects) {
        EXPECT_EQ(o.kind, ObjectKind::kPole);
        EXPECT_DOUBLE_EQ(2.0 * o.radius_m, 0.0025);
        EXPECT_NEAR(o.xyz_m.z() - 0.5 * o.height_m, 0.0, 1e-12) << "stands on the flat ground";
    }
    ASSERT_EQ(s.negatives.size(), 2U);
    for (const NegativeObstacle& n : s.negatives) {
        EXPECT_NEAR(s.ground.HeightAt(n.xy_m.x(), n.xy_m.y()), -0.2, 1e-6);
    }
}

TEST(Heightfield, LimitSlopeBoundsTheSteepestSlope) {
    Heightfield f = Heightfield::Flat({0.0, 0.0}, {4.0, 2.0}, 0.05);
    Rng rng(5);
    AddFractalNoise(f, 0.5, 0.5, 4, rng);
    ASSERT_GT(f.MaxSlopeDeg(), 20.0);
    LimitSlope(f, 20.0);
    EXPECT_LE(f.MaxSlopeDeg(), 20.0 + 1e-3);
    const core::MeshShape mesh = ToMesh(f);
    EXPECT_EQ(mesh.vertices.size(), f.z_m.size());
    EXPECT_EQ(mesh.triangles.size(), static_cast<std::size_t>(2 * (f.nx - 1) * (f.ny - 1)));
}

TEST(DrawDomain, RatesStayWithinTheTableLimits) {
    const DomainConfig config;
    Rng rng(11);
    for (int i = 0; i < 500; ++i) {
        const DomainDraw d = DrawDomain(config, rng);
        ASSERT_LE(2.0 * M_PI * d.roll_amplitude_deg / d.roll_period_s, 37.5 + 1e-9);
        ASSERT_LE(2.0 * M_PI * d.pitch_amplitude_deg / d.pitch_period_s, 37.5 + 1e-9);
        ASSERT_GE(d.pitch_center_deg - d.pitch_amplitude_deg, 25.0 - 1e-9);
        ASSERT_LE(d.pitch_center_deg + d.pitch_amplitude_deg, 40.0 + 1e-9);
        ASSERT_EQ(d.field_of_view_deg, d.angular_resolution_deg == 0.25 ? 100.0 : 180.0);
    }
}

TEST(GenerateScene, MaterialClassesIncludeRetroReflectors) {
    SceneGenConfig config;
    config.clutter_per_m2 = {2.0, 2.0};
    int objects = 0;
    int retro = 0;
    int dark = 0;
    for (std::uint64_t seed = 1; seed <= 40; ++seed) {
        const GeneratedScene scene = GenerateScene(config, seed, 2);
        for (const GenObject& o : scene.objects) {
            ++objects;
            if (o.retro_reflective) {
                ++retro;
                EXPECT_GE(o.reflectivity, config.retro_reflectivity.min);
                EXPECT_LE(o.reflectivity, config.retro_reflectivity.max);
            } else if (o.reflectivity < config.normal_reflectivity.min) {
                ++dark;
            }
        }
    }
    ASSERT_GT(objects, 400);
    // Binomial shares: p_retro = 0.03, p_dark = 0.15 (4 sigma bounds).
    const double n = objects;
    EXPECT_NEAR(retro / n, config.p_retro, 4.0 * std::sqrt(0.03 * 0.97 / n));
    EXPECT_NEAR(dark / n, config.p_dark, 4.0 * std::sqrt(0.15 * 0.85 / n));
    // Every object a retro-reflector: the scene file says so.
    config.p_dark = 0.0;
    config.p_bright = 0.0;
    config.p_retro = 1.0;
    const GeneratedScene all = GenerateScene(config, 5, 2);
    ASSERT_FALSE(all.objects.empty());
    const std::string yaml = SceneYaml(all, "g.ply", {"rock_01.ply", "rock_02.ply"}, "");
    std::size_t count = 0;
    for (std::size_t at = yaml.find("retro_reflective: true"); at != std::string::npos;
         at = yaml.find("retro_reflective: true", at + 1)) {
        ++count;
    }
    EXPECT_EQ(count, all.objects.size());
    // Shares beyond 1 are rejected naming the field.
    config.p_dark = 0.5;
    try {
        config.Validate("spec.yaml");
        FAIL() << "accepted p_dark + p_bright + p_retro = 1.5";
    } catch (const InputError& e) {
        EXPECT_NE(std::string(e.what()).find("p_dark"), std::string::npos) << e.what();
        EXPECT_NE(std::string(e.what()).find("p_retro"), std::string::npos) << e.what();
    }
}

TEST(DatasetSpec, DefaultsAreValid) { EXPECT_NO_THROW(DatasetSpec{}.Validate("spec.yaml")); }

TEST(DatasetSpec, RejectsARangeOutsideItsBoundsNamingTheField) {
    DatasetSpec spec;
    spec.scene.pole_diameter_m = {0.001, 0.01};
    try {
        spec.Validate("spec.yaml");
        FAIL() << "accepted a 1 mm pole";
    } catch (const InputError& e) {
        EXPECT_NE(std::string(e.what()).find("spec.yaml"), std::string::npos) << e.what();
        EXPECT_NE(std::string(e.what()).find("scene.pole_diameter_m"), std::string::npos)
            << e.what();
    }
    spec = DatasetSpec{};
    spec.domain.angular_resolutions_deg = {0.3};
    EXPECT_THROW(spec.Validate("spec.yaml"), InputError);
    spec = DatasetSpec{};
    spec.train_fraction = 0.95;
    EXPECT_THROW(spec.Validate("spec.yaml"), InputError);
}

TEST(SplitOf, FollowsTheFractions) {
    DatasetSpec spec;
    int train = 0;
    for (std::uint64_t i = 0; i < 4000; ++i) {
        train += std::string(SplitOf(spec, SampleSeed(1, i))) == "train" ? 1 : 0;
    }
    EXPECT_NEAR(train / 4000.0, 0.8, 0.03);
}

}  // namespace
}  // namespace casmap::scenegen
