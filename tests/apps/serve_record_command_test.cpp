// `casmap serve --run` and `casmap record` as processes talking through a pseudo-terminal:
// every recorded scan equals the served one value for value, the JSON line is complete, a map
// of a served-and-recorded run equals the map of the same run made directly, and bad input
// ends with exit 2 and no run file.
#include <gtest/gtest.h>
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <map>
#include <numbers>
#include <string>
#include <thread>

#include "casmap/core/grid.hpp"
#include "casmap/core/pose.hpp"
#include "casmap/io/image.hpp"
#include "casmap/io/run_file.hpp"

extern char** environ;

#include "tests/apps/cli_runner.hpp"

namespace casmap {
namespace {
namespace fs = std::filesystem;

using test::Casmap;
using test::Result;

/// A run of `count` 181-beam scans in mm; beam 0 of scan i holds i mm, so scans name themselves.
io::RunData NumberedRun(int count) {
    io::RunData run;
    const core::Lms200Format mm{};
    for (int i = 0; i < count; ++i) {
        core::Scan s;
        s.stamp_s = i / 75.0;
        s.start_angle_rad = -std::numbers::pi / 2;
        s.angle_step_rad = std::numbers::pi / 180.0;
        s.beam_period_s = (1.0 / 75.0) / 360.0;
        s.beams.resize(181);
        for (int b = 0; b < 181; ++b) {
            const auto raw = static_cast<std::uint16_t>(b == 0 ? i : (i * 37 + b * 101) % 8190);
            s.beams[static_cast<std::size_t>(b)] = mm.Decode(raw);
        }
        run.scans.push_back(s);
    }
    run.format = mm;
    return run;
}

constexpr double kDeg = std::numbers::pi / 180.0;

/// Exact range along a ray to the floor z = 0.1 x (a ramp, so that every scan's ranges differ)
/// or the flat top of one of two blocks (x 1.0..1.3, y -0.2..0.2, top z = 0.35; x 1.6..1.8,
/// y -0.6..-0.1, top z = 0.3); NaN if the ray does not hit the floor.
double RangeToScene(const Eigen::Vector3d& o, const Eigen::Vector3d& d) {
    constexpr double kSlope = 0.1;
    const double denom = d.z() - kSlope * d.x();
    if (denom >= -1e-9) {
        return std::nan("");
    }
    struct Block {
        double x0, x1, y0, y1, top;
    };
    for (const Block& b : {Block{1.0, 1.3, -0.2, 0.2, 0.35}, Block{1.6, 1.8, -0.6, -0.1, 0.3}}) {
        const double t = (b.top - o.z()) / d.z();
        const Eigen::Vector3d p = o + t * d;
        if (t > 0.0 && p.x() >= b.x0 && p.x() <= b.x1 && p.y() >= b.y0 && p.y() <= b.y1) {
            return t;
        }
    }
    return (kSlope * o.x() - o.z()) / denom;
}

/// The simulated run: the sensor 0.5 m high, pitched 40 deg down, moving along x at 1 m/s
/// (x = -0.5 + t) for 4 s, 75 scans/s of 181 beams in mm, each beam's range the exact range
/// at its own time (as the simulator does), poses at 1 kHz.
io::RunData FloorRun(int count) {
    io::RunData run;
    run.format = core::Lms200Format{};
    std::vector<core::TimedPose> poses;
    for (int i = 0; i <= (count + 10) * 1000 / 75; ++i) {
        const double t = i * 0.001;
        poses.push_back({t, core::PoseFromXyzRpy({-0.5 + t, 0.0, 0.5}, {0.0, 40 * kDeg, 0.0})});
    }
    run.poses = core::Trajectory(poses);
    for (int k = 0; k < count; ++k) {
        core::Scan s;
        s.stamp_s = 0.01 + k / 75.0;
        s.start_angle_rad = -90 * kDeg;
        s.angle_step_rad = 1 * kDeg;
        s.beam_period_s = core::Lms200Timing::kBeamPeriodS;
        for (std::size_t i = 0; i < 181; ++i) {
            const core::Pose pose = *run.poses.PoseAt(s.BeamTime(i));
            const double a = s.BeamAngle(i);
            const Eigen::Vector3d d = pose.rotation * Eigen::Vector3d(std::cos(a), std::sin(a), 0);
            const double r = RangeToScene(pose.translation, d);
            core::Beam b;
            if (std::isfinite(r) && r < 8.0) {
                b.status = core::BeamStatus::kOk;
                b.raw = run.format->EncodeRange(r);
                b.range_m = run.format->Decode(b.raw).range_m;  // what the telegram carries
            } else {
                b.status = core::BeamStatus::kNoReturn;
                b.raw = run.format->CodeFor(b.status);
            }
            s.beams.push_back(b);
        }
        run.scans.push_back(s);
    }
    return run;
}

/// Index of the served scan whose raw values `s` carries (on the ramp every scan's values
/// differ); -1 if none, -2 if several.
int ServedIndex(const io::RunData& served, const core::Scan& s) {
    int found = -1;
    for (std::size_t k = 0; k < served.scans.size(); ++k) {
        const std::vector<core::Beam>& b = served.scans[k].beams;
        if (b.size() == s.beams.size() &&
            std::equal(b.begin(), b.end(), s.beams.begin(),
                       [](const core::Beam& x, const core::Beam& y) { return x.raw == y.raw; })) {
            if (found >= 0) {
                return -2;
            }
            found = static_cast<int>(k);
        }
    }
    return found;
}

constexpr core::GridGeometry kGrid{0.0, -1.5, 0.025, 100, 120};  // x 0..2.5, y -1.5..1.5

/// Cell of beam i of `s` placed with `poses` at the beam's time (as the mapper places it).
std::optional<core::Cell> BeamCell(const core::Scan& s,
                                   std::size_t i,
                                   const core::Trajectory& poses) {
    const std::optional<core::Pose> pose = poses.PoseAt(s.BeamTime(i));
    if (!pose || s.beams[i].status != core::BeamStatus::kOk) {
        return std::nullopt;
    }
    const double a = s.BeamAngle(i);
    const double r = s.beams[i].range_m;
    const Eigen::Vector3d p =
        pose->rotation * Eigen::Vector3d(r * std::cos(a), r * std::sin(a), 0) + pose->translation;
    return kGrid.CellOf(p.x(), p.y());
}

struct MapDiff {
    int seen = 0;         // cells seen in either map
    int certainty = 0;    // cells whose certainty (beam count) differs
    int elevation = 0;    // cells seen in both whose elevation differs by more than 1e-4 m
    int unexplained = 0;  // differing cells no moved beam touches (must be 0)
};

/// Compares the maps; a difference is explained if the cell is in `moved` (a beam that the
/// stamp error put into another cell left or entered it) or next to one (the mapper's filter
/// looks at a cell's 8 neighbours).
MapDiff CompareMaps(const fs::path& a, const fs::path& b, const std::vector<char>& moved) {
    const core::MapF ha = io::ReadMapTiff(a / "elevation.tiff");
    const core::MapF hb = io::ReadMapTiff(b / "elevation.tiff");
    const core::MapF ca = io::ReadMapTiff(a / "certainty.tiff");
    const core::MapF cb = io::ReadMapTiff(b / "certainty.tiff");
    MapDiff d;
    for (int row = 0; row < kGrid.rows; ++row) {
        for (int col = 0; col < kGrid.cols; ++col) {
            const float h0 = ha.at(row, col);
            const float h1 = hb.at(row, col);
            const float c0 = ca.at(row, col);
            const float c1 = cb.at(row, col);
            d.seen += c0 > 0.0F || c1 > 0.0F ? 1 : 0;
            const bool dc = c0 != c1;
            const bool dh = c0 > 0.0F && c1 > 0.0F && !(std::abs(h0 - h1) <= 1e-4F);
            d.certainty += dc ? 1 : 0;
            d.elevation += dh ? 1 : 0;
            if (!dc && !dh) {
                continue;
            }
            bool near_moved = false;
            for (int dr = -1; dr <= 1; ++dr) {
                for (int dcol = -1; dcol <= 1; ++dcol) {
                    const int r = row + dr;
                    const int c = col + dcol;
                    if (r >= 0 && c >= 0 && r < kGrid.rows && c < kGrid.cols &&
                        moved[static_cast<std::size_t>(r * kGrid.cols + c)] != 0) {
                        near_moved = near_moved || ((dr == 0 && dcol == 0) || !dc);
                    }
                }
            }
            d.unexplained += near_moved ? 0 : 1;
        }
    }
    return d;
}

class ServeRecordCommand : public ::testing::Test {
protected:
    void SetUp() override {
        dir_ = fs::path(testing::TempDir()) / ("casmap_serve_record_" + std::to_string(getpid()));
        fs::remove_all(dir_);
        fs::create_directories(dir_);
    }
    void TearDown() override {
        StopServe();
        fs::remove_all(dir_);
    }
    void StartServe(const std::vector<std::string>& args) {
        std::vector<std::string> argv_s{CASMAP_EXE, "serve"};
        argv_s.insert(argv_s.end(), args.begin(), args.end());
        std::vector<char*> argv;
        for (std::string& a : argv_s) {
            argv.push_back(a.data());
        }
        argv.push_back(nullptr);
        ASSERT_EQ(posix_spawn(&serve_pid_, CASMAP_EXE, nullptr, nullptr, argv.data(), environ), 0);
    }
    void StopServe() {
        if (serve_pid_ > 0) {
            kill(serve_pid_, SIGINT);
            int status = 0;
            waitpid(serve_pid_, &status, 0);
            serve_pid_ = -1;
        }
    }
    bool WaitForLink(const fs::path& link) {
        for (int i = 0; i < 200; ++i) {
            if (fs::is_symlink(link)) {
                return true;
            }
            std::this_thread::sleep_for(std::chrono::milliseconds(10));
        }
        return false;
    }
    fs::path dir_;
    pid_t serve_pid_ = -1;
};

TEST_F(ServeRecordCommand, RecordedScansEqualTheServedOnes) {
    const io::RunData served = NumberedRun(200);
    io::WriteRunFile(dir_ / "served.h5", served);
    const fs::path link = dir_ / "lms";
    StartServe({"--run", (dir_ / "served.h5").string(), "--link", link.string()});
    ASSERT_TRUE(WaitForLink(link));
    const fs::path out = dir_ / "rec.h5";
    const Result r = Casmap("record --device " + link.string() +
                            " --baud 500000 --scans 30 --timeout 5 --out " + out.string());
    ASSERT_EQ(r.code, 0) << r.output;
    for (const char* key : {"\"scans\": 30", "\"bytes\": ", "\"crc_errors\": 0",
                            "\"resyncs\": ", "\"reconnects\": 0", "\"scans_per_second\": "}) {
        EXPECT_NE(r.output.find(key), std::string::npos) << key << " in " << r.output;
    }
    const io::RunData rec = io::ReadRunFile(out);
    ASSERT_EQ(rec.scans.size(), 30U);
    ASSERT_TRUE(rec.format.has_value());
    for (const core::Scan& s : rec.scans) {
        const std::size_t index = s.beams.at(0).raw;
        ASSERT_LT(index, served.scans.size());
        const core::Scan& want = served.scans[index];
        for (std::size_t b = 0; b < s.beams.size(); ++b) {
            EXPECT_EQ(s.beams[b].raw, want.beams[b].raw) << "scan " << index << " beam " << b;
            EXPECT_EQ(s.beams[b].status, want.beams[b].status);
        }
        EXPECT_NEAR(s.angle_step_rad, want.angle_step_rad, 1e-12);
    }
}

// The map test: at 500000 baud the scan clock stamps every scan on the sweep grid, so
// the recorded run (poses from serve --poses-out, in the recorder's clock) maps like the
// simulated one. Set CASMAP_RECORD_STAMPS=arrival to measure the per-scan latency correction
// instead (the assertions then fail: 0.7 ms mean jitter moves hundreds of cells).
TEST_F(ServeRecordCommand, MapOfARecordedRunEqualsTheDirectMapAt500000) {
    const io::RunData served = FloorRun(300);
    io::WriteRunFile(dir_ / "served.h5", served);
    const fs::path link = dir_ / "lms";
    const fs::path poses = dir_ / "poses.txt";
    // The scanner's EEPROM has real-time indices on (availability bit 1): the driver then knows
    // each scan's sweep slot from the scanner, so a stalled process on a loaded machine cannot
    // put a scan into the wrong slot (without them, a stall of more than 10 ms can: about 1
    // run in 4 with seven builds on two cores). The stamps still come from the arrival times.
    // (The EEPROM file format of docs/commands/serve.md: the 34 configuration bytes in hex;
    // byte 4 availability = 0x02, byte 6 units = 1 mm.)
    {
        std::FILE* f = std::fopen((dir_ / "eeprom.txt").c_str(), "w");
        ASSERT_NE(f, nullptr);
        std::fputs("# virtual LMS 200 EEPROM\nconfig: 00 00 00 00 02 00 01", f);
        for (int i = 7; i < 34; ++i) {
            std::fputs(" 00", f);
        }
        std::fputs("\n", f);
        std::fclose(f);
    }
    StartServe({"--run", (dir_ / "served.h5").string(), "--link", link.string(), "--poses-out",
                poses.string(), "--eeprom", (dir_ / "eeprom.txt").string()});
    ASSERT_TRUE(WaitForLink(link));
    const char* mode = std::getenv("CASMAP_RECORD_STAMPS");
    const std::string stamps = mode != nullptr ? mode : "scan-clock";
    const fs::path rec_path = dir_ / "rec.h5";
    const Result r = Casmap("record --device " + link.string() +
                            " --baud 500000 --scans 120 --timeout 5 --stamps " + stamps +
                            " --poses " + poses.string() + " --out " + rec_path.string());
    ASSERT_EQ(r.code, 0) << r.output;
    StopServe();
    const io::RunData rec = io::ReadRunFile(rec_path);
    ASSERT_EQ(rec.scans.size(), 120U);
    ASSERT_FALSE(rec.poses.empty());

    // The same scans straight from the simulated run, with its own stamps and poses.
    io::RunData direct;
    direct.format = served.format;
    direct.poses = served.poses;
    const double offset_s = rec.poses.StartTime() - served.poses.StartTime();
    double sum_abs = 0.0;
    double max_abs = 0.0;
    double mean = 0.0;
    for (const core::Scan& s : rec.scans) {
        const int k = ServedIndex(served, s);
        ASSERT_GE(k, 0) << "a recorded scan that was never served, or ambiguous: " << k;
        direct.scans.push_back(served.scans[static_cast<std::size_t>(k)]);
        const double e = (s.stamp_s - offset_s) - direct.scans.back().stamp_s;
        sum_abs += std::abs(e);
        mean += e;
        max_abs = std::max(max_abs, std::abs(e));
    }
    const double n = static_cast<double>(rec.scans.size());
    std::printf("stamps (%s): error mean %.1f us, mean |e| %.1f us, max |e| %.1f us\n",
                stamps.c_str(), mean / n * 1e6, sum_abs / n * 1e6, max_abs * 1e6);
    io::WriteRunFile(dir_ / "direct.h5", direct);

    // The cells the measured stamp errors can change: those a beam leaves or enters when it
    // is placed at its recorded time instead of its simulated one.
    std::vector<char> moved(static_cast<std::size_t>(kGrid.rows * kGrid.cols), 0);
    int moved_beams = 0;
    double expected_moves = 0.0;
    for (std::size_t j = 0; j < rec.scans.size(); ++j) {
        for (std::size_t i = 0; i < rec.scans[j].beams.size(); ++i) {
            const std::optional<core::Cell> c0 = BeamCell(direct.scans[j], i, direct.poses);
            const std::optional<core::Cell> c1 = BeamCell(rec.scans[j], i, rec.poses);
            if (c0) {
                expected_moves +=
                    std::abs(rec.scans[j].stamp_s - offset_s - direct.scans[j].stamp_s) /
                    kGrid.cell_m;  // 1 m/s
            }
            if (c0.has_value() != c1.has_value() ||
                (c0 && (c0->row != c1->row || c0->col != c1->col))) {
                ++moved_beams;
                for (const std::optional<core::Cell>& c : {c0, c1}) {
                    if (c) {
                        moved[static_cast<std::size_t>(c->row * kGrid.cols + c->col)] = 1;
                    }
                }
            }
        }
    }

    const std::string grid = " --grid 0,-1.5,0.025,100,120 --threads 1";
    Result m = Casmap("map " + (dir_ / "direct.h5").string() + grid + " --out " +
                      (dir_ / "direct_maps").string());
    ASSERT_EQ(m.code, 0) << m.output;
    m = Casmap("map " + rec_path.string() + grid + " --out " + (dir_ / "rec_maps").string());
    ASSERT_EQ(m.code, 0) << m.output;
    const MapDiff d = CompareMaps(dir_ / "direct_maps", dir_ / "rec_maps", moved);
    std::printf(
        "maps: %d cells seen, %d differ in certainty, %d in elevation; %d of %zu beams change "
        "cell through the stamp error (%.1f expected)\n",
        d.seen, d.certainty, d.elevation, moved_beams, rec.scans.size() * 181, expected_moves);
    EXPECT_GT(d.seen, 4000);
    // Exact stamps would give identical maps. The scan clock leaves the host's minimum read
    // latency (a few to tens of microseconds: tens of micrometres at 1 m/s), which carries a
    // beam across a cell edge only when it ends that close to one. Every differing cell must
    // be one such a beam left or entered (or, for the elevation, next to one).
    EXPECT_EQ(d.unexplained, 0);
    EXPECT_LE(d.certainty, 2 * moved_beams);
    // A beam of scan j moves by v |e_j| along x (v = 1 m/s), so it changes cell with
    // probability v |e_j| / 25 mm: the moved beams must not exceed 3x that expectation + 3.
    EXPECT_LE(moved_beams, 3.0 * expected_moves + 3.0) << expected_moves;
    // The stamps themselves: on the sweep grid, within 1 ms of the simulated ones (typically
    // 2-60 us; the first 8 scans carry the warm-up envelope, a few hundred us when the machine
    // stalled the processes at start-up).
    EXPECT_LT(max_abs, 1e-3);
}

TEST_F(ServeRecordCommand, BadInputIsExitTwoWithoutARunFile) {
    const fs::path out = dir_ / "rec.h5";
    // An absent device is retried with back-off until --timeout, then named.
    Result r = Casmap("record --device /nonexistent/ttyX --timeout 1 --out " + out.string());
    EXPECT_EQ(r.code, 2) << r.output;
    EXPECT_NE(r.output.find("/nonexistent/ttyX"), std::string::npos) << r.output;
    EXPECT_NE(r.output.find("attempts"), std::string::npos) << r.output;
    r = Casmap("record --device /dev/null --out " + out.string());
    EXPECT_EQ(r.code, 2) << r.output;
    EXPECT_NE(r.output.find("not a terminal"), std::string::npos) << r.output;
    r = Casmap("record --device /dev/null --baud 57600 --out " + out.string());
    EXPECT_EQ(r.code, 2) << r.output;
    EXPECT_NE(r.output.find("--baud = 57600"), std::string::npos) << r.output;
    r = Casmap("serve --run " + (dir_ / "missing.h5").string());
    EXPECT_EQ(r.code, 2) << r.output;
    r = Casmap("serve --run x.h5 --faults crc=7");
    EXPECT_EQ(r.code, 2) << r.output;
    EXPECT_NE(r.output.find("crc"), std::string::npos) << r.output;
    EXPECT_FALSE(fs::exists(out));
}

// Issue #13 item 2: every input is checked before connecting (no device is needed to see
// these errors, and they come at once even with a long --timeout).
TEST_F(ServeRecordCommand, RecordChecksItsInputsBeforeConnecting) {
    const std::string device = " --device /nonexistent/ttyX --timeout 60";
    const auto started = std::chrono::steady_clock::now();
    Result r = Casmap("record" + device + " --out " + (dir_ / "missing" / "rec.h5").string());
    EXPECT_EQ(r.code, 2) << r.output;
    EXPECT_NE(r.output.find("--out"), std::string::npos) << r.output;
    r = Casmap("record" + device + " --out " + dir_.string());
    EXPECT_EQ(r.code, 2) << r.output;
    EXPECT_NE(r.output.find("is a folder"), std::string::npos) << r.output;
    r = Casmap("record" + device + " --poses " + dir_.string() + " --out " +
               (dir_ / "rec.h5").string());
    EXPECT_EQ(r.code, 2) << r.output;
    EXPECT_NE(r.output.find("--poses"), std::string::npos) << r.output;
    r = Casmap("record" + device + " --poses " + (dir_ / "nodir" / "p.txt").string() + " --out " +
               (dir_ / "rec.h5").string());
    EXPECT_EQ(r.code, 2) << r.output;
    r = Casmap("record" + device + " --mode mean:1 --out " + (dir_ / "rec.h5").string());
    EXPECT_EQ(r.code, 2) << r.output;
    EXPECT_NE(r.output.find("mean scans"), std::string::npos) << r.output;
    r = Casmap("record" + device + " --mode fast --out " + (dir_ / "rec.h5").string());
    EXPECT_EQ(r.code, 2) << r.output;
    EXPECT_NE(r.output.find("--mode"), std::string::npos) << r.output;
    r = Casmap("record" + device + " --scans 0 --out " + (dir_ / "rec.h5").string());
    EXPECT_NE(r.code, 0) << r.output;
    EXPECT_LT(std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count(),
              30.0);
    EXPECT_FALSE(fs::exists(dir_ / "rec.h5"));
}

// Issue #13 item 1: --poses-out into a missing folder is refused before serving, and no
// --link symlink is left behind.
TEST_F(ServeRecordCommand, ServeRefusesAPoseFileItCannotWrite) {
    io::WriteRunFile(dir_ / "served.h5", NumberedRun(20));
    const fs::path link = dir_ / "lms";
    const Result r =
        Casmap("serve --run " + (dir_ / "served.h5").string() + " --link " + link.string() +
               " --poses-out " + (dir_ / "missing" / "poses.txt").string());
    EXPECT_EQ(r.code, 2) << r.output;
    EXPECT_NE(r.output.find("--poses-out"), std::string::npos) << r.output;
    EXPECT_FALSE(fs::exists(fs::symlink_status(link)));
}

// Issue #13 item 8: a device absent at start is waited for (retry with back-off).
TEST_F(ServeRecordCommand, RecordWaitsForAScannerThatAppearsLater) {
    io::WriteRunFile(dir_ / "served.h5", NumberedRun(400));
    const fs::path link = dir_ / "lms";
    const fs::path out = dir_ / "rec.h5";
    std::thread late([&] {
        std::this_thread::sleep_for(std::chrono::milliseconds(1500));
        StartServe({"--run", (dir_ / "served.h5").string(), "--link", link.string()});
    });
    const Result r = Casmap("record --device " + link.string() +
                            " --baud 500000 --scans 10 --timeout 20 --out " + out.string());
    late.join();
    ASSERT_EQ(r.code, 0) << r.output;
    EXPECT_EQ(r.output.find("\"connect_attempts\": 1,"), std::string::npos) << r.output;
    EXPECT_EQ(io::ReadRunFile(out).scans.size(), 10U);
}

// Every streaming mode through the CLI: partial scans of 0.5 deg are joined into complete
// scans equal to the served ones; sub-ranges carry their beams; mean values one beam mean.
TEST_F(ServeRecordCommand, RecordAcceptsEveryStreamingMode) {
    io::RunData served = NumberedRun(600);
    for (core::Scan& s : served.scans) {  // 0.5 deg: 361 beams
        s.angle_step_rad = 0.5 * kDeg;
        s.beam_period_s = (1.0 / 75.0) / 720.0;
        s.beams.resize(361, s.beams.back());
    }
    io::WriteRunFile(dir_ / "served.h5", served);
    const fs::path link = dir_ / "lms";
    StartServe({"--run", (dir_ / "served.h5").string(), "--link", link.string()});
    ASSERT_TRUE(WaitForLink(link));
    struct Case {
        std::string mode;
        std::size_t beams;
        double start_deg;
    };
    for (const Case& c : {Case{"partial", 361, -90.0}, Case{"subrange:21-60", 40, -80.0},
                          Case{"mean:2", 361, -90.0}, Case{"mean-subrange:2:1-10", 10, -90.0}}) {
        const fs::path out = dir_ / "rec.h5";
        const Result r = Casmap("record --device " + link.string() +
                                " --baud 500000 --scans 6 --timeout 10 --mode " + c.mode +
                                " --out " + out.string());
        ASSERT_EQ(r.code, 0) << c.mode << ": " << r.output;
        const io::RunData rec = io::ReadRunFile(out);
        ASSERT_EQ(rec.scans.size(), 6U) << c.mode;
        for (const core::Scan& s : rec.scans) {
            ASSERT_EQ(s.beams.size(), c.beams) << c.mode;
            EXPECT_NEAR(s.start_angle_rad, c.start_deg * kDeg, 1e-9) << c.mode;
            if (c.mode == "partial") {  // complete scans, value for value
                const core::Scan& want = served.scans.at(s.beams[0].raw);
                for (std::size_t b = 0; b < s.beams.size(); ++b) {
                    EXPECT_EQ(s.beams[b].raw, want.beams[b].raw) << "beam " << b;
                }
            }
        }
        EXPECT_NE(r.output.find("\"malformed\": 0"), std::string::npos) << r.output;
        fs::remove(out);
    }
}

}  // namespace
}  // namespace casmap
