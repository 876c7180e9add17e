// The sweep-jump pre-filter on closed-form geometry: the bench rig's scanner (1 m high, pitched
// 40 degrees down, 75 scans/s) driving at 1 m/s towards the far edge of a box top. Every range is
// the exact distance to the first plane the beam meets; the mixed pixels put in by hand are the
// only returns between two surfaces, so the expected labels are known beam by beam.
#include "casmap/mapper/sweep_jump.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <numbers>
#include <set>
#include <span>
#include <utility>

#include "casmap/core/input_error.hpp"

namespace casmap::mapper {
namespace {

constexpr double kDeg = std::numbers::pi / 180.0;
constexpr double kScanPeriodS = 1.0 / 75.0;
constexpr double kSpeedMS = 1.0;
constexpr double kHeightM = 1.0;
constexpr double kPitchRad = 40.0 * kDeg;
constexpr double kBoxTopM = 0.46;  // box top height
constexpr double kBoxEndXM = 2.0;  // the box top spans x < 2.0 m (every y); floor z = 0 beyond
constexpr int kBeams = 181;

core::Pose PoseAt(int k, double roll_per_scan_rad) {
    return core::PoseFromXyzRpy({kSpeedMS * kScanPeriodS * k, 0.0, kHeightM},
                                {roll_per_scan_rad * k, kPitchRad, 0.0});
}

// The world ray of beam i of scan k (its pose is the scan's: the trajectory below holds one
// sample per scan and the beams' times all fall on it, beam_period_s = 0).
std::pair<Eigen::Vector3d, Eigen::Vector3d> Ray(int k, int i, double roll_per_scan_rad) {
    const core::Pose pose = PoseAt(k, roll_per_scan_rad);
    const double angle = (-90.0 + i) * kDeg;
    return {pose.translation,
            pose.rotation * Eigen::Vector3d(std::cos(angle), std::sin(angle), 0.0)};
}

// Range along (o, d) to the horizontal plane z = h, or a negative number if it is not ahead.
double ToPlane(const Eigen::Vector3d& o, const Eigen::Vector3d& d, double h) {
    return d.z() < 0.0 ? (h - o.z()) / d.z() : -1.0;
}

struct SweepRun {
    std::vector<core::Scan> scans;
    core::Trajectory poses;
    std::set<std::pair<int, int>> mixed;  // (scan, beam) given a mixed range
};

// `count` scans; with_box: the box top ends at kBoxEndXM and the first `mixed_scans` beams of
// each column to reach the floor past it return halfway between the top's plane and the floor
// (mixed pixels), for beams in [mixed_from, mixed_to].
SweepRun MakeRun(int count,
                 bool with_box,
                 double roll_per_scan_rad,
                 int mixed_from,
                 int mixed_to,
                 int mixed_scans = 1) {
    SweepRun run;
    std::vector<core::TimedPose> samples;
    std::vector<int> crossed(kBeams, 0);
    for (int k = 0; k < count; ++k) {
        samples.push_back({k * kScanPeriodS, PoseAt(k, roll_per_scan_rad)});
        core::Scan scan;
        scan.stamp_s = k * kScanPeriodS;
        scan.start_angle_rad = -90.0 * kDeg;
        scan.angle_step_rad = kDeg;
        scan.beam_period_s = 0.0;
        scan.beams.assign(kBeams, core::Beam{});
        for (int i = 0; i < kBeams; ++i) {
            const auto [o, d] = Ray(k, i, roll_per_scan_rad);
            const double floor = ToPlane(o, d, 0.0);
            double range = floor;
            if (with_box) {
                const double top = ToPlane(o, d, kBoxTopM);
                const bool on_top = top > 0.0 && (o + top * d).x() < kBoxEndXM;
                range = on_top ? top : floor;
                if (!on_top && crossed[static_cast<std::size_t>(i)] < mixed_scans && k > 0) {
                    ++crossed[static_cast<std::size_t>(i)];
                    if (i >= mixed_from && i <= mixed_to) {
                        range = 0.5 * (top + floor);
                        run.mixed.insert({k, i});
                    }
                }
            }
            if (range > 0.2 && range < 8.0) {
                scan.beams[static_cast<std::size_t>(i)] =
                    core::Beam{static_cast<float>(range), core::BeamStatus::kOk, 0};
            }
        }
        run.scans.push_back(std::move(scan));
    }
    run.poses = core::Trajectory(std::move(samples));
    return run;
}

std::set<std::pair<int, int>> Rejected(const std::vector<std::vector<std::uint8_t>>& keep) {
    std::set<std::pair<int, int>> out;
    for (std::size_t k = 0; k < keep.size(); ++k) {
        for (std::size_t i = 0; i < keep[k].size(); ++i) {
            if (keep[k][i] == 0) {
                out.insert({static_cast<int>(k), static_cast<int>(i)});
            }
        }
    }
    return out;
}

TEST(SweepJump, RejectsExactlyTheMixedPixelsAtABoxsFarEdge) {
    // The scan line reaches the box's far edge (x = 2 m) about 1.6 s in; 200 scans cross it.
    const SweepRun run = MakeRun(200, true, 0.0, 60, 120);
    ASSERT_GT(run.mixed.size(), 50U);
    const auto keep = SweepJumpLabels(run.scans, run.poses, {});
    ASSERT_EQ(keep.size(), run.scans.size());
    EXPECT_EQ(Rejected(keep), run.mixed);
}

TEST(SweepJump, ReachTwoRejectsMixedPixelsRepeatedInTwoScans) {
    // A slower sweep over the edge: two consecutive scans of each column return mixed ranges, so
    // each mixed return has a mixed neighbour and reach 1 cannot bracket it; scans k -/+ 2 can.
    const SweepRun run = MakeRun(200, true, 0.0, 60, 120, 2);
    ASSERT_EQ(run.mixed.size(), 2U * 61U);
    EXPECT_TRUE(Rejected(SweepJumpLabels(run.scans, run.poses, {})).empty());
    SweepJumpConfig two;
    two.reach = 2;
    EXPECT_EQ(Rejected(SweepJumpLabels(run.scans, run.poses, two)), run.mixed);
    // Reach 2 adds no rejection where reach 1 already finds them all, nor at a clean edge.
    const SweepRun single = MakeRun(200, true, 0.0, 60, 120);
    EXPECT_EQ(Rejected(SweepJumpLabels(single.scans, single.poses, two)), single.mixed);
    const SweepRun clean = MakeRun(200, true, 0.0, 1, 0);
    two.reach = 3;
    EXPECT_TRUE(Rejected(SweepJumpLabels(clean.scans, clean.poses, two)).empty());
}

TEST(SweepJump, KeepsTheSameEdgeWithoutMixedPixels) {
    // The depth jumps from the box top to the floor behind it; no return lies between.
    const SweepRun run = MakeRun(200, true, 0.0, 1, 0);
    EXPECT_TRUE(Rejected(SweepJumpLabels(run.scans, run.poses, {})).empty());
}

TEST(SweepJump, TheLineOfSightTestKeepsAFloorSeenByARollingScanner) {
    // 1.5 degrees of roll per scan: on the outer beams consecutive floor points are tens of
    // centimetres apart in depth, and the middle one lies between them, so only the chord
    // test (the three points lie along the floor, not along the line of sight) keeps them.
    const SweepRun run = MakeRun(60, false, 1.5 * kDeg, 1, 0);
    EXPECT_TRUE(Rejected(SweepJumpLabels(run.scans, run.poses, {})).empty());
    SweepJumpConfig no_chord;
    no_chord.max_angle_deg = 89.9;
    no_chord.depression_share = 0.0;
    EXPECT_GT(Rejected(SweepJumpLabels(run.scans, run.poses, no_chord)).size(), 100U);
}

// A scanner 0.5 m above a flat floor looking 7 degrees down, its pitch rising 0.3 degrees per
// scan (a vehicle pitching over rough ground): the floor ranges fall 0.1-0.2 m per scan, so each
// return lies between its neighbours, and their chord runs along the floor, 7-9 degrees from
// the line of sight, inside max_angle_deg.
TEST(SweepJump, TheDepressionLimitKeepsGroundSeenAtAGrazingAngle) {
    std::vector<core::TimedPose> samples;
    std::vector<core::Scan> scans;
    for (int k = 0; k < 8; ++k) {
        const core::Pose pose =
            core::PoseFromXyzRpy({0.01 * k, 0.0, 0.5}, {0.0, (7.0 + 0.3 * k) * kDeg, 0.0});
        samples.push_back({k * kScanPeriodS, pose});
        core::Scan scan;
        scan.stamp_s = k * kScanPeriodS;
        scan.start_angle_rad = -10.0 * kDeg;
        scan.angle_step_rad = kDeg;
        scan.beam_period_s = 0.0;
        for (int i = 0; i <= 20; ++i) {
            const double angle = (-10.0 + i) * kDeg;
            const Eigen::Vector3d d =
                pose.rotation * Eigen::Vector3d(std::cos(angle), std::sin(angle), 0.0);
            scan.beams.push_back(core::Beam{static_cast<float>(ToPlane(pose.translation, d, 0.0)),
                                            core::BeamStatus::kOk, 0});
        }
        scans.push_back(std::move(scan));
    }
    const core::Trajectory poses(std::move(samples));
    EXPECT_TRUE(Rejected(SweepJumpLabels(scans, poses, {})).empty());
    SweepJumpConfig no_depression_limit;
    no_depression_limit.depression_share = 0.0;
    // Every beam of every inner scan: 6 scans x 21 beams.
    EXPECT_EQ(Rejected(SweepJumpLabels(scans, poses, no_depression_limit)).size(), 126U);
}

TEST(SweepJump, KeepsAForegroundReturnAndEveryBeamItCannotJudge) {
    SweepRun run = MakeRun(5, false, 0.0, 1, 0);
    // A pole in scan 2 on beam 90: nearer than both neighbours, not between them.
    run.scans[2].beams[90].range_m *= 0.5F;
    // A return between its neighbours but with beam 91 of scan 3 missing: kept.
    run.scans[2].beams[91].range_m += 0.5F;
    run.scans[3].beams[91].status = core::BeamStatus::kNoReturn;
    auto keep = SweepJumpLabels(run.scans, run.poses, {});
    EXPECT_TRUE(Rejected(keep).empty());
    // The same return with scan 3 restored and made far: rejected.
    run.scans[3].beams[91].status = core::BeamStatus::kOk;
    run.scans[3].beams[91].range_m += 2.0F;
    keep = SweepJumpLabels(run.scans, run.poses, {});
    EXPECT_EQ(Rejected(keep), (std::set<std::pair<int, int>>{{2, 91}}));
    // A neighbour of another scan geometry counts as missing; so does a beam without a pose.
    SweepRun other = run;
    other.scans[1].angle_step_rad = 0.5 * kDeg;
    EXPECT_TRUE(Rejected(SweepJumpLabels(other.scans, other.poses, {})).empty());
    // A neighbour more than 1.5 median scan gaps away (a scan dropped between) counts as
    // missing; one within the jitter allowance still counts.
    other = run;
    other.scans[3].stamp_s += 0.9 * kScanPeriodS;
    EXPECT_TRUE(Rejected(SweepJumpLabels(other.scans, other.poses, {})).empty());
    other = run;
    other.scans[3].stamp_s += 0.3 * kScanPeriodS;
    EXPECT_EQ(Rejected(SweepJumpLabels(other.scans, other.poses, {})),
              (std::set<std::pair<int, int>>{{2, 91}}));
    other = run;
    other.scans[2].stamp_s = 99.0;  // after the trajectory's end
    EXPECT_TRUE(Rejected(SweepJumpLabels(other.scans, other.poses, {})).empty());
    // An empty run gives no labels (first and last scans: the next test).
    EXPECT_TRUE(SweepJumpLabels({}, run.poses, {}).empty());
}

TEST(SweepJump, JudgesOnlyScansWithTwoNeighboursNeverWrappingAround) {
    SweepRun run = MakeRun(3, false, 0.0, 1, 0);
    const auto set = [&run](int beam, float r0, float r1, float r2) {
        const float floor = run.scans[1].beams[static_cast<std::size_t>(beam)].range_m;
        for (const auto& [k, r] : {std::pair{0, r0}, std::pair{1, r1}, std::pair{2, r2}}) {
            run.scans[static_cast<std::size_t>(k)].beams[static_cast<std::size_t>(beam)].range_m =
                floor + r;
        }
    };
    // Beam 110: a mixed return in the middle scan, rejected (the control).
    set(110, 0.0F, 0.5F, 1.0F);
    // Beam 90: the first scan's return lies between the other two scans' (it would be rejected
    // if scan 0's neighbours wrapped around to the last scan); beam 70: the same for the last.
    set(90, 0.5F, 0.0F, 1.0F);
    set(70, 0.0F, 1.0F, 0.5F);
    EXPECT_EQ(Rejected(SweepJumpLabels(run.scans, run.poses, {})),
              (std::set<std::pair<int, int>>{{1, 110}}));
    // One or two scans: nothing to compare, every beam kept, one label per beam.
    for (const std::size_t count : {1U, 2U}) {
        const std::span<const core::Scan> part(run.scans.data(), count);
        const auto keep = SweepJumpLabels(part, run.poses, {});
        ASSERT_EQ(keep.size(), count);
        for (const auto& labels : keep) {
            EXPECT_EQ(labels, std::vector<std::uint8_t>(kBeams, 1));
        }
    }
}

TEST(SweepJump, NeighboursWithoutAFinitePositiveRangeCountAsMissing) {
    SweepRun run = MakeRun(5, false, 0.0, 1, 0);
    core::Beam& before = run.scans[1].beams[91];
    core::Beam& beam = run.scans[2].beams[91];
    core::Beam& after = run.scans[3].beams[91];
    const float floor = beam.range_m;
    // The control: a return halfway between a near and a far neighbour is rejected.
    beam.range_m = floor + 0.5F;
    after.range_m = floor + 1.0F;
    ASSERT_EQ(Rejected(SweepJumpLabels(run.scans, run.poses, {})),
              (std::set<std::pair<int, int>>{{2, 91}}));
    // A kOk neighbour at +inf (far at infinity, chord along the line of sight) or NaN: kept.
    for (const float bad :
         {std::numeric_limits<float>::infinity(), std::numeric_limits<float>::quiet_NaN()}) {
        after.range_m = bad;
        EXPECT_TRUE(Rejected(SweepJumpLabels(run.scans, run.poses, {})).empty()) << bad;
    }
    // A neighbour at range 0 or below would sit at (or behind) the origin, a near depth on the
    // line of sight itself: kept too.
    after.range_m = floor;
    beam.range_m = 0.5F * floor;
    for (const float bad : {0.0F, -1.0F}) {
        before.range_m = bad;
        EXPECT_TRUE(Rejected(SweepJumpLabels(run.scans, run.poses, {})).empty()) << bad;
    }
    // The beam itself at +inf or NaN: not between its neighbours, kept.
    before.range_m = floor;
    for (const float bad :
         {std::numeric_limits<float>::infinity(), std::numeric_limits<float>::quiet_NaN()}) {
        beam.range_m = bad;
        EXPECT_TRUE(Rejected(SweepJumpLabels(run.scans, run.poses, {})).empty()) << bad;
    }
}

TEST(SweepJump, ValidatesEveryFieldByName) {
    const auto fails = [](SweepJumpConfig c, const std::string& field) {
        try {
            c.Validate();
            ADD_FAILURE() << field << " accepted";
        } catch (const InputError& e) {
            EXPECT_NE(std::string(e.what()).find(field), std::string::npos) << e.what();
        }
    };
    SweepJumpConfig c;
    c.jump_min_m = 0.0;
    fails(c, "sweep_jump.jump_min_m");
    c = {};
    c.margin_m = 0.06;  // above jump_min_m / 2
    fails(c, "sweep_jump.margin_m");
    c = {};
    c.max_angle_deg = 90.0;
    fails(c, "sweep_jump.max_angle_deg");
    c = {};
    c.max_angle_deg = std::nan("");
    fails(c, "sweep_jump.max_angle_deg");
    c = {};
    c.depression_share = 1.5;
    fails(c, "sweep_jump.depression_share");
    c = {};
    c.reach = 0;
    fails(c, "sweep_jump.reach");
    c.reach = 4;
    fails(c, "sweep_jump.reach");
    c = {};
    c.margin_m = 0.05;  // exactly jump_min_m / 2: allowed
    EXPECT_NO_THROW(c.Validate());
}

}  // namespace
}  // namespace casmap::mapper
