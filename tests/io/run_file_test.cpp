#include "casmap/io/run_file.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <fstream>
#include <iterator>
#include <limits>
#include <map>
#include <random>
#include <sstream>
#include <string>

#include "casmap/core/input_error.hpp"
#include "run_file_fixtures.hpp"
#include "tests/temp_dir.hpp"

namespace casmap::io {
namespace {
using test::kDeg;
using test::MakeRun;
using test::Ramp;
using test::ReadBytes;
using test::RunPython;
namespace fs = std::filesystem;

fs::path FreshDir(const std::string& name) { return casmap::test::MakeTempDir("run_file_" + name); }

std::string G(double x) {
    char buffer[64];
    std::snprintf(buffer, sizeof(buffer), "%.17g", x);
    return buffer;
}

bool SameFloat(float a, float b) { return (std::isnan(a) && std::isnan(b)) || a == b; }

void ExpectSameMap(const core::MapF& a, const core::MapF& b) {
    ASSERT_EQ(a.rows, b.rows);
    ASSERT_EQ(a.cols, b.cols);
    for (std::size_t i = 0; i < a.data.size(); ++i) {
        EXPECT_TRUE(SameFloat(a.data[i], b.data[i])) << i;
    }
}

TEST(RunFile, RoundTripKeepsEverything) {
    const fs::path dir = FreshDir("roundtrip");
    const RunData run = MakeRun(9, 181);
    WriteRunFile(dir / "run.h5", run);
    const RunData back = ReadRunFile(dir / "run.h5");

    ASSERT_EQ(back.scans.size(), run.scans.size());
    for (std::size_t i = 0; i < run.scans.size(); ++i) {
        const core::Scan& a = run.scans[i];
        const core::Scan& b = back.scans[i];
        EXPECT_EQ(b.stamp_s, a.stamp_s);
        EXPECT_EQ(b.start_angle_rad, a.start_angle_rad);
        EXPECT_EQ(b.angle_step_rad, a.angle_step_rad);
        EXPECT_EQ(b.beam_period_s, a.beam_period_s);
        ASSERT_EQ(b.beams.size(), a.beams.size());
        for (std::size_t j = 0; j < a.beams.size(); ++j) {
            EXPECT_EQ(b.beams[j].status, a.beams[j].status);
            EXPECT_EQ(b.beams[j].raw, a.beams[j].raw);
            if (a.beams[j].status == core::BeamStatus::kOk) {
                EXPECT_EQ(b.beams[j].range_m, a.beams[j].range_m);
            } else {
                EXPECT_TRUE(std::isnan(b.beams[j].range_m));
            }
        }
        EXPECT_EQ(back.truth[i].labels, run.truth[i].labels);
        for (std::size_t j = 0; j < a.beams.size(); ++j) {
            EXPECT_TRUE(SameFloat(back.truth[i].true_range_m[j], run.truth[i].true_range_m[j]));
        }
    }
    ASSERT_EQ(back.poses.size(), run.poses.size());
    for (std::size_t i = 0; i < run.poses.size(); ++i) {
        const core::TimedPose& a = run.poses.samples()[i];
        const core::TimedPose& b = back.poses.samples()[i];
        EXPECT_EQ(b.stamp_s, a.stamp_s);
        EXPECT_EQ(b.world_T_sensor.translation, a.world_T_sensor.translation);
        EXPECT_NEAR(b.world_T_sensor.rotation.angularDistance(a.world_T_sensor.rotation), 0.0,
                    1e-12);
    }
    EXPECT_EQ(back.seed, run.seed);
    EXPECT_EQ(back.config_yaml, run.config_yaml);
    EXPECT_EQ(back.format, run.format);
    ASSERT_TRUE(back.maps.grid.has_value());
    EXPECT_EQ(*back.maps.grid, *run.maps.grid);
    ExpectSameMap(*back.maps.elevation_m, *run.maps.elevation_m);
    ExpectSameMap(*back.maps.certainty, *run.maps.certainty);
    ExpectSameMap(*back.maps.truth_m, *run.maps.truth_m);
    ASSERT_EQ(back.maps.filtered.size(), 2U);
    ExpectSameMap(back.maps.filtered.at("cas"), run.maps.filtered.at("cas"));
    ExpectSameMap(back.maps.filtered.at("median"), run.maps.filtered.at("median"));
}

TEST(RunFile, RecordedRunWithoutTruthOrMapsRoundTrips) {
    const fs::path dir = FreshDir("recorded");
    RunData run = MakeRun(3, 361);
    run.truth.clear();
    run.maps = RunMaps{};
    run.seed.reset();
    run.format = core::Lms200Format{core::RangeMode::k32m, core::RangeUnits::kCentimetre};
    for (core::Scan& s : run.scans) {  // interleaved 0.5 deg mode: explicit beam times
        s.beam_time_offset_s.assign(361, 0.0);
        for (std::size_t j = 0; j < 361; ++j) {
            s.beam_time_offset_s[j] = static_cast<double>(j % 2) / 75.0 + j * 1e-5;
        }
    }
    WriteRunFile(dir / "rec.h5", run);
    const RunData back = ReadRunFile(dir / "rec.h5");
    EXPECT_TRUE(back.truth.empty());
    EXPECT_TRUE(back.maps.empty());
    EXPECT_FALSE(back.maps.grid.has_value());
    EXPECT_FALSE(back.seed.has_value());
    EXPECT_EQ(back.format, run.format);
    EXPECT_EQ(back.scans.at(2).beam_time_offset_s, run.scans.at(2).beam_time_offset_s);
}

TEST(RunFile, EmptyRunRoundTrips) {
    const fs::path dir = FreshDir("empty");
    WriteRunFile(dir / "empty.h5", RunData{});
    const RunData back = ReadRunFile(dir / "empty.h5");
    EXPECT_TRUE(back.scans.empty());
    EXPECT_TRUE(back.poses.empty());
    EXPECT_EQ(back.config_yaml, "");
}

TEST(RunFile, SameDataGivesByteIdenticalFiles) {
    const fs::path dir = FreshDir("bytes");
    const RunData run = MakeRun(200, 181);  // large enough to be chunked and compressed
    WriteRunFile(dir / "a.h5", run);
    WriteRunFile(dir / "b.h5", ReadRunFile(dir / "a.h5"));
    const std::string a = ReadBytes(dir / "a.h5");
    EXPECT_GT(a.size(), 1000U);
    EXPECT_TRUE(a == ReadBytes(dir / "b.h5")) << "rewriting a read run changed its bytes";
}

// The independent oracle: h5py reads the datasets by the names DESIGN.md gives, checks dtypes
// and shapes, and reports values the C++ side knows.
TEST(RunFile, H5pyReadsTheDesignLayout) {
    const fs::path dir = FreshDir("h5py");
    const RunData run = MakeRun(5, 181);
    WriteRunFile(dir / "run.h5", run);
    const std::string out = RunPython(dir, R"PY(
import h5py, numpy as np
def g(x): return "%.17g" % x
f = h5py.File(")PY" + (dir / "run.h5").string() +
                                               R"PY(", "r")
s = f["scans"]
print("stamp", s["stamp_s"].dtype, s["stamp_s"].shape, g(s["stamp_s"][3]))
print("ranges", s["ranges_m"].dtype, s["ranges_m"].shape, int(np.isnan(s["ranges_m"][()]).sum()))
print("raw", s["raw"].dtype, s["raw"].shape, int(s["raw"][2, 6]))
print("status", s["status"].dtype, s["status"].shape, int(s["status"][()].sum()))
print("labels", s["labels"].dtype, s["labels"].shape, int(s["labels"][()].sum()))
print("range24", g(s["ranges_m"][2, 4]))
p = f["poses"]
print("poses", p["stamp_s"].shape, p["xyz_m"].shape, p["quat_xyzw"].shape,
      g(p["quat_xyzw"][5, 3]), g(p["xyz_m"][7, 0]))
m = f["maps"]
print("maps", m["elevation_m"].dtype, m["elevation_m"].shape, sorted(m["filtered"].keys()),
      g(m["truth_m"][3, 1]), g(m.attrs["cell_m"]), g(m.attrs["origin_y_m"]))
print("attrs", f.attrs["seed"], g(s.attrs["angle_step_rad"]), s.attrs["range_mode"].decode(),
      s.attrs["range_units"].decode())
print("config", f["config_yaml"][()].decode().splitlines()[1], f.attrs["casmap_run_format_version"])
mt = [h5py.h5g.get_objinfo(f.id, n.encode()).mtime
      for n in ["scans", "scans/ranges_m", "poses/xyz_m", "maps/filtered/cas"]]
print("mtime", max(mt))
)PY");
    std::map<std::string, std::string> lines;
    std::istringstream in(out);
    for (std::string line; std::getline(in, line);) {
        lines[line.substr(0, line.find(' '))] = line;
    }
    std::size_t nan_count = 0;
    int status_sum = 0;
    int label_sum = 0;
    for (std::size_t i = 0; i < run.scans.size(); ++i) {
        for (std::size_t j = 0; j < 181; ++j) {
            nan_count += run.scans[i].beams[j].status != core::BeamStatus::kOk;
            status_sum += static_cast<int>(run.scans[i].beams[j].status);
            label_sum += static_cast<int>(run.truth[i].labels[j]);
        }
    }
    const core::Beam& b24 = run.scans[2].beams[4];
    ASSERT_EQ(b24.status, core::BeamStatus::kOk);

    ASSERT_EQ(lines.count("stamp"), 1U) << out;
    EXPECT_EQ(lines["stamp"], "stamp float64 (5,) " + G(run.scans[3].stamp_s));
    EXPECT_EQ(lines["ranges"], "ranges float32 (5, 181) " + std::to_string(nan_count));
    EXPECT_EQ(lines["raw"], "raw uint16 (5, 181) " + std::to_string(run.scans[2].beams[6].raw));
    EXPECT_EQ(lines["status"], "status uint8 (5, 181) " + std::to_string(status_sum));
    EXPECT_EQ(lines["labels"], "labels uint8 (5, 181) " + std::to_string(label_sum));
    EXPECT_EQ(lines["range24"], "range24 " + G(b24.range_m));
    EXPECT_EQ(lines["poses"], "poses (12,) (12, 3) (12, 4) " +
                                  G(run.poses.samples()[5].world_T_sensor.rotation.w()) + " " +
                                  G(run.poses.samples()[7].world_T_sensor.translation.x()));
    EXPECT_EQ(lines["maps"], "maps float32 (4, 3) ['cas', 'median'] " +
                                 G(run.maps.truth_m->at(3, 1)) + " " + G(0.025) + " " + G(-1.0));
    EXPECT_EQ(lines["attrs"], "attrs 18364758544493064720 " + G(1.0 * kDeg) + " 8m mm");
    EXPECT_EQ(lines["config"], "config motion: T 2");
    EXPECT_EQ(lines["mtime"], "mtime 0") << "objects carry timestamps";
}

TEST(RunFile, AddRunMapsKeepsScansAndOtherLayers) {
    const fs::path dir = FreshDir("addmaps");
    RunData run = MakeRun(4, 181);
    const RunMaps maps = run.maps;
    run.maps = RunMaps{};
    WriteRunFile(dir / "run.h5", run);

    RunMaps first;
    first.grid = maps.grid;
    first.elevation_m = maps.elevation_m;
    first.certainty = maps.certainty;
    AddRunMaps(dir / "run.h5", first);
    RunMaps second;
    second.grid = maps.grid;
    second.filtered["cas"] = maps.filtered.at("cas");
    AddRunMaps(dir / "run.h5", second);

    const RunData back = ReadRunFile(dir / "run.h5");
    EXPECT_EQ(back.scans.size(), 4U);
    EXPECT_EQ(back.truth.size(), 4U);
    ExpectSameMap(*back.maps.elevation_m, *maps.elevation_m);
    ExpectSameMap(*back.maps.certainty, *maps.certainty);
    EXPECT_FALSE(back.maps.truth_m.has_value());
    ExpectSameMap(back.maps.filtered.at("cas"), maps.filtered.at("cas"));
    ExpectSameMap(*ReadRunMaps(dir / "run.h5").elevation_m, *maps.elevation_m);

    RunMaps other;
    other.grid = core::GridGeometry{0.0, 0.0, 0.05, 4, 3};
    other.truth_m = maps.truth_m;
    EXPECT_THROW(AddRunMaps(dir / "run.h5", other), InputError);
}

TEST(RunFile, NaNMapsAndNegativeTruthRoundTrip) {
    // Unknown cells as NaN (mapper Unknown::kNaN) and terrain truth below the datum.
    const fs::path dir = FreshDir("nanmaps");
    RunData run = MakeRun(2, 181);
    run.maps.elevation_m->at(0, 0) = std::numeric_limits<float>::quiet_NaN();
    run.maps.truth_m->at(1, 1) = -0.12F;
    WriteRunFile(dir / "run.h5", run);
    const RunData back = ReadRunFile(dir / "run.h5");
    EXPECT_TRUE(std::isnan(back.maps.elevation_m->at(0, 0)));
    EXPECT_EQ(back.maps.truth_m->at(1, 1), -0.12F);
    ExpectSameMap(*back.maps.elevation_m, *run.maps.elevation_m);
}

TEST(RunFile, FailedWriteLeavesNoFileAndKeepsTheOldOne) {
    const fs::path dir = FreshDir("atomic");
    RunData bad = MakeRun(3, 181);
    bad.scans[2].beams.pop_back();
    try {
        WriteRunFile(dir / "run.h5", bad);
        FAIL() << "no error for a short scan";
    } catch (const InputError& e) {
        EXPECT_NE(std::string(e.what()).find("scans[2].beams"), std::string::npos) << e.what();
    }
    EXPECT_TRUE(fs::is_empty(dir)) << "a temporary or partial file was left behind";

    const RunData good = MakeRun(3, 181);
    WriteRunFile(dir / "run.h5", good);
    const std::string before = ReadBytes(dir / "run.h5");
    EXPECT_THROW(WriteRunFile(dir / "run.h5", bad), InputError);
    EXPECT_EQ(ReadBytes(dir / "run.h5"), before);
    EXPECT_EQ(std::distance(fs::directory_iterator(dir), fs::directory_iterator()), 1);
}

// The N x B arrays are filled chunk by chunk (362 scans of float ranges per chunk): three
// chunks, the last one partial, round-trip, and a bad beam in the last chunk still fails the
// whole write naming the beam.
TEST(RunFile, ChunkByChunkArraysRoundTripAndCheckEveryChunk) {
    const fs::path dir = FreshDir("chunks");
    RunData run = MakeRun(800, 181);
    WriteRunFile(dir / "run.h5", run);
    const RunData back = ReadRunFile(dir / "run.h5");
    ASSERT_EQ(back.scans.size(), run.scans.size());
    std::size_t mismatches = 0;
    for (std::size_t i = 0; i < run.scans.size(); ++i) {
        for (std::size_t j = 0; j < 181; ++j) {
            const core::Beam& a = run.scans[i].beams[j];
            const core::Beam& b = back.scans[i].beams[j];
            const bool ok = a.status == core::BeamStatus::kOk;
            mismatches += static_cast<std::size_t>(
                b.status != a.status || b.raw != a.raw ||
                !SameFloat(b.range_m, ok ? a.range_m : std::nanf("")) ||
                back.truth[i].labels[j] != run.truth[i].labels[j] ||
                !SameFloat(back.truth[i].true_range_m[j], run.truth[i].true_range_m[j]));
        }
    }
    EXPECT_EQ(mismatches, 0U);

    run.scans[700].beams[4].status = core::BeamStatus::kOk;
    run.scans[700].beams[4].range_m = std::nanf("");
    const fs::path bad_dir = FreshDir("chunks_bad");
    try {
        WriteRunFile(bad_dir / "run.h5", run);
        FAIL() << "no error for an ok beam without a range";
    } catch (const InputError& e) {
        EXPECT_NE(std::string(e.what()).find("scans[700].beams[4].range_m"), std::string::npos)
            << e.what();
    }
    EXPECT_TRUE(fs::is_empty(bad_dir)) << "a temporary or partial file was left behind";
}

TEST(RunFile, UnwritableDirectoryIsInputError) {
    EXPECT_THROW(WriteRunFile("/nonexistent_casmap_dir/run.h5", RunData{}), InputError);
}

}  // namespace
}  // namespace casmap::io
