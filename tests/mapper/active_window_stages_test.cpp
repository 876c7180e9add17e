// The live window's streaming stages against their offline definitions: the consensus cell
// height in the rolling window (a hand-made cell, rows recycled, and a whole run bit for bit
// against TerrainMapper in consensus mode), and the sweep_jump pre-filter as a stream (labels
// bit for bit those of SweepJumpLabels over the same scans and poses).
#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <numbers>
#include <string>
#include <vector>

#include "casmap/core/input_error.hpp"
#include "casmap/mapper/active_window.hpp"
#include "casmap/mapper/sweep_jump.hpp"
#include "casmap/mapper/sweep_jump_stream.hpp"
#include "casmap/mapper/synthetic_scans.hpp"

namespace casmap::mapper {
namespace {

constexpr double kDeg = std::numbers::pi / 180.0;
constexpr double kPitchRad = 60.0 * kDeg;  // the hand-made cases' scanner, 1 m up

// A 20 x 20 window of 0.2 m cells: row 3 (x in [0.6, 0.8) m ahead of a scanner at x = 0.05)
// is among the updated rows 2 .. 19.
ActiveWindowConfig SmallWindow(bool consensus) {
    ActiveWindowConfig c;
    c.rows = 20;
    c.cols = 20;
    c.m = 18;
    c.cell_m = 0.2;
    c.cas.cell_m = 0.2;
    if (consensus) {
        c.consensus = ConsensusConfig{0.02, 2};
    }
    return c;
}

// A scanner standing at (x, y, 1) pitched 60 deg down, heading `yaw`, from t = 0 to 10 s.
core::Trajectory Standing(double x_m, double y_m = 0.1, double yaw_rad = 0.0) {
    const core::Pose p = core::PoseFromXyzRpy({x_m, y_m, 1.0}, {0.0, kPitchRad, yaw_rad});
    return core::Trajectory({{0.0, p}, {10.0, p}});
}

// One beam straight ahead (sensor angle 0) with range r: lands at x + r / 2, z = 1 - r sin 60.
core::Scan OneBeam(double stamp_s, double range_m) {
    core::Scan s;
    s.stamp_s = stamp_s;
    s.start_angle_rad = 0.0;
    s.angle_step_rad = kDeg;
    s.beams = {core::Beam{static_cast<float>(range_m), core::BeamStatus::kOk, 0}};
    return s;
}

double HeightOf(double range_m) { return 1.0 - range_m * std::sin(kPitchRad); }

float Cell(const ActiveWindow& w, int row, int col, bool certainty = false) {
    core::MapF h;
    core::MapF c;
    w.Snapshot(h, c);
    return certainty ? c.at(row, col) : h.at(row, col);
}

TEST(ActiveWindowConsensus, ThreeAgreeingPointsGiveTheirMeanAnOutlierGivesEq6) {
    const core::Trajectory poses = Standing(0.05);
    ActiveWindow consensus(SmallWindow(true));
    ActiveWindow paper(SmallWindow(false));
    const double ranges[] = {1.40, 1.41, 1.39, 1.30};  // heights within 9 mm, then 0.09 m higher
    for (int n = 0; n < 4; ++n) {
        const core::Scan s = OneBeam(0.1 * (n + 1), ranges[n]);
        (void)consensus.AddScan(s, poses);
        (void)paper.AddScan(s, poses);
        // The cell: row 3 (x = 0.7 .. 0.755), column C / 2 (y = 0.1).
        EXPECT_EQ(Cell(consensus, 3, 10, true), Cell(paper, 3, 10, true)) << "certainty, " << n;
        if (n == 1) {
            EXPECT_NEAR(Cell(consensus, 3, 10), (HeightOf(1.40) + HeightOf(1.41)) / 2.0, 1e-6);
        }
    }
    // Hand-computed heights: -0.2124, -0.2211, -0.2038, -0.1258 m.
    ActiveWindow three(SmallWindow(true));
    for (int n = 0; n < 3; ++n) {
        (void)three.AddScan(OneBeam(0.1 * (n + 1), ranges[n]), poses);
    }
    const double mean = (HeightOf(1.40) + HeightOf(1.41) + HeightOf(1.39)) / 3.0;
    EXPECT_NEAR(Cell(three, 3, 10), mean, 1e-6);
    EXPECT_GT(std::abs(Cell(three, 3, 10) - HeightOf(1.41)), 0.005);  // not Eq. 6's
    // The outlier spreads the cell over 0.095 m > 0.02 m: Eq. 6, the height of largest
    // magnitude (range 1.41), as the paper mode holds.
    EXPECT_NEAR(Cell(consensus, 3, 10), HeightOf(1.41), 1e-6);
    EXPECT_EQ(Cell(consensus, 3, 10), Cell(paper, 3, 10));
    EXPECT_EQ(Cell(consensus, 3, 10, true), 9.0F);  // 1.30 m is beyond Eq. 5's bound: no count
}

TEST(ActiveWindowConsensus, RecycledRowsStartWithoutConsensusState) {
    ActiveWindow w(SmallWindow(true));
    const core::Trajectory here = Standing(0.05);
    (void)w.AddScan(OneBeam(0.1, 1.40), here);
    (void)w.AddScan(OneBeam(0.2, 1.30), here);  // spread: the cell keeps Eq. 6
    EXPECT_NEAR(Cell(w, 3, 10), HeightOf(1.40), 1e-6);
    // 20 rows (4 m) on: lattice row 23 lives in row 3's slot.
    const core::Trajectory there = Standing(4.05);
    (void)w.AddScan(OneBeam(0.3, 1.20), there);
    (void)w.AddScan(OneBeam(0.4, 1.21), there);
    ASSERT_EQ(w.first_row(), 20);
    // Two agreeing points of a fresh cell: their mean with certainty 2 a, whatever the slot
    // held before (a stale Eq. 6 height of -0.21 m, count and spread would give Eq. 6's -0.21).
    EXPECT_NEAR(Cell(w, 3, 10), (HeightOf(1.20) + HeightOf(1.21)) / 2.0, 1e-6);
    EXPECT_EQ(Cell(w, 3, 10, true), 6.0F);
}

TEST(ActiveWindowConsensus, ResamplingCarriesTheConsensusState) {
    ActiveWindow w(SmallWindow(true));
    (void)w.AddScan(OneBeam(0.1, 1.40), Standing(0.05));  // (0.75, 0.1): lattice cell (3, 0)
    (void)w.AddScan(OneBeam(0.2, 1.41), Standing(0.05));
    // Heading 32 deg: the frame turns to 30 deg. The scanner stands so that its beam lands
    // 0.7 m (range 1.4) ahead at (0.7, 0.1): new lattice cell (3, -2), whose centre (0.756,
    // 0.090) lies in the old cell (3, 0), so that cell is carried into it.
    const double yaw = 32.0 * kDeg;
    const core::Trajectory turned =
        Standing(0.7 - 0.7 * std::cos(yaw), 0.1 - 0.7 * std::sin(yaw), yaw);
    (void)w.AddScan(OneBeam(0.3, 1.39), turned);  // lands at (0.696, 0.097): the same new cell
    ASSERT_EQ(w.stats().turns, 1U);
    ASSERT_NEAR(w.heading_rad(), 30.0 * kDeg, 1e-12);
    ASSERT_EQ(w.first_row(), -1);
    ASSERT_EQ(w.first_col(), -12);
    // The three heights' mean: the third point joined the carried sum and count (a cleared
    // state would show the third height alone, Eq. 6 of a one-point cell).
    const double mean = (HeightOf(1.40) + HeightOf(1.41) + HeightOf(1.39)) / 3.0;
    EXPECT_NEAR(Cell(w, 4, 10), mean, 1e-6);
    EXPECT_EQ(Cell(w, 4, 10, true), 9.0F);
}

TEST(ActiveWindowConsensus, BadSettingsNameTheField) {
    ActiveWindowConfig c;
    c.consensus = ConsensusConfig{-0.01, 2};
    try {
        c.Validate();
        FAIL() << "accepted a negative spread";
    } catch (const InputError& e) {
        EXPECT_NE(std::string(e.what()).find("active window"), std::string::npos) << e.what();
        EXPECT_EQ(e.field(), "consensus.spread_m");
    }
    c.consensus = ConsensusConfig{0.02, 1};
    try {
        c.Validate();
        FAIL() << "accepted min_hits 1";
    } catch (const InputError& e) {
        EXPECT_EQ(e.field(), "consensus.min_hits");
    }
    ActiveWindow w(ActiveWindowConfig{});
    const SyntheticRun run = BuildSyntheticRun(SyntheticDrive{});
    const std::vector<std::uint8_t> keep(3, 1);
    EXPECT_THROW((void)w.AddScan(run.scans[0], run.poses, keep), InputError);
}

// The paper vehicle at 1 m/s past three boxes, with cross-scan mixed pixels at the boxes' far
// edges, in-scan spikes and 1 cm of range noise.
SyntheticRun MixedRun() {
    SyntheticDrive d;
    d.duration_s = 4.0;
    d.boxes = {
        {4.0, 4.3, -0.4, -0.1, 0.25}, {4.6, 4.8, 0.3, 0.9, 0.15}, {5.5, 5.9, -1.2, -0.7, 0.2}};
    d.spike_every = 37;
    d.mixed_far_edges = true;
    d.range_noise_m = 0.01;
    return BuildSyntheticRun(d);
}

std::size_t Rejected(const std::vector<std::vector<std::uint8_t>>& labels) {
    std::size_t n = 0;
    for (const auto& l : labels) {
        for (const std::uint8_t v : l) {
            n += v == 0 ? 1 : 0;
        }
    }
    return n;
}

// Streams `run` (each scan with the whole trajectory) and returns the labels in scan order.
std::vector<std::vector<std::uint8_t>> StreamLabels(const SyntheticRun& run,
                                                    const SweepJumpConfig& config) {
    SweepJumpStream stream(config);
    std::vector<std::vector<std::uint8_t>> out;
    for (std::size_t k = 0; k < run.scans.size(); ++k) {
        stream.Push(run.scans[k], run.poses);
        EXPECT_EQ(stream.waiting(), std::min<std::size_t>(k + 1, config.reach)) << k;
        while (auto l = stream.Pop()) {
            EXPECT_EQ(l->scan.stamp_s, run.scans[out.size()].stamp_s);
            out.push_back(std::move(l->keep));
        }
        // Scan k - reach is labelled once scan k has arrived.
        EXPECT_EQ(out.size(), k + 1 >= config.reach ? k + 1 - config.reach : 0) << k;
    }
    stream.Finish();
    while (auto l = stream.Pop()) {
        out.push_back(std::move(l->keep));
    }
    EXPECT_EQ(stream.waiting(), 0U);
    EXPECT_THROW(stream.Push(run.scans[0], run.poses), InputError);
    return out;
}

TEST(SweepJumpStream, LabelsAreTheOfflineFiltersBitForBit) {
    const SyntheticRun run = MixedRun();
    for (const int reach : {1, 2, 3}) {
        SweepJumpConfig config;
        config.reach = reach;
        const auto offline = SweepJumpLabels(run.scans, run.poses, config);
        const auto live = StreamLabels(run, config);
        ASSERT_EQ(live.size(), run.scans.size());
        EXPECT_EQ(live, offline) << "reach " << reach;
        EXPECT_GT(Rejected(offline), 20U) << "reach " << reach;  // the mixed pixels are there
    }
    // Without the mixed pixels nothing is rejected (the spikes are in-scan, not sweep jumps).
    SyntheticDrive clean;
    clean.boxes = {{4.0, 4.3, -0.4, -0.1, 0.25}};
    clean.duration_s = 2.0;
    EXPECT_EQ(Rejected(SweepJumpLabels(BuildSyntheticRun(clean).scans,
                                       BuildSyntheticRun(clean).poses, {})),
              0U);
}

TEST(SweepJumpStream, RunningMedianGapIsTheOfflineMedian) {
    SweepJumpStream stream({});
    const double stamps[] = {0.0, 0.01, 0.03, 0.04, 0.10, 0.11};   // gaps .01 .02 .01 .06 .01
    const double medians[] = {0.0, 0.01, 0.02, 0.01, 0.02, 0.01};  // element n / 2 of the sorted
    const SyntheticRun run = BuildSyntheticRun(SyntheticDrive{});
    for (int n = 0; n < 6; ++n) {
        core::Scan s = run.scans[static_cast<std::size_t>(n)];
        s.stamp_s = stamps[n];
        stream.Push(s, run.poses);
        EXPECT_NEAR(stream.median_gap_s(), medians[n], 1e-12) << n;
    }
}

// Compares each filtered row with the offline consensus map + whole-map CAS, bit for bit.
std::size_t CompareRows(const std::vector<FilteredRow>& rows,
                        const TerrainMapper& offline,
                        const CasParams& cas) {
    const FilterResult full = CasFilter(offline.elevation(), offline.certainty(), cas);
    const core::GridGeometry& g = offline.config().grid;
    std::size_t compared = 0;
    for (const FilteredRow& r : rows) {
        EXPECT_GE(r.row, 2);
        EXPECT_LT(r.row, g.rows - 2);
        for (std::size_t j = 2; j + 2 < r.elevation.size(); ++j) {
            const std::int64_t b = r.first_col + static_cast<std::int64_t>(j);
            if (b < 2 || b >= g.cols - 2) {
                continue;
            }
            const int ri = static_cast<int>(r.row);
            const int bi = static_cast<int>(b);
            if (std::bit_cast<std::uint32_t>(r.raw[j]) !=
                    std::bit_cast<std::uint32_t>(offline.elevation().at(ri, bi)) ||
                r.certainty[j] != offline.certainty().at(ri, bi) ||
                std::bit_cast<std::uint32_t>(r.elevation[j]) !=
                    std::bit_cast<std::uint32_t>(full.elevation.at(ri, bi)) ||
                r.classes[j] != full.classes.at(ri, bi)) {
                ADD_FAILURE() << "cell " << r.row << "," << b << ": live " << r.raw[j] << " "
                              << r.certainty[j] << " " << r.elevation[j] << ", offline "
                              << offline.elevation().at(ri, bi) << " "
                              << offline.certainty().at(ri, bi) << " " << full.elevation.at(ri, bi);
                return compared;
            }
            ++compared;
        }
    }
    return compared;
}

TEST(ActiveWindowConsensus, StraightRunWithSweepJumpIsTheOfflinePathBitForBit) {
    const SyntheticRun run = MixedRun();
    ActiveWindowConfig cfg;
    cfg.origin_x_m = -2.0;
    cfg.origin_y_m = -6.0;
    cfg.consensus = ConsensusConfig{0.02, 2};
    ActiveWindow w(cfg);
    SweepJumpStream stream({});
    std::vector<FilteredRow> rows;
    std::size_t in_consensus = 0;  // cells the window shows another height than Eq. 6's
    const auto take = [&](const SweepJumpStream::Labelled& l) {
        for (const FilteredRow& r : w.AddScan(l.scan, l.poses, l.keep)) {
            rows.push_back(r);
        }
    };
    for (const core::Scan& s : run.scans) {
        stream.Push(s, run.poses);
        while (const auto l = stream.Pop()) {
            take(*l);
        }
    }
    stream.Finish();
    while (const auto l = stream.Pop()) {
        take(*l);
    }
    // Offline: the run's labels, then the consensus mapper over the same grid lattice.
    const auto labels = SweepJumpLabels(run.scans, run.poses, {});
    TerrainMapperConfig mc;
    mc.grid = core::GridGeometry{cfg.origin_x_m, cfg.origin_y_m, 0.025, 520, 480};
    mc.consensus = cfg.consensus;
    TerrainMapper offline(mc);
    TerrainMapperConfig pc = mc;
    pc.consensus.reset();
    TerrainMapper paper(pc);
    for (std::size_t k = 0; k < run.scans.size(); ++k) {
        offline.AddScan(run.scans[k], run.poses, labels[k]);
        paper.AddScan(run.scans[k], run.poses, labels[k]);
    }
    ASSERT_EQ(w.stats().turns, 0U);
    ASSERT_EQ(w.stats().beams_behind, 0U);
    ASSERT_GT(rows.size(), 100U);
    EXPECT_EQ(w.stats().beams.beams_rejected, Rejected(labels));
    EXPECT_EQ(w.stats().beams.beams_rejected, offline.stats().beams_rejected);
    EXPECT_GT(w.stats().beams.beams_rejected, 20U);
    EXPECT_GT(CompareRows(rows, offline, cfg.cas), 40000U);
    for (const FilteredRow& r : rows) {
        for (std::size_t j = 0; j < r.raw.size(); ++j) {
            const std::int64_t b = r.first_col + static_cast<std::int64_t>(j);
            if (b >= 0 && b < mc.grid.cols && r.certainty[j] > 0.0F) {
                in_consensus +=
                    r.raw[j] != paper.elevation().at(static_cast<int>(r.row), static_cast<int>(b))
                        ? 1
                        : 0;
            }
        }
    }
    EXPECT_GT(in_consensus, 1000U);  // the consensus rule is exercised, not just Eq. 6
}

}  // namespace
}  // namespace casmap::mapper
