// `casmap serve --run` + `casmap record` through a pseudo-terminal, mapped: a map of a
// served-and-recorded run equals the map of the same run made directly, up to the cells that
// the measured stamp errors explain (serve_record_command_test.cpp has the other serve/record
// tests).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <numbers>
#include <optional>
#include <string>
#include <vector>

#include "casmap/core/grid.hpp"
#include "casmap/core/pose.hpp"
#include "casmap/io/image.hpp"
#include "casmap/io/run_file.hpp"
#include "tests/apps/cli_runner.hpp"
#include "tests/apps/serve_fixture.hpp"

namespace casmap {
namespace {
namespace fs = std::filesystem;

using test::Casmap;
using test::Result;
using test::ServeRecordCommand;

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
    std::vector<double> errors;  // recorded stamp - simulated stamp, per recorded scan
    for (const core::Scan& s : rec.scans) {
        const int k = ServedIndex(served, s);
        ASSERT_GE(k, 0) << "a recorded scan that was never served, or ambiguous: " << k;
        direct.scans.push_back(served.scans[static_cast<std::size_t>(k)]);
        const double e = (s.stamp_s - offset_s) - direct.scans.back().stamp_s;
        sum_abs += std::abs(e);
        mean += e;
        max_abs = std::max(max_abs, std::abs(e));
        errors.push_back(e);
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
    // The stamps themselves. With real-time indices the scan clock knows each scan's sweep
    // slot, and its phase is the lower envelope of the arrival latencies: every stamp error is
    // the smallest latency seen so far (2-60 us on a quiet machine, 1-5 ms measured with two
    // busy loops and other tests on two cores: a bound on that would test the machine, and
    // the map checks above already account for whatever error there was). What must hold at
    // any load: no stamp early (latency is one-sided; 50 us = the emulator's byte-time pacing
    // plus rounding), none a sweep or more late (a scan in the next slot would be), and,
    // while the 2 s envelope window still holds every earlier scan (sweeps within 1.5 s of
    // the first, unless a scan arrived 0.5 s late), errors that never grow (2 us: a few
    // roundings of a stamp in seconds since 1970, 0.24 us each).
    const double period_s = 1.0 / 75.0;
    for (std::size_t j = 0; j < errors.size(); ++j) {
        EXPECT_GT(errors[j], -5e-5) << "scan " << j;
        EXPECT_LT(errors[j], period_s) << "scan " << j;
        if (j > 0 && direct.scans[j].stamp_s - direct.scans[0].stamp_s < 1.5) {
            EXPECT_LE(errors[j], errors[j - 1] + 2e-6) << "scan " << j;
        }
    }
}

}  // namespace
}  // namespace casmap
