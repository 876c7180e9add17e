// pipeline::ScanAt / MakeScanSensorConfig / ScanJson (what `casmap scan` and casmap.scan_at
// run): the sensor file with its overrides, the pose parser, one scan and its JSON.
#include "casmap/pipeline/scan_at.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>

#include "casmap/core/input_error.hpp"
#include "tests/input_error_of.hpp"
#include "tests/temp_dir.hpp"

namespace casmap::pipeline {
namespace {
namespace fs = std::filesystem;

fs::path WallScene() {
    const fs::path path =
        casmap::test::MakeTempDir("pipeline_scan_at") / "casmap_pipeline_scan_at.yaml";
    std::ofstream(path) << "objects:\n"
                           "  - name: wall\n"
                           "    box: {size_m: [1, 4, 2]}\n"
                           "    pose: {xyz_m: [3, 0, 0.5], rpy_deg: [0, 0, 0]}\n";
    return path;
}

using test::ErrorOf;

TEST(ScanSensorConfig, OverridesApplyOnlyWhenGiven) {
    const casmap::test::TempDir tmp("pipeline_scan_at");
    const fs::path file = tmp / "casmap_pipeline_scan_at_lms.yaml";
    std::ofstream(file) << "range_mode_m: 16\nrange_units: cm\n";
    ScanSensorOptions o;
    o.sensor = file.string();
    sensor_models::Lms200Config c = MakeScanSensorConfig(o);
    EXPECT_EQ(c.format.mode, core::RangeMode::k16m);
    EXPECT_EQ(c.format.units, core::RangeUnits::kCentimetre);
    o.range_mode_m = 32;
    o.units = "mm";
    o.ideal = true;
    c = MakeScanSensorConfig(o);
    EXPECT_EQ(c.format.mode, core::RangeMode::k32m);
    EXPECT_EQ(c.format.units, core::RangeUnits::kMillimetre);
    EXPECT_TRUE(c.ideal);
    EXPECT_EQ(MakeScanSensorConfig({}).format.mode, core::RangeMode::k8m);  // built-in default
}

TEST(ScanSensorConfig, BadOverridesNameTheirField) {
    EXPECT_EQ(ErrorOf([] {
                  (void)MakeScanSensorConfig({"", false, 12, {}});
              }),
              "range_mode_m = 12 (allowed: 8, 16, 32)");
    EXPECT_EQ(ErrorOf([] {
                  (void)MakeScanSensorConfig({"", false, {}, "km"});
              }),
              "units = km (allowed: mm, cm)");
}

TEST(ScanPose, SixNumbersInDegrees) {
    const core::Pose p = ParsePoseXyzRpyDeg("1,2,3,0,0,90");
    EXPECT_NEAR(p.translation.x(), 1.0, 1e-12);
    EXPECT_NEAR(p.translation.z(), 3.0, 1e-12);
    const Eigen::Vector3d x = p.rotation * Eigen::Vector3d::UnitX();
    EXPECT_NEAR(x.y(), 1.0, 1e-12);  // yaw 90 deg turns x into y
    EXPECT_EQ(ErrorOf([] { (void)ParsePoseXyzRpyDeg("1,2,3"); }),
              "pose = 1,2,3 (must be six numbers X,Y,Z,ROLL_DEG,PITCH_DEG,YAW_DEG)");
    EXPECT_EQ(ErrorOf([] {
                  (void)PoseFromXyzRpyDeg({1, 2}, "p");
              }),
              "p = 2 numbers (must be six numbers X,Y,Z,ROLL_DEG,PITCH_DEG,YAW_DEG)");
    EXPECT_EQ(ErrorOf([] {
                  (void)PoseFromXyzRpyDeg({1, 2, NAN, 0, 0, 0});
              }),
              "pose = 1,2,.nan,0,0,0 (must be six numbers X,Y,Z,ROLL_DEG,PITCH_DEG,YAW_DEG)");
}

TEST(ScanAt, IdealScanOfAWallAndItsJson) {
    ScanAtOptions o;
    o.scene = WallScene().string();
    o.world_T_sensor = ParsePoseXyzRpyDeg("0,0,0.5,0,0,0");
    o.sensor.ideal = true;
    const ScanAtResult r = ScanAt(o);
    ASSERT_EQ(r.scan.scan.beams.size(), 181U);
    const core::Beam& ahead = r.scan.scan.beams[90];  // 0 deg: the wall face at x = 2.5 m
    EXPECT_EQ(ahead.status, core::BeamStatus::kOk);
    EXPECT_NEAR(ahead.range_m, 2.5, 1e-3);
    const std::string json = ScanJson(r);
    EXPECT_EQ(json.rfind("{\n  \"angles_deg\": [-90, -89, ", 0), 0U) << json.substr(0, 80);
    EXPECT_NE(json.find("\"ranges_m\": [null, "), std::string::npos);
    EXPECT_NE(json.find(", 2.500000, "), std::string::npos);
    EXPECT_NE(json.find("\"labels\": [\"no_target\", "), std::string::npos);
    EXPECT_EQ(json.substr(json.size() - 4), "]\n}\n");
}

}  // namespace
}  // namespace casmap::pipeline
