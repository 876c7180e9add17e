#include "casmap/core/trajectory.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <numbers>
#include <random>
#include <vector>

#include "casmap/core/input_error.hpp"

namespace casmap::core {
namespace {

constexpr double kDeg = std::numbers::pi / 180.0;

TEST(Pose, RpyRoundTrip) {
    const Eigen::Vector3d rpy(10 * kDeg, 25 * kDeg, -40 * kDeg);
    const Eigen::Vector3d back = RpyFromQuaternion(QuaternionFromRpy(rpy.x(), rpy.y(), rpy.z()));
    EXPECT_NEAR(back.x(), rpy.x(), 1e-12);
    EXPECT_NEAR(back.y(), rpy.y(), 1e-12);
    EXPECT_NEAR(back.z(), rpy.z(), 1e-12);
}

TEST(Pose, PositivePitchIsNoseDown) {
    const Pose pose = PoseFromXyzRpy(Eigen::Vector3d::Zero(), Eigen::Vector3d(0, 30 * kDeg, 0));
    const Eigen::Vector3d forward = pose * Eigen::Vector3d::UnitX();
    EXPECT_NEAR(forward.z(), -std::sin(30 * kDeg), 1e-12);
    EXPECT_NEAR(forward.x(), std::cos(30 * kDeg), 1e-12);
}

TEST(Pose, InverseComposesToIdentity) {
    const Pose pose = PoseFromXyzRpy({1, 2, 3}, {0.1, 0.2, 0.3});
    const Pose id = pose * pose.Inverse();
    EXPECT_NEAR(id.translation.norm(), 0.0, 1e-12);
    EXPECT_NEAR(id.rotation.angularDistance(Eigen::Quaterniond::Identity()), 0.0, 1e-12);
}

TEST(Trajectory, InterpolatesLinearlyAndSlerps) {
    const Trajectory traj({{0.0, PoseFromXyzRpy({0, 0, 0}, {0, 0, 0})},
                           {1.0, PoseFromXyzRpy({2, 0, 1}, {0, 0, 90 * kDeg})}});
    const std::optional<Pose> mid = traj.PoseAt(0.25);
    ASSERT_TRUE(mid.has_value());
    EXPECT_NEAR(mid->translation.x(), 0.5, 1e-12);
    EXPECT_NEAR(mid->translation.z(), 0.25, 1e-12);
    EXPECT_NEAR(RpyFromQuaternion(mid->rotation).z(), 22.5 * kDeg, 1e-9);
}

TEST(Trajectory, NoPoseOutsideItsSpan) {
    const Trajectory traj({{0.0, Pose{}}, {1.0, Pose{}}});
    EXPECT_FALSE(traj.PoseAt(-0.001).has_value());
    EXPECT_FALSE(traj.PoseAt(1.001).has_value());
    EXPECT_TRUE(traj.PoseAt(1.0).has_value());
}

// The pose at t by a plain binary search (the definition PoseAt with a hint must reproduce).
Pose ReferencePoseAt(const std::vector<TimedPose>& s, double t) {
    const auto after = std::upper_bound(s.begin(), s.end(), t,
                                        [](double x, const TimedPose& p) { return x < p.stamp_s; });
    if (after == s.end()) {
        return s.back().world_T_sensor;
    }
    const TimedPose& a = *(after - 1);
    return Interpolate(a.world_T_sensor, after->world_T_sensor,
                       (t - a.stamp_s) / (after->stamp_s - a.stamp_s));
}

TEST(Trajectory, HintedLookupIsBitIdenticalToTheBinarySearch) {
    std::mt19937_64 rng(20261127);
    std::uniform_real_distribution<double> u(0.0, 1.0);
    std::vector<TimedPose> samples;
    double t = 0.0;
    for (int i = 0; i < 2000; ++i) {  // uneven stamps, turning poses
        samples.push_back(
            {t, PoseFromXyzRpy({u(rng), u(rng), u(rng)}, {u(rng), u(rng), 3.0 * u(rng)})});
        t += 1e-4 + 1e-3 * u(rng);
    }
    const Trajectory traj(samples);
    std::size_t hint = 0;
    double stamp = traj.StartTime();
    for (int k = 0; k < 20000; ++k) {
        const double r = u(rng);
        if (r < 0.6) {
            stamp += 1e-4 * u(rng);  // beams of a scan: small steps forward
        } else if (r < 0.8) {
            stamp += 0.05 * u(rng);  // a jump forward
        } else if (r < 0.9) {
            stamp -= 0.02 * u(rng);  // back (interleaved turns)
        } else if (r < 0.95) {
            stamp = samples[static_cast<std::size_t>(u(rng) * 1999.0)].stamp_s;  // on a sample
        } else {
            hint = static_cast<std::size_t>(u(rng) * 2100.0);  // any hint is safe
        }
        stamp = std::clamp(stamp, traj.StartTime(), traj.EndTime());
        if (k % 997 == 0) {
            stamp = traj.EndTime();
        }
        const std::optional<Pose> got = traj.PoseAt(stamp, hint);
        ASSERT_TRUE(got.has_value());
        const Pose want = ReferencePoseAt(samples, stamp);
        ASSERT_EQ(got->translation, want.translation) << "stamp " << stamp;
        ASSERT_EQ(got->rotation.coeffs(), want.rotation.coeffs()) << "stamp " << stamp;
        ASSERT_EQ(traj.PoseAt(stamp)->translation, want.translation);
    }
    EXPECT_FALSE(traj.PoseAt(traj.EndTime() + 1e-9, hint).has_value());
    EXPECT_FALSE(traj.PoseAt(-1e-9, hint).has_value());
}

// Bit patterns of a pose, so -0 and +0 (or two NaNs) are told apart.
std::vector<std::uint64_t> Bits(const Pose& p) {
    std::vector<std::uint64_t> bits;
    for (const double v : {p.translation.x(), p.translation.y(), p.translation.z(), p.rotation.x(),
                           p.rotation.y(), p.rotation.z(), p.rotation.w()}) {
        bits.push_back(std::bit_cast<std::uint64_t>(v));
    }
    return bits;
}

// The cursor look-up takes the sines of small angles from a polynomial (within ~1 ulp of
// std::sin) where Eigen's slerp calls std::sin: the translation is bit-identical, the
// quaternion within a few ulp (|q| = 1, so 4e-16 absolute).
TEST(Trajectory, CursorLookupMatchesPoseAt) {
    std::mt19937_64 rng(11);
    std::uniform_real_distribution<double> u(0.0, 1.0);
    // Orientations: large random turns (the acos branch, and dot < 0 between neighbours), a
    // 1 kHz table's tiny steps, a constant orientation and a quaternion and its negative
    // (Eigen's nearly-equal branch, with and without the sign flip).
    for (int kind = 0; kind < 4; ++kind) {
        std::vector<TimedPose> samples;
        for (int i = 0; i < 1000; ++i) {
            const double t = 1e-3 * i;
            Eigen::Vector3d rpy(0.1, 0.7, 0.2);
            if (kind == 0) {
                rpy = {3.0 * u(rng), 3.0 * u(rng), 6.0 * u(rng)};
            } else if (kind == 1) {
                rpy = {0.1 * std::sin(5.0 * t), 0.7 + 0.1 * std::sin(3.0 * t), 0.0};
            }
            Pose pose = PoseFromXyzRpy({t, 0.1 * u(rng), 1.0}, rpy);
            if (kind == 3 && i % 2 == 1) {
                pose.rotation.coeffs() = -pose.rotation.coeffs();
            }
            samples.push_back({t, pose});
        }
        const Trajectory traj(samples);
        Trajectory::Cursor cursor;
        double stamp = traj.StartTime();
        for (int k = 0; k < 20000; ++k) {
            const double r = u(rng);
            if (r < 0.8) {
                stamp += 3.7e-5 * u(rng);  // the beams of a scan
            } else if (r < 0.9) {
                stamp -= 0.01 * u(rng);  // back (interleaved turns)
            } else if (r < 0.95) {
                stamp = samples[static_cast<std::size_t>(u(rng) * 999.0)].stamp_s;  // on a sample
            } else {
                cursor = Trajectory::Cursor{};  // a fresh cursor mid-run
            }
            stamp = std::clamp(stamp, traj.StartTime(), traj.EndTime());
            const std::optional<Pose> got = traj.PoseAt(stamp, cursor);
            ASSERT_TRUE(got.has_value());
            const Pose want = *traj.PoseAt(stamp);
            const std::vector<std::uint64_t> got_bits = Bits(*got);
            const std::vector<std::uint64_t> want_bits = Bits(want);
            ASSERT_EQ(std::vector<std::uint64_t>(got_bits.begin(), got_bits.begin() + 3),
                      std::vector<std::uint64_t>(want_bits.begin(), want_bits.begin() + 3))
                << "kind " << kind << " stamp " << stamp;
            ASSERT_LE((got->rotation.coeffs() - want.rotation.coeffs()).cwiseAbs().maxCoeff(),
                      4e-16)
                << "kind " << kind << " stamp " << stamp;
        }
        EXPECT_EQ(Bits(*traj.PoseAt(traj.EndTime(), cursor)), Bits(samples.back().world_T_sensor));
        EXPECT_FALSE(traj.PoseAt(traj.EndTime() + 1e-9, cursor).has_value());
    }
}

TEST(Trajectory, RejectsNonIncreasingStamps) {
    EXPECT_THROW(Trajectory({{1.0, Pose{}}, {1.0, Pose{}}}), InputError);
}

}  // namespace
}  // namespace casmap::core
