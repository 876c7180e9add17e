// The mapper's batch kernel: AVX2 lanes and the scalar remainder give the same bits, and the
// batch agrees with the scalar Eq. 1-4 functions of terrain_mapper.hpp.
#include "casmap/mapper/beam_batch.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <numbers>

#include "casmap/mapper/terrain_mapper.hpp"

namespace casmap::mapper {
namespace {

constexpr double kDeg = std::numbers::pi / 180.0;

core::Trajectory Rocking() {
    std::vector<core::TimedPose> samples;
    for (int n = 0; n <= 200; ++n) {
        const double t = n * 1e-3;
        samples.push_back({t, core::PoseFromXyzRpy(Eigen::Vector3d(t, 0.1 * t, 1.0 + 0.2 * t),
                                                   Eigen::Vector3d(15 * kDeg * std::sin(40 * t),
                                                                   (30 + 200 * t) * kDeg, 0.3))});
    }
    return core::Trajectory(samples);
}

core::Scan ScanAt(double stamp_s, std::size_t beams) {
    core::Scan s;
    s.stamp_s = stamp_s;
    s.start_angle_rad = -90 * kDeg;
    s.angle_step_rad = kDeg;
    s.beam_period_s = (1.0 / 75.0) / 360.0;
    for (std::size_t i = 0; i < beams; ++i) {
        s.beams.push_back(core::Beam{static_cast<float>(1.5 + 0.01 * static_cast<double>(i)),
                                     core::BeamStatus::kOk, 0});
    }
    return s;
}

TEST(BeamBatch, VectorLanesAndScalarRemainderGiveTheSameBits) {
    const core::Trajectory traj = Rocking();
    const core::Scan scan = ScanAt(0.05, 7);
    detail::BeamBatch b;
    BeamDirections dirs;
    dirs.Update(scan);
    ASSERT_EQ(detail::FillBatch(scan, traj, dirs, 1.0 / 75.0, {}, b).no_pose, 0U);
    // Entries 0-3 go through the 4-lane path (where the CPU has AVX2), 4-6 through the scalar
    // one: make entry 4 a copy of entry 0 and compare.
    for (std::vector<double>* v :
         {&b.qw, &b.qx, &b.qy, &b.qz, &b.q0w, &b.q0x, &b.q0y, &b.q0z, &b.ox, &b.oy, &b.oz, &b.dx,
          &b.dy, &b.dz, &b.cos_a, &b.sin_a, &b.range_m}) {
        (*v)[4] = (*v)[0];
    }
    detail::ComputeBatch(0.032, b);
    for (const std::vector<double>* v : {&b.x, &b.y, &b.z, &b.dz_max, &b.beam_z}) {
        EXPECT_EQ(std::memcmp(&(*v)[0], &(*v)[4], sizeof(double)), 0);
    }
}

TEST(BeamBatch, AgreesWithTheScalarEquations) {
    const core::Trajectory traj = Rocking();
    const core::Scan scan = ScanAt(0.08, 181);
    detail::BeamBatch b;
    BeamDirections dirs;
    dirs.Update(scan);
    (void)detail::FillBatch(scan, traj, dirs, 1.0 / 75.0, {}, b);
    ASSERT_EQ(b.size, 181U);
    detail::ComputeBatch(0.032, b);
    for (std::size_t i = 0; i < b.size; ++i) {
        const double t = scan.BeamTime(i);
        const core::Pose now = *traj.PoseAt(t);
        const core::Pose before = *traj.PoseAt(t - 1.0 / 75.0);
        SensorState s;
        s.world_R_sensor = now.rotation.normalized().toRotationMatrix();
        s.origin_m = now.translation;
        s.motion = MotionBetween(before, now);
        const double a = scan.BeamAngle(i);
        const double l = static_cast<double>(scan.beams[i].range_m);
        const Eigen::Vector3d p = BeamToWorld(now, a, l);
        EXPECT_NEAR(b.x[i], p.x(), 1e-6) << i;
        EXPECT_NEAR(b.y[i], p.y(), 1e-6) << i;
        EXPECT_NEAR(b.z[i], p.z(), 1e-6) << i;
        EXPECT_NEAR(b.dz_max[i], DeltaZMax(s, a, l, 0.032), 1e-6) << i;
        EXPECT_NEAR(b.beam_z[i], BeamZPartials(s.world_R_sensor, a, l).d_range, 1e-6) << i;
    }
}

}  // namespace
}  // namespace casmap::mapper
