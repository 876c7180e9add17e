// The live session's streaming stages (pipeline/live.hpp): a session with the consensus mapper
// and the sweep_jump pre-filter over a run, from a source handing out its scans as fast as the
// session takes them, against the offline path over the same scans and poses (the run's
// sweep_jump labels, then TerrainMapper in consensus mode on the window's lattice, then CAS):
// every filtered row's cells bit for bit. And the setup's checks of the new options.
#include <gtest/gtest.h>

#include <atomic>
#include <bit>
#include <fstream>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include "casmap/core/input_error.hpp"
#include "casmap/mapper/filters.hpp"
#include "casmap/mapper/sweep_jump.hpp"
#include "casmap/mapper/synthetic_scans.hpp"
#include "casmap/mapper/terrain_mapper.hpp"
#include "casmap/pipeline/live.hpp"
#include "casmap/pipeline/live_setup.hpp"
#include "tests/temp_dir.hpp"

namespace casmap::pipeline {
namespace {

// The scans of a run, one per Next(), then finished.
class RunSource final : public LiveScanSource {
public:
    explicit RunSource(std::vector<core::Scan> scans) : scans_(std::move(scans)) {}
    std::optional<core::Scan> Next(double /*timeout_s*/) override {
        return next_ < scans_.size() ? std::optional<core::Scan>(scans_[next_++]) : std::nullopt;
    }
    bool finished() const override { return next_ == scans_.size(); }
    std::string name() const override { return "test run"; }

private:
    std::vector<core::Scan> scans_;
    std::size_t next_ = 0;
};

// The paper vehicle at 1 m/s past three boxes: mixed pixels across scans at the boxes' far
// edges (what sweep_jump removes), in-scan spikes (what CAS removes), 1 cm range noise (so
// consensus means differ from Eq. 6's heights).
mapper::SyntheticRun MixedRun() {
    mapper::SyntheticDrive d;
    d.duration_s = 4.0;
    d.boxes = {
        {4.0, 4.3, -0.4, -0.1, 0.25}, {4.6, 4.8, 0.3, 0.9, 0.15}, {5.5, 5.9, -1.2, -0.7, 0.2}};
    d.spike_every = 37;
    d.mixed_far_edges = true;
    d.range_noise_m = 0.01;
    return mapper::BuildSyntheticRun(d);
}

std::string ReadText(const std::filesystem::path& p) {
    std::ifstream in(p);
    std::stringstream s;
    s << in.rdbuf();
    return s.str();
}

TEST(LiveStages, ConsensusAndSweepJumpSessionIsTheOfflinePathBitForBit) {
    const mapper::SyntheticRun run = MixedRun();
    const test::TempDir dir("live_stages");
    LiveConfig cfg;
    cfg.out_dir = dir.Path();
    cfg.snapshot_every_s = 0.0;
    cfg.window.origin_x_m = -2.0;
    cfg.window.origin_y_m = -6.0;
    cfg.window.consensus = mapper::ConsensusConfig{0.02, 2};
    cfg.prefilter = Prefilter::kSweepJump;
    std::vector<mapper::FilteredRow> rows;
    cfg.on_row = [&](const mapper::FilteredRow& r) { rows.push_back(r); };
    RunSource source(run.scans);
    TrajectoryPoseStream poses(run.poses);
    const std::atomic<bool> stop{false};
    const LiveResult live = RunLive(cfg, source, poses, stop, {});
    ASSERT_EQ(live.status.scans_mapped, run.scans.size());
    ASSERT_EQ(live.window.turns, 0U);

    // Offline: the whole run's labels, then the consensus mapper on the window's lattice.
    const auto labels = mapper::SweepJumpLabels(run.scans, run.poses, cfg.sweep_jump);
    mapper::TerrainMapperConfig mc;
    mc.grid = core::GridGeometry{-2.0, -6.0, 0.025, 520, 480};
    mc.consensus = cfg.window.consensus;
    mapper::TerrainMapper offline(mc);
    for (std::size_t k = 0; k < run.scans.size(); ++k) {
        offline.AddScan(run.scans[k], run.poses, labels[k]);
    }
    const mapper::FilterResult full =
        mapper::CasFilter(offline.elevation(), offline.certainty(), cfg.window.cas);
    ASSERT_GT(rows.size(), 100U);
    std::size_t compared = 0;
    for (const mapper::FilteredRow& r : rows) {
        for (std::size_t j = 2; j + 2 < r.elevation.size(); ++j) {
            const std::int64_t b = r.first_col + static_cast<std::int64_t>(j);
            ASSERT_GE(r.row, 2);
            ASSERT_LT(r.row, mc.grid.rows - 2);
            if (b < 2 || b >= mc.grid.cols - 2) {
                continue;
            }
            const int ri = static_cast<int>(r.row);
            const int bi = static_cast<int>(b);
            ASSERT_EQ(std::bit_cast<std::uint32_t>(r.raw[j]),
                      std::bit_cast<std::uint32_t>(offline.elevation().at(ri, bi)))
                << ri << "," << bi;
            ASSERT_EQ(r.certainty[j], offline.certainty().at(ri, bi)) << ri << "," << bi;
            ASSERT_EQ(std::bit_cast<std::uint32_t>(r.elevation[j]),
                      std::bit_cast<std::uint32_t>(full.elevation.at(ri, bi)))
                << ri << "," << bi;
            ASSERT_EQ(r.classes[j], full.classes.at(ri, bi));
            ++compared;
        }
    }
    EXPECT_GT(compared, 40000U);
    // The rejected beams are counted, in the result, status.json and the effective config.
    EXPECT_EQ(live.status.beams_rejected, offline.stats().beams_rejected);
    EXPECT_GT(live.status.beams_rejected, 20U);
    EXPECT_EQ(live.window.beams.beams_rejected, live.status.beams_rejected);
    const std::string status = ReadText(dir.Path() / "status.json");
    EXPECT_NE(status.find("\"beams_rejected\": " + std::to_string(live.status.beams_rejected)),
              std::string::npos)
        << status;
    const std::string config = ReadText(dir.Path() / "config.yaml");
    EXPECT_NE(config.find("mode: consensus"), std::string::npos) << config;
    EXPECT_NE(config.find("prefilter: sweep_jump"), std::string::npos) << config;
    EXPECT_NE(config.find("consensus: {spread_m: 0.02, min_hits: 2}"), std::string::npos) << config;
    EXPECT_NE(config.find("sweep_jump: {jump_min_m: 0.1,"), std::string::npos) << config;
    EXPECT_NE(LiveSummaryJson(live).find("\"beams_rejected\": "), std::string::npos);
}

TEST(LiveStages, PaperSessionWritesNoStageSections) {
    const mapper::SyntheticRun run = MixedRun();
    const test::TempDir dir("live_paper");
    LiveConfig cfg;
    cfg.out_dir = dir.Path();
    cfg.snapshot_every_s = 0.0;
    cfg.max_scans = 30;
    RunSource source(run.scans);
    TrajectoryPoseStream poses(run.poses);
    const std::atomic<bool> stop{false};
    const LiveResult live = RunLive(cfg, source, poses, stop, {});
    EXPECT_EQ(live.status.beams_rejected, 0U);
    const std::string config = ReadText(dir.Path() / "config.yaml");
    EXPECT_NE(config.find("mode: paper, prefilter: none"), std::string::npos) << config;
    EXPECT_EQ(config.find("consensus:"), std::string::npos) << config;
    EXPECT_EQ(config.find("sweep_jump:"), std::string::npos) << config;
}

LiveOptions DeviceOptions() {
    LiveOptions o;
    o.device = "/dev/null";
    o.poses = "poses.txt";
    o.out = "unused";
    return o;
}

// MakeLiveSetup's error for `o`: the field it names ("" if it accepted `o`).
std::string ErrorField(const LiveOptions& o) {
    try {
        (void)MakeLiveSetup(o, 1);
    } catch (const InputError& e) {
        return e.field();
    }
    return "";
}

TEST(LiveStages, SetupTakesTheStagesAndNamesEachBadField) {
    LiveOptions o = DeviceOptions();
    o.mapper = "consensus";
    o.prefilter = "sweep_jump";
    o.cas = {"consensus.spread_m=0.03", "sweep_jump.reach=2", "k=2"};
    const LiveSetup s = MakeLiveSetup(o, 1);
    ASSERT_TRUE(s.config.window.consensus.has_value());
    EXPECT_EQ(s.config.window.consensus->spread_m, 0.03);
    EXPECT_EQ(s.config.prefilter, Prefilter::kSweepJump);
    EXPECT_EQ(s.config.sweep_jump.reach, 2);
    EXPECT_FALSE(MakeLiveSetup(DeviceOptions(), 1).config.window.consensus.has_value());

    LiveOptions bad = DeviceOptions();
    bad.mapper = "kalman";
    EXPECT_EQ(ErrorField(bad), "mapper");
    bad.mapper = "median";
    EXPECT_EQ(ErrorField(bad), "mapper");
    bad = DeviceOptions();
    bad.prefilter = "shadow";
    EXPECT_EQ(ErrorField(bad), "prefilter");
    bad = DeviceOptions();
    bad.cas = {"sweep_jump.reach=2"};  // the pre-filter is none
    EXPECT_EQ(ErrorField(bad), "set");
    bad.cas = {"consensus.min_hits=3"};  // the mapper is paper
    EXPECT_EQ(ErrorField(bad), "set");
    bad.cas = {"kalman.range_sigma_m=0.01"};
    EXPECT_EQ(ErrorField(bad), "set");
    bad.prefilter = "sweep_jump";
    bad.mapper = "consensus";
    bad.cas = {"sweep_jump.reach=7"};
    EXPECT_EQ(ErrorField(bad), "sweep_jump.reach");
    bad.cas = {"consensus.spread_m=-1"};
    EXPECT_EQ(ErrorField(bad), "consensus.spread_m");
    bad.cas = {"consensus.min_hits=1"};
    EXPECT_EQ(ErrorField(bad), "consensus.min_hits");
}

}  // namespace
}  // namespace casmap::pipeline
