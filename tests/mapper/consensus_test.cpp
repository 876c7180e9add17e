// The consensus cell height (mapper/consensus.hpp): hand-computed cases, the sample mean as
// the oracle on noisy floor points, and Eq. 5's certainty left exactly as the paper's.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>
#include <vector>

#include "casmap/core/input_error.hpp"
#include "casmap/mapper/terrain_mapper.hpp"

namespace casmap::mapper {
namespace {

TerrainMapperConfig Grid(std::optional<ConsensusConfig> consensus) {
    TerrainMapperConfig cfg;
    cfg.grid = core::GridGeometry{0.0, -1.0, 0.025, 160, 80};  // x in [0, 4), y in [-1, 1)
    cfg.consensus = consensus;
    return cfg;
}

// One cell of two mappers fed the same points: the paper's and the consensus one.
struct TwoMappers {
    explicit TwoMappers(ConsensusConfig consensus)
        : paper(Grid(std::nullopt)), mean(Grid(consensus)) {}
    void Add(double z, double dz_max_m = 0.02) {
        ASSERT_TRUE(paper.AddPoint(Eigen::Vector3d(1.01, 0.01, z), dz_max_m));
        ASSERT_TRUE(mean.AddPoint(Eigen::Vector3d(1.01, 0.01, z), dz_max_m));
    }
    [[nodiscard]] core::Cell Cell() const { return *paper.config().grid.CellOf(1.01, 0.01); }
    [[nodiscard]] float Paper() const { return paper.elevation().at(Cell().row, Cell().col); }
    [[nodiscard]] float Mean() const { return mean.elevation().at(Cell().row, Cell().col); }
    TerrainMapper paper;
    TerrainMapper mean;
};

TEST(ConsensusConfig, RejectsBadValuesNamingTheField) {
    ConsensusConfig c;
    EXPECT_NO_THROW(c.Validate());
    c.spread_m = -0.01;
    EXPECT_THROW(
        {
            try {
                c.Validate();
            } catch (const InputError& e) {
                EXPECT_NE(std::string(e.what()).find("consensus.spread_m"), std::string::npos);
                throw;
            }
        },
        InputError);
    c = ConsensusConfig{};
    c.min_hits = 1;
    EXPECT_THROW(TerrainMapper(Grid(c)), InputError);
    c = ConsensusConfig{};
    c.spread_m = std::numeric_limits<double>::infinity();
    EXPECT_THROW(TerrainMapper(Grid(c)), InputError);
}

TEST(Consensus, HandComputedMeanWhileTheHeightsAgree) {
    TwoMappers m(ConsensusConfig{0.02, 2});
    m.Add(0.10);  // one point: its own height in both
    EXPECT_FLOAT_EQ(m.Mean(), 0.10F);
    m.Add(0.11);  // spread 0.01 <= 0.02: mean 0.105; Eq. 6 keeps 0.11
    EXPECT_FLOAT_EQ(m.Mean(), 0.105F);
    EXPECT_FLOAT_EQ(m.Paper(), 0.11F);
    m.Add(0.115);  // spread 0.015: mean (0.10 + 0.11 + 0.115) / 3
    EXPECT_FLOAT_EQ(m.Mean(), static_cast<float>((0.10 + 0.11 + 0.115) / 3.0));
    m.Add(0.50);  // spread 0.40: two surfaces, Eq. 6's largest magnitude in both
    EXPECT_FLOAT_EQ(m.Mean(), 0.50F);
    EXPECT_FLOAT_EQ(m.Paper(), 0.50F);
    m.Add(0.12);  // the spread stays 0.40: still Eq. 6
    EXPECT_FLOAT_EQ(m.Mean(), 0.50F);
}

TEST(Consensus, MinHitsHoldsEq6UntilEnoughPoints) {
    TwoMappers m(ConsensusConfig{0.02, 3});
    m.Add(-0.01);
    m.Add(0.004);  // two points agree, but min_hits is 3: Eq. 6's -0.01 (the larger |z|)
    EXPECT_FLOAT_EQ(m.Mean(), -0.01F);
    m.Add(0.0);  // three: the mean
    EXPECT_FLOAT_EQ(m.Mean(), static_cast<float>((-0.01 + 0.004 + 0.0) / 3.0));
}

TEST(Consensus, CertaintyIsThePapersEq5) {
    // Eq. 5 compares each point with Eq. 6's height before the update, in both modes.
    TwoMappers m(ConsensusConfig{0.05, 2});
    for (const double z : {0.10, 0.11, 0.13, 0.09, 0.50, 0.45, 0.12, -0.60, 0.0}) {
        m.Add(z, 0.02);
        const core::Cell c = m.Cell();
        EXPECT_EQ(m.paper.certainty().at(c.row, c.col), m.mean.certainty().at(c.row, c.col)) << z;
    }
}

TEST(Consensus, NoisyFloorCellHoldsTheSampleMean) {
    const unsigned seed = 20261128;
    SCOPED_TRACE("seed " + std::to_string(seed));
    std::mt19937 rng(seed);
    std::normal_distribution<double> noise(0.0, 0.003);  // LMS 200-like height noise, 3 mm
    TwoMappers m(ConsensusConfig{0.05, 2});              // 40 samples span about 6 sigma
    std::vector<double> z(40);
    double largest = 0.0;
    double sum = 0.0;
    for (double& v : z) {
        v = noise(rng);
        m.Add(v);
        sum += v;
        largest = std::abs(v) > std::abs(largest) ? v : largest;
    }
    const auto [lo, hi] = std::minmax_element(z.begin(), z.end());
    ASSERT_LE(*hi - *lo, 0.05);
    EXPECT_FLOAT_EQ(m.Mean(), static_cast<float>(sum / 40.0));
    EXPECT_FLOAT_EQ(m.Paper(), static_cast<float>(largest));
    EXPECT_LT(std::abs(m.Mean()), std::abs(m.Paper()));  // the point of the mode
}

TEST(Consensus, UnknownCellsStayUnknownInBothConventions) {
    ConsensusConfig c;
    TerrainMapperConfig zero = Grid(c);
    TerrainMapperConfig nan = Grid(c);
    nan.unknown = Unknown::kNaN;
    TerrainMapper a(zero);
    TerrainMapper b(nan);
    EXPECT_EQ(a.elevation().at(3, 3), 0.0F);
    EXPECT_TRUE(std::isnan(b.elevation().at(3, 3)));
    ASSERT_TRUE(b.AddPoint(Eigen::Vector3d(1.01, 0.01, 0.0), 0.02));  // a first hit at 0 m
    const core::Cell cell = *b.config().grid.CellOf(1.01, 0.01);
    EXPECT_EQ(b.elevation().at(cell.row, cell.col), 0.0F);
    EXPECT_TRUE(std::isnan(b.elevation().at(3, 3)));
}

TEST(Consensus, AddScanMatchesAddPointPerBeam) {
    // The batched scan path and the per-point path give the same consensus map.
    std::vector<core::TimedPose> samples;
    for (int n = 0; n <= 1000; ++n) {
        const double t = n * 1e-3;
        samples.push_back({t, core::PoseFromXyzRpy(Eigen::Vector3d(t, 0.0, 1.0),
                                                   Eigen::Vector3d(0.0, 0.5, 0.0))});
    }
    const core::Trajectory traj(samples);
    ConsensusConfig c;
    TerrainMapper scans(Grid(c));
    TerrainMapper points(Grid(c));
    std::mt19937 rng(7);
    std::normal_distribution<double> noise(0.0, 0.004);
    for (int k = 0; k < 60; ++k) {
        core::Scan scan;
        scan.stamp_s = 0.1 + k / 75.0;
        scan.start_angle_rad = -0.2;
        scan.angle_step_rad = 0.01;
        scan.beam_period_s = 0.0;
        for (int i = 0; i < 41; ++i) {
            scan.beams.push_back(
                core::Beam{static_cast<float>(2.0 + noise(rng)), core::BeamStatus::kOk, 0});
        }
        scans.AddScan(scan, traj);
        const core::Pose pose = *traj.PoseAt(scan.stamp_s);
        for (std::size_t i = 0; i < scan.beams.size(); ++i) {
            SensorState state;
            state.world_R_sensor = pose.rotation.toRotationMatrix();
            state.origin_m = pose.translation;
            points.AddBeam(state, scan.BeamAngle(i), scan.beams[i].range_m);
        }
    }
    std::size_t agree = 0;
    for (std::size_t i = 0; i < scans.elevation().data.size(); ++i) {
        EXPECT_NEAR(scans.elevation().data[i], points.elevation().data[i], 1e-5F) << i;
        agree += scans.certainty().data[i] > 0.0F;
    }
    EXPECT_GT(agree, 50U);
}

}  // namespace
}  // namespace casmap::mapper
