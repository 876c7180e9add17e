#include "casmap/drivers/pose_file.hpp"

#include <gtest/gtest.h>
#include <unistd.h>

#include <fstream>
#include <numbers>

#include "casmap/core/input_error.hpp"
#include "casmap/drivers/scan_list_source.hpp"
#include "test_source.hpp"

namespace casmap::drivers {
namespace {

std::string TempFile(const std::string& name, const std::string& text) {
    const std::string path = "/tmp/casmap_pose_test_" + std::to_string(getpid()) + "_" + name;
    std::ofstream(path) << text;
    return path;
}

std::string ErrorOf(const std::string& path) {
    try {
        (void)ReadPoseFile(path);
    } catch (const InputError& e) {
        return e.what();
    }
    return "no error";
}

TEST(PoseFile, WrittenPosesReadBackExactly) {
    std::vector<core::TimedPose> samples;
    for (int i = 0; i < 5; ++i) {
        core::TimedPose p;
        p.stamp_s = 0.1 * i + 1.0 / 3.0;
        p.world_T_sensor = core::PoseFromXyzRpy(Eigen::Vector3d(0.1 * i, -0.3, 1.0 / 7.0),
                                                Eigen::Vector3d(0.01 * i, 0.4, -0.2));
        samples.push_back(p);
    }
    const core::Trajectory t(samples);
    const std::string path = TempFile("ok.txt", PoseFileText(t, 1e9));
    const core::Trajectory back = ReadPoseFile(path);
    ASSERT_EQ(back.size(), t.size());
    for (std::size_t i = 0; i < t.size(); ++i) {
        EXPECT_NEAR(back.samples()[i].stamp_s, t.samples()[i].stamp_s + 1e9, 1e-6);
        EXPECT_EQ(back.samples()[i].world_T_sensor.translation,
                  t.samples()[i].world_T_sensor.translation);
        EXPECT_NEAR(back.samples()[i].world_T_sensor.rotation.angularDistance(
                        t.samples()[i].world_T_sensor.rotation),
                    0.0, 1e-12);
    }
    std::remove(path.c_str());
}

TEST(PoseFile, BadLinesNameFileLineAndRule) {
    const std::string cols = TempFile("cols.txt", "# c\n1 0 0 0 0 0 0 1\n2 0 0 0 0 0 1\n");
    EXPECT_NE(ErrorOf(cols).find(cols + ":3: columns = 7"), std::string::npos) << ErrorOf(cols);
    const std::string order = TempFile("order.txt", "2 0 0 0 0 0 0 1\n1 0 0 0 0 0 0 1\n");
    EXPECT_NE(ErrorOf(order).find(":2: stamp_s"), std::string::npos) << ErrorOf(order);
    const std::string quat = TempFile("quat.txt", "1 0 0 0 0 0 0 2\n");
    EXPECT_NE(ErrorOf(quat).find("quaternion norm"), std::string::npos) << ErrorOf(quat);
    const std::string nan = TempFile("nan.txt", "1 0 0 x 0 0 0 1\n");
    EXPECT_NE(ErrorOf(nan).find("column 4 = x"), std::string::npos) << ErrorOf(nan);
    const std::string empty = TempFile("empty.txt", "# nothing\n\n");
    EXPECT_NE(ErrorOf(empty).find("no poses"), std::string::npos) << ErrorOf(empty);
    EXPECT_NE(ErrorOf("/nonexistent/poses.txt").find("cannot be opened"), std::string::npos);
    for (const std::string& p : {cols, order, quat, nan, empty}) {
        std::remove(p.c_str());
    }
}

TEST(ScanListSource, ServesItsScansAndOnlyTheirVariant) {
    std::vector<core::Scan> scans;
    for (int i = 0; i < 3; ++i) {
        core::Scan s = testing::NumberedSource::Make(static_cast<std::uint64_t>(i), {180, 50});
        s.angle_step_rad = 0.5 * std::numbers::pi / 180.0;
        scans.push_back(s);
    }
    ScanListSource source(scans, "run.h5");
    EXPECT_EQ(source.variant(), (Variant{180, 50}));
    EXPECT_TRUE(source.Supports({180, 50}));
    EXPECT_FALSE(source.Supports({180, 100}));
    EXPECT_EQ(source.Sweep(2, {180, 50})->beams[0].raw, 2);
    EXPECT_FALSE(source.Sweep(3, {180, 50}).has_value());
    scans[1].beams.pop_back();
    EXPECT_THROW(ScanListSource(scans, "run.h5"), InputError);
    EXPECT_THROW(ScanListSource({}, "run.h5"), InputError);
}

}  // namespace
}  // namespace casmap::drivers
