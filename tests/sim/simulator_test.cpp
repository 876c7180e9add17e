#include "casmap/sim/simulator.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <numbers>
#include <optional>
#include <string>
#include <vector>

#include "casmap/core/input_error.hpp"
#include "casmap/core/pose.hpp"
#include "casmap/core/scene.hpp"

namespace casmap::sim {
namespace {

constexpr double kDeg = std::numbers::pi / 180.0;

core::SceneObject Box(const std::string& name,
                      const Eigen::Vector3d& size,
                      const Eigen::Vector3d& centre,
                      double reflectivity = 0.5,
                      const Eigen::Vector3d& rpy_rad = Eigen::Vector3d::Zero()) {
    core::SceneObject o;
    o.name = name;
    o.shape = core::BoxShape{size};
    o.world_T_object = core::PoseFromXyzRpy(centre, rpy_rad);
    o.reflectivity = reflectivity;
    return o;
}

sensor_models::Lms200Model IdealModel() {
    sensor_models::Lms200Config c;
    c.ideal = true;
    return sensor_models::Lms200Model{c};
}

// World direction of beam i for a sensor with orientation q.
Eigen::Vector3d BeamDirection(const sensor_models::Lms200Model& m,
                              const Eigen::Quaterniond& q,
                              std::size_t i) {
    const double phi = m.BeamAngleRad(i);
    return q * Eigen::Vector3d(std::cos(phi), std::sin(phi), 0.0);
}

TEST(Simulator, IdealRangesToATiltedFloorMatchTheClosedForm) {
    core::Scene scene;
    scene.objects.push_back(Box("floor", {200.0, 200.0, 0.02}, {0.0, 0.0, -0.01}));
    const World world(scene);
    const auto model = IdealModel();
    const double h = 0.8;
    int checked = 0;
    for (const double pitch_deg : {10.0, 25.0, 40.0, 70.0}) {
        for (const double roll_deg : {-15.0, 0.0, 12.0}) {
            const core::Pose pose = core::PoseFromXyzRpy(
                {0.3, -0.2, h}, {roll_deg * kDeg, pitch_deg * kDeg, 20.0 * kDeg});
            const ScanResult r = CastScanAt(world, model, pose, 0.0, 0);
            for (std::size_t i = 0; i < model.BeamCount(); ++i) {
                const Eigen::Vector3d d = BeamDirection(model, pose.rotation, i);
                const double expected = d.z() < -1e-3 ? h / -d.z() : INFINITY;
                if (expected > 60.0) {
                    continue;  // grazing rays may leave the 200 m floor
                }
                ASSERT_EQ(r.scan.beams[i].status, core::BeamStatus::kOk) << i;
                EXPECT_NEAR(r.scan.beams[i].range_m, expected, 1e-3)
                    << "pitch " << pitch_deg << " roll " << roll_deg << " beam " << i;
                ++checked;
            }
        }
    }
    EXPECT_GT(checked, 1000);
}

TEST(Simulator, IdealRangesToBoxFacesAndACylinder) {
    core::Scene scene;
    scene.objects.push_back(Box("wall", {1.0, 4.0, 2.0}, {3.0, 0.0, 0.0}));  // face at x = 2.5
    core::SceneObject cyl;
    cyl.name = "cylinder";
    cyl.shape = core::CylinderShape{0.4, 2.0};
    cyl.world_T_object = core::PoseFromXyzRpy({-2.0, 1.5, 0.0}, Eigen::Vector3d::Zero());
    scene.objects.push_back(cyl);
    const World world(scene);
    const auto model = IdealModel();
    // Sensor at the origin looking along +x; also rotated by 180 deg in yaw to see the cylinder.
    const ScanResult front = CastScanAt(world, model, core::Pose{}, 0.0, 0);
    int checked = 0;
    for (std::size_t i = 0; i < model.BeamCount(); ++i) {
        const double phi = model.BeamAngleRad(i);
        if (std::abs(2.5 * std::tan(phi)) < 1.95 && std::cos(phi) > 0.0) {
            EXPECT_NEAR(front.scan.beams[i].range_m, 2.5 / std::cos(phi), 1e-3) << i;
            ++checked;
        }
    }
    const core::Pose back =
        core::PoseFromXyzRpy(Eigen::Vector3d::Zero(), {0.0, 0.0, std::numbers::pi});
    const ScanResult rear = CastScanAt(world, model, back, 0.0, 0);
    const Eigen::Vector2d c(-2.0, 1.5);
    for (std::size_t i = 0; i < model.BeamCount(); ++i) {
        const Eigen::Vector3d d3 = BeamDirection(model, back.rotation, i);
        const Eigen::Vector2d d(d3.x(), d3.y());
        // |t d - c|^2 = R^2 -> t^2 - 2 t d.c + |c|^2 - R^2 = 0
        const double b = d.dot(c);
        const double disc = b * b - (c.squaredNorm() - 0.4 * 0.4);
        if (disc > 1e-4) {
            EXPECT_NEAR(rear.scan.beams[i].range_m, b - std::sqrt(disc), 1e-3) << i;
            ++checked;
        }
    }
    EXPECT_GT(checked, 60);
}

TEST(Simulator, EveryPulseUsesThePoseOfItsOwnTime) {
    core::Scene scene;
    scene.objects.push_back(Box("wall", {0.2, 40.0, 4.0}, {6.1, 0.0, 0.0}));  // face at x = 6
    const World world(scene);
    const auto model = IdealModel();
    const double v = 20.0;  // m/s along +x, so a half-turn sweep moves 0.13 m
    core::Trajectory traj({core::TimedPose{0.0, core::Pose{}},
                           core::TimedPose{1.0, core::Pose{{v, 0.0, 0.0}, {1, 0, 0, 0}}}});
    const ScanResult r = CastScan(world, model, traj, 0.1, 0);
    for (std::size_t i = 45; i <= 135; ++i) {
        const double x = v * r.scan.BeamTime(i);
        EXPECT_NEAR(r.scan.beams[i].range_m, (6.0 - x) / std::cos(model.BeamAngleRad(i)), 1e-3)
            << i;
    }
    EXPECT_THROW((void)CastScan(world, model, traj, 0.999, 1), InputError);
}

TEST(Simulator, QuarterDegreeBeamsComeFromFourInterleavedTurns) {
    core::Scene scene;
    scene.objects.push_back(Box("wall", {0.2, 40.0, 4.0}, {6.1, 0.0, 0.0}));  // face at x = 6
    const World world(scene);
    sensor_models::Lms200Config c;
    c.ideal = true;
    c.angular_resolution_deg = 0.25;
    c.field_of_view_deg = 100.0;
    const sensor_models::Lms200Model model{c};
    const double v = 10.0;
    core::Trajectory traj({core::TimedPose{0.0, core::Pose{}},
                           core::TimedPose{1.0, core::Pose{{v, 0.0, 0.0}, {1, 0, 0, 0}}}});
    const ScanResult r = CastScan(world, model, traj, 0.2, 0);
    ASSERT_EQ(r.scan.beams.size(), 401U);
    for (std::size_t i = 0; i < 401; ++i) {
        const double x = v * r.scan.BeamTime(i);
        EXPECT_NEAR(r.scan.beams[i].range_m, (6.0 - x) / std::cos(model.BeamAngleRad(i)), 1e-3)
            << i;
    }
    // Neighbouring beams are one mirror turn (13.3 ms, 0.133 m of travel) apart.
    EXPECT_NEAR(r.scan.beams[200].range_m - r.scan.beams[201].range_m, v / 75.0, 2e-3);
}

// A foreground plate (x = 2, y < 0) before a background wall at x = 2 + gap.
World EdgeWorld(double gap_m) {
    core::Scene scene;
    scene.objects.push_back(Box("plate", {0.02, 3.0, 2.0}, {2.01, -1.5, 0.0}));
    scene.objects.push_back(Box("wall", {0.2, 20.0, 4.0}, {2.1 + gap_m, 0.0, 0.0}));
    return World(scene);
}

struct EdgeCount {
    int mixed = 0;
    int between = 0;
};

// 400 scans with the sensor yawed in steps of 0.005 deg so the edge crosses the beam near 0 deg.
EdgeCount CountMixed(double gap_m) {
    const World world = EdgeWorld(gap_m);
    const sensor_models::Lms200Model model{sensor_models::Lms200Config{}, 99};
    EdgeCount count;
    for (int k = 0; k < 400; ++k) {
        const double yaw = (-1.0 + 0.005 * k) * kDeg;
        const core::Pose pose = core::PoseFromXyzRpy(Eigen::Vector3d::Zero(), {0.0, 0.0, yaw});
        const ScanResult r = CastScanAt(world, model, pose, 0.0, static_cast<std::uint64_t>(k));
        for (std::size_t i = 85; i <= 95; ++i) {
            if (r.truth.labels[i] != core::BeamLabel::kMixed) {
                continue;
            }
            ++count.mixed;
            const double c = std::cos(model.BeamAngleRad(i) + yaw);
            const double range = r.scan.beams[i].range_m;
            count.between += range > 2.0 / c - 0.03 && range < (2.0 + gap_m) / c + 0.03;
        }
    }
    return count;
}

TEST(Simulator, DepthEdgeGivesMixedPixelsBetweenTheSurfaces) {
    const EdgeCount close = CountMixed(0.5);
    EXPECT_GT(close.mixed, 50);
    EXPECT_EQ(close.between, close.mixed);
    const EdgeCount far = CountMixed(3.0);
    std::printf("mixed 0.5: %d 3.0: %d\n", close.mixed, far.mixed);
    EXPECT_LE(far.mixed, close.mixed / 20) << "mixed at 3 m: " << far.mixed;
}

TEST(Simulator, SameSeedSameScansAtAnyThreadCount) {
    const World world = EdgeWorld(0.5);
    const sensor_models::Lms200Model a{sensor_models::Lms200Config{}, 5};
    const sensor_models::Lms200Model b{sensor_models::Lms200Config{}, 6};
    core::Trajectory traj(
        {core::TimedPose{0.0, core::Pose{}},
         core::TimedPose{1.0, core::PoseFromXyzRpy({0.2, 0.0, 0.0}, {0.0, 0.0, 0.3})}});
    SimulateOptions opt;
    opt.scan_count = 20;
    opt.threads = 1;
    const auto one = Simulate(world, a, traj, opt);
    opt.threads = 2;
    const auto two = Simulate(world, a, traj, opt);
    const auto other = Simulate(world, b, traj, opt);
    int differ = 0;
    for (std::size_t k = 0; k < one.size(); ++k) {
        for (std::size_t i = 0; i < one[k].scan.beams.size(); ++i) {
            ASSERT_EQ(one[k].scan.beams[i].raw, two[k].scan.beams[i].raw);
            ASSERT_EQ(one[k].truth.labels[i], two[k].truth.labels[i]);
            differ += one[k].scan.beams[i].raw != other[k].scan.beams[i].raw;
        }
    }
    EXPECT_GT(differ, 500);  // another seed, other noise
}

TEST(Simulator, ClosedFormPathMatchesTheWaveformOnATiltedFloor) {
    // A grazing floor and box edges: compact footprints take the closed form under kAuto.
    core::Scene scene;
    scene.objects.push_back(Box("floor", {40.0, 40.0, 0.02}, {0.0, 0.0, -0.01}, 0.3));
    scene.objects.push_back(Box("box", {0.5, 0.5, 0.4}, {2.0, 0.3, 0.2}, 0.6));
    const World world(scene);
    sensor_models::Lms200Config exact;
    exact.return_algorithm = sensor_models::ReturnAlgorithm::kWaveform;
    const sensor_models::Lms200Model reference{exact, 4};
    const sensor_models::Lms200Model fast{sensor_models::Lms200Config{}, 4};
    const core::Pose pose = core::PoseFromXyzRpy({0.0, 0.0, 1.0}, {0.0, 35.0 * kDeg, 0.0});
    int same = 0;
    int total = 0;
    for (std::uint64_t k = 0; k < 10; ++k) {
        const ScanResult a = CastScanAt(world, reference, pose, 0.0, k);
        const ScanResult b = CastScanAt(world, fast, pose, 0.0, k);
        for (std::size_t i = 0; i < a.scan.beams.size(); ++i) {
            ASSERT_EQ(a.scan.beams[i].status, b.scan.beams[i].status) << k << " " << i;
            ASSERT_EQ(a.truth.labels[i], b.truth.labels[i]) << k << " " << i;
            EXPECT_LE(std::abs(int{a.scan.beams[i].raw} - int{b.scan.beams[i].raw}), 1);
            same += a.scan.beams[i].raw == b.scan.beams[i].raw;
            ++total;
        }
    }
    EXPECT_GT(same, total * 95 / 100);  // centroids agree to < 0.25 mm, so 1 mm steps rarely flip
}

TEST(Simulator, TargetBeyondTheEightMetreModeGives8183) {
    core::Scene scene;
    scene.objects.push_back(Box("wall", {0.2, 4.0, 4.0}, {9.1, 0.0, 0.0}, 0.9));
    const World world(scene);
    const sensor_models::Lms200Model model{sensor_models::Lms200Config{}, 1};
    int beyond = 0;
    for (std::uint64_t k = 0; k < 20; ++k) {
        const ScanResult r = CastScanAt(world, model, core::Pose{}, 0.0, k);
        beyond += r.scan.beams[90].raw == 8183;
        EXPECT_NE(r.truth.labels[90], core::BeamLabel::kValid);
    }
    EXPECT_GE(beyond, 18);
}

TEST(Simulator, SixteenMetreModeWrapsAt17Metres) {
    core::Scene scene;
    scene.objects.push_back(Box("wall", {0.2, 8.0, 4.0}, {17.1, 0.0, 0.0}, 0.9));
    const World world(scene);
    sensor_models::Lms200Config c;
    c.format.mode = core::RangeMode::k16m;
    const sensor_models::Lms200Model model{c, 1};
    int wrapped = 0;
    for (std::uint64_t k = 0; k < 40; ++k) {
        const ScanResult r = CastScanAt(world, model, core::Pose{}, 0.0, k);
        const core::Beam& b = r.scan.beams[90];
        if (b.status == core::BeamStatus::kOk) {
            EXPECT_NEAR(b.range_m, 0.616, 0.04);
            EXPECT_EQ(r.truth.labels[90], core::BeamLabel::kSpike);
            ++wrapped;
        }
    }
    EXPECT_GE(wrapped, 30);
}

// A retro-reflective wall at 2 m (inside the 3.16 m saturation range of a new reflector)
// dazzles the beams that see it; the same wall as white paint, or the reflector at 5 m, ranges.
TEST(Simulator, RetroReflectiveWallDazzlesWhenClose) {
    const sensor_models::Lms200Model model{sensor_models::Lms200Config{}, 1};
    for (const double x : {2.0, 5.0}) {
        for (const bool retro : {true, false}) {
            core::Scene scene;
            core::SceneObject wall = Box("wall", {0.2, 1.0, 1.0}, {x + 0.1, 0.0, 0.0}, 1.0);
            wall.retro_reflective = retro;
            scene.objects.push_back(wall);
            const World world(scene);
            int dazzled = 0;
            int ranged = 0;
            for (std::uint64_t k = 0; k < 20; ++k) {
                const ScanResult r = CastScanAt(world, model, core::Pose{}, 0.0, k);
                const core::Beam& b = r.scan.beams[90];
                if (b.raw == 8190) {
                    EXPECT_EQ(b.status, core::BeamStatus::kDazzle);
                    EXPECT_EQ(r.truth.labels[90], core::BeamLabel::kDazzled);
                    ++dazzled;
                } else if (b.status == core::BeamStatus::kOk &&
                           r.truth.labels[90] == core::BeamLabel::kValid) {
                    EXPECT_NEAR(b.range_m, x, 0.04);
                    ++ranged;
                }
            }
            const bool expect_dazzle = retro && x < 3.0;
            EXPECT_GE(expect_dazzle ? dazzled : ranged, 19) << "x " << x << " retro " << retro;
            EXPECT_EQ(expect_dazzle ? ranged : dazzled, 0) << "x " << x << " retro " << retro;
        }
    }
}

TEST(Simulator, NoNoiseOnNoReturnBeams) {
    const World world{core::Scene{}};
    const sensor_models::Lms200Model model{sensor_models::Lms200Config{}, 3};
    for (std::uint64_t k = 0; k < 20; ++k) {
        const ScanResult r = CastScanAt(world, model, core::Pose{}, 0.0, k);
        for (std::size_t i = 0; i < r.scan.beams.size(); ++i) {
            if (r.truth.labels[i] == core::BeamLabel::kSpike) {
                continue;
            }
            EXPECT_EQ(r.scan.beams[i].raw, 8191);
            EXPECT_EQ(r.scan.beams[i].range_m, 0.0F);
            EXPECT_EQ(r.truth.labels[i], core::BeamLabel::kNoTarget);
        }
    }
}

}  // namespace
}  // namespace casmap::sim
