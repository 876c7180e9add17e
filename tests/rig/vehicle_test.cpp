#include "casmap/rig/vehicle.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "casmap/core/input_error.hpp"
#include "casmap/io/scene_file.hpp"

namespace casmap::rig {
namespace {

constexpr double kDeg = std::numbers::pi / 180.0;

/// A height-field mesh on x in [-2, 6], y in [-1.5, 1.5] (5 cm grid), z = height(x, y).
template <typename Height>
core::SceneObject HeightField(Height height) {
    core::MeshShape mesh;
    mesh.source_path = "test height field";
    const int nx = 160;
    const int ny = 60;
    for (int i = 0; i <= nx; ++i) {
        for (int j = 0; j <= ny; ++j) {
            const double x = -2.0 + 0.05 * i;
            const double y = -1.5 + 0.05 * j;
            mesh.vertices.emplace_back(static_cast<float>(x), static_cast<float>(y),
                                       static_cast<float>(height(x, y)));
        }
    }
    const auto id = [&](int i, int j) { return i * (ny + 1) + j; };
    for (int i = 0; i < nx; ++i) {
        for (int j = 0; j < ny; ++j) {
            mesh.triangles.emplace_back(id(i, j), id(i + 1, j), id(i + 1, j + 1));
            mesh.triangles.emplace_back(id(i, j), id(i + 1, j + 1), id(i, j + 1));
        }
    }
    core::SceneObject object;
    object.name = "ground";
    object.shape = mesh;
    object.terrain = true;
    return object;
}

core::Scene RoughScene() {
    core::Scene scene;
    scene.source_path = "rough.yaml";
    scene.objects.push_back(HeightField([](double x, double y) {
        return 0.03 * std::sin(2.0 * std::numbers::pi * x / 0.8) *
                   std::cos(2.0 * std::numbers::pi * (y + 0.2) / 1.3) +
               0.02 * std::sin(2.0 * std::numbers::pi * x / 1.9 + 0.5);
    }));
    return scene;
}

core::Scene FlatBoxScene() {
    core::Scene scene;
    scene.source_path = "flat.yaml";
    core::SceneObject floor;
    floor.name = "floor";
    floor.shape = core::BoxShape{Eigen::Vector3d(10.0, 4.0, 0.1)};
    floor.world_T_object.translation = Eigen::Vector3d(2.0, 0.0, -0.05);
    floor.terrain = true;
    scene.objects.push_back(floor);
    return scene;
}

VehicleConfig ShortDrive() {
    VehicleConfig config;
    config.start_xy_m = Eigen::Vector2d(0.0, 0.0);
    config.end_x_m = 2.5;
    config.speed_ramp_s = 0.5;
    return config;
}

struct Spread {
    double z_m = 0.0;
    double roll_rad = 0.0;
    double pitch_rad = 0.0;
};

/// Standard deviation of height, roll and pitch of the scanner from `from_s` on.
Spread PoseSpread(const core::Trajectory& trajectory, double from_s) {
    Eigen::Vector3d sum = Eigen::Vector3d::Zero();
    Eigen::Vector3d sum2 = Eigen::Vector3d::Zero();
    double n = 0.0;
    for (const core::TimedPose& s : trajectory.samples()) {
        if (s.stamp_s < from_s) {
            continue;
        }
        n += 1.0;
        const Eigen::Vector3d rpy = core::RpyFromQuaternion(s.world_T_sensor.rotation);
        const Eigen::Vector3d v(s.world_T_sensor.translation.z(), rpy.x(), rpy.y());
        sum += v;
        sum2 += v.cwiseProduct(v);
    }
    const Eigen::Vector3d var = sum2 / n - (sum / n).cwiseProduct(sum / n);
    return {std::sqrt(std::max(var.x(), 0.0)), std::sqrt(std::max(var.y(), 0.0)),
            std::sqrt(std::max(var.z(), 0.0))};
}

TEST(Vehicle, DefaultsAreValid) { EXPECT_NO_THROW(VehicleConfig{}.Validate()); }

TEST(Vehicle, DrivesFlatGroundAtTheSetSpeedWithTheScannerPitchedDown) {
    const VehicleConfig config = ShortDrive();
    const VehicleRun run = RunVehicle(FlatBoxScene(), config);
    const auto& samples = run.trajectory.samples();
    EXPECT_GE(samples.back().world_T_sensor.translation.x(), config.end_x_m);
    for (std::size_t i = 0; i < samples.size(); ++i) {
        ASSERT_EQ(run.wheels_in_contact[i], 4) << "t = " << samples[i].stamp_s;
        if (samples[i].stamp_s > 1.5) {
            ASSERT_NEAR(run.speed_m_s[i], config.speed_m_s, 0.03) << "t = " << samples[i].stamp_s;
        }
    }
    const Eigen::Vector3d rpy = core::RpyFromQuaternion(samples.back().world_T_sensor.rotation);
    EXPECT_NEAR(rpy.y(), 11.0 * kDeg, 0.5 * kDeg);
    EXPECT_NEAR(rpy.x(), 0.0, 0.2 * kDeg);
    EXPECT_NEAR(samples.back().world_T_sensor.translation.y(), 0.0, 0.02);
    // Steady after the ramp (squat and pitch while accelerating are real and allowed).
    const Spread spread = PoseSpread(run.trajectory, 1.0);
    EXPECT_LT(spread.z_m, 0.001);
    EXPECT_LT(spread.roll_rad, 0.05 * kDeg);
    EXPECT_LT(spread.pitch_rad, 0.05 * kDeg);
}

TEST(Vehicle, StaysOnRoughTerrainAndItsPoseVaries) {
    const VehicleConfig config = ShortDrive();
    const VehicleRun run = RunVehicle(RoughScene(), config);
    std::size_t all_four = 0;
    for (const int n : run.wheels_in_contact) {
        ASSERT_GE(n, 3);
        all_four += n == 4 ? 1 : 0;
    }
    EXPECT_GT(static_cast<double>(all_four),
              0.9 * static_cast<double>(run.wheels_in_contact.size()));
    EXPECT_GE(run.trajectory.samples().back().world_T_sensor.translation.x(), config.end_x_m);
    const Spread spread = PoseSpread(run.trajectory, 1.0);
    std::printf("rough: z %.4f m, roll %.3f deg, pitch %.3f deg\n", spread.z_m,
                spread.roll_rad / kDeg, spread.pitch_rad / kDeg);
    EXPECT_GT(spread.z_m, 0.005);
    EXPECT_GT(spread.roll_rad, 0.5 * kDeg);
    EXPECT_GT(spread.pitch_rad, 0.5 * kDeg);
}

TEST(Vehicle, SameConfigGivesIdenticalTrajectory) {
    VehicleConfig config = ShortDrive();
    config.end_x_m = 1.2;
    const core::Trajectory a = SimulateVehicle(RoughScene(), config);
    const core::Trajectory b = SimulateVehicle(RoughScene(), config);
    ASSERT_EQ(a.size(), b.size());
    for (std::size_t i = 0; i < a.size(); ++i) {
        ASSERT_EQ(a.samples()[i].world_T_sensor.translation,
                  b.samples()[i].world_T_sensor.translation);
        ASSERT_EQ(a.samples()[i].world_T_sensor.rotation.coeffs(),
                  b.samples()[i].world_T_sensor.rotation.coeffs());
    }
}

TEST(Vehicle, RejectsASceneWithoutTerrain) {
    core::Scene scene = FlatBoxScene();
    scene.objects[0].terrain = false;
    EXPECT_THAT(
        [&] { (void)SimulateVehicle(scene, ShortDrive()); },
        testing::ThrowsMessage<InputError>(testing::HasSubstr("flat.yaml: objects[].terrain")));
}

TEST(Vehicle, RejectsValuesBeyondTheLimitsNamingTheField) {
    VehicleConfig c = ShortDrive();
    c.speed_m_s = 5.0;
    EXPECT_THAT(
        [&] { c.Validate("v.yaml"); },
        testing::ThrowsMessage<InputError>(testing::HasSubstr("v.yaml: vehicle.speed_m_s = 5")));
    c = ShortDrive();
    c.mount_pitch_deg = 60.0;
    EXPECT_THAT(
        [&] { (void)SimulateVehicle(FlatBoxScene(), c); },
        testing::ThrowsMessage<InputError>(testing::HasSubstr("vehicle.mount_pitch_deg = 60")));
    c = ShortDrive();
    c.start_xy_m = Eigen::Vector2d(50.0, 0.0);
    c.end_x_m = 60.0;
    EXPECT_THAT([&] { (void)SimulateVehicle(FlatBoxScene(), c); },
                testing::ThrowsMessage<InputError>(testing::HasSubstr("vehicle.start_xy_m")));
}

}  // namespace
}  // namespace casmap::rig

namespace casmap::rig {
namespace {

TEST(Vehicle, DefaultsDriveTheOutdoorScene) {
    const core::Scene scene =
        io::LoadScene(std::string(CASMAP_SOURCE_DIR) + "/scenes/outdoor.yaml");
    const VehicleConfig config;
    const VehicleRun run = RunVehicle(scene, config);
    for (const int n : run.wheels_in_contact) {
        ASSERT_GE(n, 3);
    }
    const core::Pose& last = run.trajectory.samples().back().world_T_sensor;
    EXPECT_GE(last.translation.x(), config.end_x_m);
    EXPECT_NEAR(last.translation.y(), config.start_xy_m.y(), 0.1);
    const Spread spread = PoseSpread(run.trajectory, 1.0);
    std::printf(
        "outdoor: %zu poses over %.2f s; z %.4f m, roll %.3f deg, pitch %.3f deg, "
        "height %.3f m\n",
        run.trajectory.size(), run.trajectory.EndTime(), spread.z_m, spread.roll_rad / kDeg,
        spread.pitch_rad / kDeg, last.translation.z());
    EXPECT_GT(spread.pitch_rad, 0.1 * kDeg);
}

}  // namespace
}  // namespace casmap::rig
