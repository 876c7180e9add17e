// pipeline::StreamMapper against its oracle, MapScans on the same scans: every mapper mode and
// pre-filter, bit for bit once the stream is finished.
#include "casmap/pipeline/stream_mapper.hpp"

#include <gtest/gtest.h>

#include <cstring>
#include <string>
#include <tuple>
#include <vector>

#include "casmap/core/input_error.hpp"
#include "casmap/mapper/synthetic_scans.hpp"
#include "casmap/pipeline/map_run.hpp"

namespace casmap::pipeline {
namespace {

// The paper vehicle at 1 m/s past three boxes, with cross-scan mixed pixels at the boxes' far
// edges (sweep_jump's case), in-scan spikes (range_jump's and shadow's) and 1 cm range noise.
const mapper::SyntheticRun& MixedRun() {
    static const mapper::SyntheticRun run = [] {
        mapper::SyntheticDrive d;
        d.duration_s = 3.0;
        d.boxes = {
            {4.0, 4.3, -0.4, -0.1, 0.25}, {4.6, 4.8, 0.3, 0.9, 0.15}, {5.5, 5.9, -1.2, -0.7, 0.2}};
        d.spike_every = 37;
        d.mixed_far_edges = true;
        d.range_noise_m = 0.01;
        return mapper::BuildSyntheticRun(d);
    }();
    return run;
}

core::GridGeometry Grid() {
    core::GridGeometry g;
    g.x0_m = 1.0;
    g.y0_m = -2.0;
    g.cell_m = 0.05;
    g.rows = 120;
    g.cols = 80;
    return g;
}

bool SameBits(const core::MapF& a, const core::MapF& b) {
    return a.rows == b.rows && a.cols == b.cols && a.data.size() == b.data.size() &&
           std::memcmp(a.data.data(), b.data.data(), sizeof(float) * a.data.size()) == 0;
}

using Case = std::tuple<MapperMode, Prefilter>;

class StreamMapperEqualsMapScans : public testing::TestWithParam<Case> {};

TEST_P(StreamMapperEqualsMapScans, BitForBitOnceFinished) {
    const auto [mode, prefilter] = GetParam();
    MapSettings settings;
    settings.mode = mode;
    settings.prefilter = prefilter;
    settings.unknown = mode == MapperMode::kKalman ? mapper::Unknown::kNaN : mapper::Unknown::kZero;
    const mapper::SyntheticRun& run = MixedRun();
    const MappedRun oracle = MapScans(run.scans, run.poses, Grid(), settings);

    StreamMapper stream(Grid(), settings, ScanPeriod(run.scans));
    for (const core::Scan& scan : run.scans) {
        stream.AddScan(scan, run.poses);
        // sweep_jump holds back the scans whose next neighbour has not arrived: reach 1.
        EXPECT_EQ(stream.waiting(), prefilter == Prefilter::kSweepJump ? 1U : 0U);
    }
    stream.Finish();
    EXPECT_EQ(stream.waiting(), 0U);
    EXPECT_TRUE(SameBits(stream.elevation(), oracle.elevation));
    EXPECT_TRUE(SameBits(stream.certainty(), oracle.certainty));
    EXPECT_EQ(stream.stats().beams_seen, oracle.stats.beams_seen);
    EXPECT_EQ(stream.stats().beams_rejected, oracle.stats.beams_rejected);
    EXPECT_EQ(stream.stats().beams_mapped, oracle.stats.beams_mapped);
    if (prefilter != Prefilter::kNone) {
        EXPECT_GT(stream.stats().beams_rejected, 0U);  // the run gives each filter work
    }
}

INSTANTIATE_TEST_SUITE_P(EveryModeAndPrefilter,
                         StreamMapperEqualsMapScans,
                         testing::Combine(testing::Values(MapperMode::kPaper,
                                                          MapperMode::kConsensus,
                                                          MapperMode::kKalman),
                                          testing::Values(Prefilter::kNone,
                                                          Prefilter::kShadow,
                                                          Prefilter::kRangeJump,
                                                          Prefilter::kSweepJump)),
                         [](const testing::TestParamInfo<Case>& info) {
                             return std::string(ToString(std::get<0>(info.param))) + "_" +
                                    std::string(ToString(std::get<1>(info.param)));
                         });

TEST(StreamMapper, SweepJumpMapsAScanOnlyOnceItsNeighbourArrived) {
    MapSettings settings;
    settings.prefilter = Prefilter::kSweepJump;
    settings.sweep_jump.reach = 2;
    const mapper::SyntheticRun& run = MixedRun();
    StreamMapper stream(Grid(), settings, ScanPeriod(run.scans));
    stream.AddScan(run.scans[0], run.poses);
    stream.AddScan(run.scans[1], run.poses);
    EXPECT_EQ(stream.waiting(), 2U);
    EXPECT_EQ(stream.stats().beams_seen, 0U);  // nothing mapped yet
    stream.AddScan(run.scans[2], run.poses);
    EXPECT_EQ(stream.waiting(), 2U);
    EXPECT_EQ(stream.stats().beams_seen, run.scans[0].beams.size());
    stream.Finish();
    stream.Finish();  // idempotent
    EXPECT_EQ(stream.stats().beams_seen, 3 * run.scans[0].beams.size());
}

TEST(StreamMapper, AScanAfterFinishIsAnInputError) {
    const mapper::SyntheticRun& run = MixedRun();
    StreamMapper stream(Grid(), MapSettings{}, ScanPeriod(run.scans));
    stream.AddScan(run.scans[0], run.poses);
    stream.Finish();
    try {
        stream.AddScan(run.scans[1], run.poses);
        FAIL() << "accepted a scan after Finish()";
    } catch (const InputError& e) {
        EXPECT_EQ(e.field(), "AddScan");
    }
}

TEST(StreamMapper, BadSettingsNameTheirField) {
    MapSettings settings;
    settings.prefilter = Prefilter::kSweepJump;
    settings.sweep_jump.margin_m = -1.0;
    try {
        StreamMapper stream(Grid(), settings, 1.0 / 75.0);
        FAIL() << "accepted a negative margin";
    } catch (const InputError& e) {
        EXPECT_NE(std::string(e.what()).find("sweep_jump.margin_m"), std::string::npos) << e.what();
    }
}

}  // namespace
}  // namespace casmap::pipeline
