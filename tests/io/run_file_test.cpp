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
using test::ReadBytes;
namespace fs = std::filesystem;

constexpr double kDeg = 3.14159265358979323846 / 180.0;
constexpr std::uint32_t kSeed = 20240611;

fs::path FreshDir(const std::string& name) { return casmap::test::MakeTempDir("run_file_" + name); }

/// Runs /usr/bin/python3 (Debian's, with h5py) on `script`; returns stdout.
std::string RunPython(const fs::path& dir, const std::string& script, int* status = nullptr) {
    const fs::path py = dir / "oracle.py";
    std::ofstream(py) << script;
    const std::string cmd = "/usr/bin/python3 " + py.string() + " 2>&1";
    FILE* pipe = popen(cmd.c_str(), "r");
    std::string out;
    char buffer[4096];
    while (pipe != nullptr && fgets(buffer, sizeof(buffer), pipe) != nullptr) {
        out += buffer;
    }
    const int rc = pipe != nullptr ? pclose(pipe) : -1;
    if (status != nullptr) {
        *status = rc;
    }
    return out;
}

core::MapF Ramp(int rows, int cols, float offset) {
    core::MapF map(rows, cols);
    for (int r = 0; r < rows; ++r) {
        for (int c = 0; c < cols; ++c) {
            map.at(r, c) = offset + static_cast<float>(r) * 0.5F - static_cast<float>(c) * 0.25F;
        }
    }
    return map;
}

/// A small run with every feature: statuses, NaNs, labels, true ranges, poses, maps.
RunData MakeRun(std::size_t scans, std::size_t beams) {
    SCOPED_TRACE("seed " + std::to_string(kSeed));
    std::mt19937 rng(kSeed);
    std::uniform_real_distribution<float> range(0.2F, 7.9F);
    std::uniform_int_distribution<int> status(0, core::kBeamStatusCount - 1);
    std::uniform_int_distribution<int> label(0, core::kBeamLabelCount - 1);
    RunData run;
    run.format = core::Lms200Format{core::RangeMode::k8m, core::RangeUnits::kMillimetre};
    run.seed = 0xFEDCBA9876543210ULL;
    run.config_yaml = "scene: course04.yaml\nmotion: T\nspeed_m_s: 1.0\n";
    for (std::size_t i = 0; i < scans; ++i) {
        core::Scan s;
        s.stamp_s = 0.5 + static_cast<double>(i) / 75.0;
        s.start_angle_rad = -90.0 * kDeg;
        s.angle_step_rad = 1.0 * kDeg;
        s.beam_period_s = core::Lms200Timing::kBeamPeriodS;
        core::ScanTruth t;
        for (std::size_t j = 0; j < beams; ++j) {
            core::Beam b;
            b.status =
                (j % 3 == 0) ? static_cast<core::BeamStatus>(status(rng)) : core::BeamStatus::kOk;
            b.range_m = range(rng);
            b.raw = b.status == core::BeamStatus::kOk ? run.format->EncodeRange(b.range_m)
                                                      : run.format->CodeFor(b.status);
            s.beams.push_back(b);
            t.labels.push_back(static_cast<core::BeamLabel>(label(rng)));
            t.true_range_m.push_back(j % 7 == 0 ? std::nanf("") : b.range_m + 0.01F);
        }
        run.scans.push_back(s);
        run.truth.push_back(t);
    }
    std::vector<core::TimedPose> poses;
    for (int i = 0; i < 12; ++i) {
        poses.push_back(
            {0.4 + 0.001 * i,
             core::PoseFromXyzRpy({0.001 * i, 0.3, 0.8}, {0.01 * i, 30 * kDeg + 0.02 * i, 0.0})});
    }
    run.poses = core::Trajectory(poses);
    run.maps.grid = core::GridGeometry{0.25, -1.0, 0.025, 4, 3};
    run.maps.elevation_m = Ramp(4, 3, 0.1F);
    run.maps.certainty = Ramp(4, 3, 2.0F);
    run.maps.truth_m = Ramp(4, 3, 0.0F);
    run.maps.filtered["cas"] = Ramp(4, 3, -0.1F);
    run.maps.filtered["median"] = Ramp(4, 3, -0.2F);
    return run;
}

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

void ExpectReadError(const fs::path& file, const std::string& needle) {
    try {
        (void)ReadRunFile(file);
        ADD_FAILURE() << "no error reading " << file;
    } catch (const InputError& e) {
        const std::string what = e.what();
        EXPECT_NE(what.find(file.string()), std::string::npos) << what;
        EXPECT_NE(what.find(needle), std::string::npos) << what;
    }
}

TEST(RunFile, ReaderRejectsBadFilesNamingFileAndDataset) {
    const fs::path dir = FreshDir("bad");
    ExpectReadError(dir / "missing.h5", "does not exist");
    std::ofstream(dir / "text.h5") << "not hdf5\n";
    ExpectReadError(dir / "text.h5", "not a readable HDF5 file");

    WriteRunFile(dir / "good.h5", MakeRun(3, 181));
    // Each case copies the good file and breaks one thing with h5py.
    int rc = 0;
    const std::string out = RunPython(dir, R"PY(
import h5py, numpy as np, shutil
d = ")PY" + dir.string() + R"PY("
def case(name, fn):
    shutil.copy(d + "/good.h5", d + "/" + name + ".h5")
    with h5py.File(d + "/" + name + ".h5", "r+") as f:
        fn(f)
def short_raw(f):
    del f["scans/raw"]; f["scans/raw"] = np.zeros((3, 180), np.uint16)
def float_status(f):
    del f["scans/status"]; f["scans/status"] = np.zeros((3, 181), np.float32)
def bad_status(f):
    f["scans/status"][1, 7] = 9
def bad_label(f):
    f["scans/labels"][0, 3] = 6
def no_angle(f):
    del f["scans"].attrs["angle_step_rad"]
def no_poses(f):
    del f["poses/quat_xyzw"]
def bad_quat(f):
    f["poses/quat_xyzw"][2] = [0, 0, 0, 2]
def backwards(f):
    f["poses/stamp_s"][3] = 0.0
def ok_nan(f):
    s = f["scans/status"][()]; r = f["scans/ranges_m"][()]
    i = np.argwhere(s == 0)[0]; r[i[0], i[1]] = np.nan; f["scans/ranges_m"][...] = r
def map_shape(f):
    del f["maps/certainty"]; f["maps/certainty"] = np.zeros((3, 4), np.float32)
def mode(f):
    f["scans"].attrs["range_mode"] = "80m"
for name, fn in list(globals().items()):
    if callable(fn) and name not in ("case",) and fn.__module__ == "__main__":
        case(name, fn)
print("ok")
)PY",
                                      &rc);
    ASSERT_EQ(rc, 0) << out;
    ExpectReadError(dir / "short_raw.h5", "/scans/raw");
    ExpectReadError(dir / "float_status.h5", "/scans/status = float");
    ExpectReadError(dir / "bad_status.h5", "/scans/status[1, 7] = 9");
    ExpectReadError(dir / "bad_label.h5", "/scans/labels[0, 3] = 6");
    ExpectReadError(dir / "no_angle.h5", "/scans attribute angle_step_rad");
    ExpectReadError(dir / "no_poses.h5", "/poses/quat_xyzw (required dataset is missing)");
    ExpectReadError(dir / "bad_quat.h5", "/poses/quat_xyzw[2]");
    ExpectReadError(dir / "backwards.h5", "/poses/stamp_s");
    ExpectReadError(dir / "ok_nan.h5", "/scans/ranges_m[");
    ExpectReadError(dir / "map_shape.h5", "/maps/certainty");
    ExpectReadError(dir / "mode.h5", "range_mode = 80m");
}

// A file made by another tool with only DESIGN.md's datasets and the scan-angle attributes
// (no casmap version, no maps, no labels) is a valid recorded run.
TEST(RunFile, ReadsAMinimalThirdPartyFile) {
    const fs::path dir = FreshDir("third_party");
    int rc = 0;
    const std::string out = RunPython(dir,
                                      R"PY(
import h5py, numpy as np
with h5py.File(")PY" + (dir / "min.h5").string() +
                                          R"PY(", "w") as f:
    f["scans/stamp_s"] = np.array([0.0, 1 / 75])
    r = np.full((2, 181), 2.0, np.float32); r[1, 5] = np.nan
    f["scans/ranges_m"] = r
    f["scans/raw"] = np.full((2, 181), 2000, np.uint16)
    s = np.zeros((2, 181), np.uint8); s[1, 5] = 1
    f["scans/status"] = s
    f["scans"].attrs["start_angle_rad"] = -np.pi / 2
    f["scans"].attrs["angle_step_rad"] = np.pi / 180
    f["scans"].attrs["beam_period_s"] = 1 / 75 / 360
    f["poses/stamp_s"] = np.array([0.0, 1.0])
    f["poses/xyz_m"] = np.zeros((2, 3))
    f["poses/quat_xyzw"] = np.array([[0, 0, 0, 1.0], [0, 0, 0, 1.0]])
print("ok")
)PY",
                                      &rc);
    ASSERT_EQ(rc, 0) << out;
    const RunData run = ReadRunFile(dir / "min.h5");
    ASSERT_EQ(run.scans.size(), 2U);
    EXPECT_EQ(run.scans[1].beams[5].status, core::BeamStatus::kNoReturn);
    EXPECT_FLOAT_EQ(run.scans[1].beams[4].range_m, 2.0F);
    EXPECT_NEAR(run.scans[0].BeamAngle(180), 90 * kDeg, 1e-12);
    EXPECT_TRUE(run.truth.empty());
    EXPECT_EQ(run.poses.size(), 2U);
}

}  // namespace
}  // namespace casmap::io
