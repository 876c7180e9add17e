// `casmap live` as a process: against `casmap serve` (a virtual LMS 200 on a pty, with and
// without line faults; poses from serve's --poses-out file followed as it appears), against
// the simulator in real time (simulator builds), stopping on SIGINT, and bad input.
#include <arpa/inet.h>
#include <gtest/gtest.h>
#include <netinet/in.h>
#include <signal.h>
#include <spawn.h>
#include <sys/socket.h>
#include <sys/wait.h>
#include <unistd.h>

#include <atomic>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "casmap/core/pose.hpp"
#include "casmap/io/image.hpp"
#include "casmap/io/run_file.hpp"
#include "tests/apps/cli_runner.hpp"

extern char** environ;

namespace casmap {
namespace {
namespace fs = std::filesystem;

using test::Casmap;
using test::Result;

constexpr double kDeg = std::numbers::pi / 180.0;

/// The value of "key": N in a JSON line (-1 if absent).
double JsonNumber(const std::string& text, const std::string& key) {
    const std::size_t at = text.find("\"" + key + "\": ");
    if (at == std::string::npos) {
        return -1.0;
    }
    return std::stod(text.substr(at + key.size() + 4));
}

/// A drive at 0.25 m/s (x = 0.9 + t / 4: dense enough on the block top that CAS keeps it even
/// when a loaded machine makes serve skip sweeps), the scanner 0.5 m up and 40 deg down over a
/// floor with a block (x 1.5..2.5, y -0.3..0.3, 0.2 m high); exact ranges per beam time, in
/// mm values.
io::RunData BlockRun(int count) {
    io::RunData run;
    run.format = core::Lms200Format{};
    std::vector<core::TimedPose> poses;
    // Poses from 0.5 s before the first scan to 0.5 s after the last, at 200 Hz (the motion is
    // linear, so interpolating them is exact): serve writes its whole pose file once the first
    // sweep is out, a loaded machine formats a long one slowly, and live drops a scan that
    // waits more than 0.5 s for its poses.
    for (int i = -100; i <= count * 200 / 75 + 100; ++i) {
        const double t = i * 0.005;
        poses.push_back(
            {t, core::PoseFromXyzRpy({0.9 + 0.25 * t, 0.0, 0.5}, {0.0, 40 * kDeg, 0.0})});
    }
    run.poses = core::Trajectory(poses);
    for (int k = 0; k < count; ++k) {
        core::Scan s;
        s.stamp_s = 0.01 + k / 75.0;
        s.start_angle_rad = -90 * kDeg;
        s.angle_step_rad = kDeg;
        s.beam_period_s = core::Lms200Timing::kBeamPeriodS;
        for (std::size_t i = 0; i < 181; ++i) {
            const core::Pose p = *run.poses.PoseAt(s.BeamTime(i));
            const double a = s.BeamAngle(i);
            const Eigen::Vector3d d = p.rotation * Eigen::Vector3d(std::cos(a), std::sin(a), 0);
            double r = d.z() < -1e-9 ? -p.translation.z() / d.z() : 1e9;
            const double t_top = (0.2 - p.translation.z()) / d.z();
            const Eigen::Vector3d top = p.translation + t_top * d;
            if (t_top > 0 && top.x() >= 1.5 && top.x() <= 2.5 && std::abs(top.y()) <= 0.3) {
                r = t_top;
            }
            core::Beam b;
            if (r < 8.0) {
                b.status = core::BeamStatus::kOk;
                b.raw = run.format->EncodeRange(r);
                b.range_m = run.format->Decode(b.raw).range_m;
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

class LiveCommand : public ::testing::Test {
protected:
    void SetUp() override {
        dir_ = fs::path(testing::TempDir()) / ("casmap_live_" + std::to_string(getpid()));
        fs::remove_all(dir_);
        fs::create_directories(dir_);
    }
    void TearDown() override {
        Stop(serve_pid_);
        fs::remove_all(dir_);
    }
    static pid_t Spawn(const std::vector<std::string>& args) {
        std::vector<std::string> argv_s{CASMAP_EXE};
        argv_s.insert(argv_s.end(), args.begin(), args.end());
        std::vector<char*> argv;
        for (std::string& a : argv_s) {
            argv.push_back(a.data());
        }
        argv.push_back(nullptr);
        pid_t pid = -1;
        posix_spawn(&pid, CASMAP_EXE, nullptr, nullptr, argv.data(), environ);
        return pid;
    }
    static int Stop(pid_t& pid) {
        int status = 0;
        if (pid > 0) {
            kill(pid, SIGINT);
            waitpid(pid, &status, 0);
            pid = -1;
        }
        return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    }
    void Serve(const std::string& faults, int scans = 3000) {  // 40 s (see below)
        io::WriteRunFile(dir_ / "served.h5", BlockRun(scans));
        std::vector<std::string> args{
            "serve",         "--run",         (dir_ / "served.h5").string(),
            "--link",        link().string(), "--poses-out",
            poses().string()};
        if (!faults.empty()) {
            args.push_back("--faults");
            args.push_back(faults);
        }
        serve_pid_ = Spawn(args);
        // Until serve has made its link (a loaded machine may take seconds), or has ended.
        int status = 0;
        for (int i = 0;
             i < 3000 && !fs::is_symlink(link()) && waitpid(serve_pid_, &status, WNOHANG) == 0;
             ++i) {
            std::this_thread::sleep_for(std::chrono::milliseconds(10));
        }
        ASSERT_TRUE(fs::is_symlink(link()));
    }
    fs::path link() const { return dir_ / "lms"; }
    fs::path poses() const { return dir_ / "poses.txt"; }
    fs::path out() const { return dir_ / "live"; }
    // A window that fits the 40-deg table geometry: floor scan line 0.6 m = row 23 ahead,
    // block top 0.36 m = row 14; rows 55 - 45 = 10 .. 54 updated, row 10 filtered.
    static std::string WindowFlags() { return " --window 55,200 --m 45 --snapshot-every-s 0.5"; }

    fs::path dir_;
    pid_t serve_pid_ = -1;
};

void ExpectOutputs(const fs::path& out, std::size_t scans) {
    for (const char* f : {"window_elevation.tiff", "window_elevation.png", "window_certainty.tiff",
                          "obstacle_elevation.tiff", "obstacle_elevation.png",
                          "obstacle_certainty.tiff", "status.json", "config.yaml", "run.h5"}) {
        EXPECT_TRUE(fs::exists(out / f)) << f;
    }
    const io::RunData run = io::ReadRunFile(out / "run.h5");
    EXPECT_EQ(run.scans.size(), scans);
    std::ifstream in(out / "status.json");
    std::stringstream status;
    status << in.rdbuf();
    EXPECT_NE(status.str().find("\"finished\": true"), std::string::npos) << status.str();
    EXPECT_EQ(JsonNumber(status.str(), "scans"), static_cast<double>(scans));
}

// The served runs last far longer than the scans asked for take at 75 scans/s: the run's
// sweeps follow the wall clock, and a loaded machine (two cores, other builds and tests) lets
// live lose scans (it maps and writes snapshots between reads, and the pty holds 4 KB, 11
// telegrams) and reconnect slowly. Measured at load 10: as few as 4.5 scans/s received. The
// --timeout (no scan for that long) is 30 s for the same reason.
TEST_F(LiveCommand, MapsTheScansOfCasmapServe) {
    Serve("", 4000);  // 53 s: 250 scans at >= 4.7 scans/s
    const Result r =
        Casmap("live --device " + link().string() + " --baud 500000 --poses " + poses().string() +
               " --scans 250 --timeout 30 --out " + out().string() + WindowFlags());
    ASSERT_EQ(r.code, 0) << r.output;
    EXPECT_EQ(JsonNumber(r.output, "scans"), 250);
    EXPECT_EQ(JsonNumber(r.output, "scans_mapped"), 250) << r.output;
    EXPECT_EQ(JsonNumber(r.output, "dropped"), 0);
    // No crc_errors check: a pty on a loaded machine occasionally loses bytes even without
    // injected faults (the counter is what tells).
    EXPECT_GT(JsonNumber(r.output, "rows_filtered"), 20) << r.output;  // 250 scans: ~33 rows
    ExpectOutputs(out(), 250);
    // The block is in the obstacle map: its top (0.2 m) is the highest registered height.
    const core::MapF h = io::ReadMapTiff(out() / "obstacle_elevation.tiff");
    float top = 0.0F;
    for (const float v : h.data) {
        top = std::max(top, v);
    }
    EXPECT_NEAR(top, 0.2F, 0.01F) << r.output;
}

TEST_F(LiveCommand, KeepsEveryScanThroughLineFaults) {
    Serve("crc=0.05,garbage=0.05");  // 40 s: 100 scans at >= 2.5 scans/s
    const Result r =
        Casmap("live --device " + link().string() + " --baud 500000 --poses " + poses().string() +
               " --scans 100 --timeout 30 --out " + out().string() + WindowFlags());
    ASSERT_EQ(r.code, 0) << r.output;
    EXPECT_GT(JsonNumber(r.output, "crc_errors"), 0) << r.output;
    EXPECT_EQ(JsonNumber(r.output, "dropped"), 0) << r.output;
    ExpectOutputs(out(), 100);
}

TEST_F(LiveCommand, ReconnectsWhenTheScannerVanishes) {
    // The device disappears every 2 s for 0.3 s; the mirror turns on meanwhile, so the run
    // must outlast the reconnections. 150 scans take 2 s at 75 scans/s, more than the 1.7 s a
    // connection lasts: at least one reconnection, at any load. (Every second, a loaded
    // machine's handshake could take the whole 0.7 s a connection lasted, over and over.)
    Serve("disconnect=2", 4500);  // 60 s: 150 scans at >= 2.5 scans/s
    const Result r =
        Casmap("live --device " + link().string() + " --baud 500000 --poses " + poses().string() +
               " --scans 150 --timeout 30 --out " + out().string() + WindowFlags());
    ASSERT_EQ(r.code, 0) << r.output;
    EXPECT_GE(JsonNumber(r.output, "reconnects"), 1) << r.output;
    EXPECT_EQ(JsonNumber(r.output, "dropped"), 0) << r.output;
    ExpectOutputs(out(), 150);
}

TEST_F(LiveCommand, AScannerThatStopsEndsWithEverythingWritten) {
    Serve("");
    // The scanner stops once live has received more than 20 scans (its status.json says so,
    // every 0.5 s), not after a fixed time: a loaded machine may take seconds to connect.
    std::thread stopper([this] {
        for (int i = 0; i < 6000; ++i) {
            if (JsonNumber(test::ReadText(out() / "status.json"), "scans") > 20) {
                break;
            }
            std::this_thread::sleep_for(std::chrono::milliseconds(10));
        }
        Stop(serve_pid_);
    });
    const Result r =
        Casmap("live --device " + link().string() + " --baud 500000 --poses " + poses().string() +
               " --timeout 2 --out " + out().string() + WindowFlags());
    stopper.join();
    EXPECT_EQ(r.code, 1) << r.output;
    EXPECT_NE(r.output.find("no scan for 2 s; wrote the"), std::string::npos) << r.output;
    const double scans = JsonNumber(r.output, "scans");
    EXPECT_GT(scans, 20) << r.output;
    EXPECT_EQ(static_cast<double>(io::ReadRunFile(out() / "run.h5").scans.size()), scans);
}

/// The port `casmap live` names on stderr ("casmap live: poses on udp:PORT") once its pose
/// socket is bound; 0 if `finished` comes first or 10 s pass.
int PosesPortOf(const fs::path& stderr_file, const std::atomic<bool>& finished) {
    const std::string key = "casmap live: poses on udp:";
    for (int i = 0; i < 1000; ++i) {
        const std::string text = test::ReadText(stderr_file);
        const std::size_t at = text.find(key);
        const std::size_t eol = at == std::string::npos ? at : text.find('\n', at);
        if (eol != std::string::npos) {
            return std::stoi(text.substr(at + key.size(), eol - at - key.size()));
        }
        if (finished) {
            return 0;
        }
        std::this_thread::sleep_for(std::chrono::milliseconds(10));
    }
    return 0;
}

TEST_F(LiveCommand, TakesPosesFromAUdpSocket) {
    Serve("");
    // `udp:0`: live binds a port the system chooses and names it on stderr, so test runs at
    // the same time never share a port (and no port is probed, freed, then bound again).
    const fs::path live_stderr = dir_ / "live_stderr.txt";
    std::atomic<bool> finished = false;
    Result r;
    std::thread live([&] {
        r = test::Shell("{ " + std::string(CASMAP_EXE) + " live --device " + link().string() +
                        " --baud 500000 --poses-socket udp:0 --scans 120 --timeout 10 --out " +
                        out().string() + WindowFlags() + " 2>" + live_stderr.string() + "; }");
        finished = true;
    });
    const int port = PosesPortOf(live_stderr, finished);
    if (port > 0) {
        // A pose publisher: once serve has written its pose file, send its records over UDP in
        // datagrams of 50 lines, as a robot's localisation would.
        for (int i = 0; i < 500 && !fs::exists(poses()); ++i) {
            std::this_thread::sleep_for(std::chrono::milliseconds(10));
        }
        std::this_thread::sleep_for(std::chrono::milliseconds(200));
        std::ifstream in(poses());
        const int fd = ::socket(AF_INET, SOCK_DGRAM, 0);
        sockaddr_in addr{};
        addr.sin_family = AF_INET;
        addr.sin_port = htons(static_cast<std::uint16_t>(port));
        addr.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
        std::string line;
        std::string batch;
        int n = 0;
        const auto send = [&] {
            ::sendto(fd, batch.data(), batch.size(), 0, reinterpret_cast<sockaddr*>(&addr),
                     sizeof(addr));
            batch.clear();
            n = 0;
            std::this_thread::sleep_for(std::chrono::milliseconds(2));  // 25x real time
        };
        while (std::getline(in, line)) {
            batch += line + "\n";
            if (++n == 50) {
                send();
            }
        }
        send();
        ::close(fd);
    }
    live.join();
    const std::string errors = test::ReadText(live_stderr);
    ASSERT_GT(port, 0) << r.output << errors;
    ASSERT_EQ(r.code, 0) << r.output << errors;
    EXPECT_EQ(JsonNumber(r.output, "scans_mapped"), 120) << r.output;
    EXPECT_GT(JsonNumber(r.output, "poses"), 1000) << r.output;
}

TEST_F(LiveCommand, ScansWithoutPosesAreCountedNotMapped) {
    Serve("");
    // Poses from 1970: none covers a scan stamped on today's clock.
    std::ofstream(dir_ / "old_poses.txt") << "1 0 0 0.5 0 0 0 1\n2 0 0 0.5 0 0 0 1\n";
    const Result r = Casmap("live --device " + link().string() + " --baud 500000 --poses " +
                            (dir_ / "old_poses.txt").string() + " --scans 40 --out " +
                            out().string() + WindowFlags());
    ASSERT_EQ(r.code, 0) << r.output;
    EXPECT_EQ(JsonNumber(r.output, "dropped"), 40) << r.output;
    EXPECT_EQ(JsonNumber(r.output, "scans_mapped"), 0) << r.output;
    EXPECT_EQ(io::ReadRunFile(out() / "run.h5").scans.size(), 40U);  // still recorded
}

TEST_F(LiveCommand, BadInputExitsTwoNamingTheFlag) {
    const Result missing = Casmap("live --device " + (dir_ / "nothing").string() +
                                  " --poses p.txt --out " + out().string());
    EXPECT_EQ(missing.code, 2) << missing.output;
    EXPECT_NE(missing.output.find((dir_ / "nothing").string()), std::string::npos)
        << missing.output;
    const Result baud =
        Casmap("live --device /dev/null --baud 12345 --poses p.txt --out " + out().string());
    EXPECT_EQ(baud.code, 2) << baud.output;
    EXPECT_NE(baud.output.find("--baud"), std::string::npos) << baud.output;
    const Result no_poses = Casmap("live --device /dev/null --out " + out().string());
    EXPECT_EQ(no_poses.code, 2) << no_poses.output;
    EXPECT_NE(no_poses.output.find("--poses"), std::string::npos) << no_poses.output;
    const Result window =
        Casmap("live --device /dev/null --poses p.txt --window 200 --out " + out().string());
    EXPECT_EQ(window.code, 2) << window.output;
    EXPECT_NE(window.output.find("--window"), std::string::npos) << window.output;
    const Result set =
        Casmap("live --device /dev/null --poses p.txt --set nonsense=1 --out " + out().string());
    EXPECT_EQ(set.code, 2) << set.output;
    EXPECT_NE(set.output.find("--set"), std::string::npos) << set.output;
    const Result m =
        Casmap("live --device /dev/null --poses p.txt --m 500 --out " + out().string());
    EXPECT_EQ(m.code, 2) << m.output;
    EXPECT_NE(m.output.find("active window: m"), std::string::npos) << m.output;
}

#ifdef CASMAP_TEST_WITH_SIM
const std::string kCourse = std::string(CASMAP_SOURCE_DIR) + "/scenes/courses/course04.yaml";

TEST_F(LiveCommand, RunsTheSimulatorInRealTime) {
    const auto t0 = std::chrono::steady_clock::now();
    const Result r = Casmap("live --scene " + kCourse + " --motion T --realtime --duration 2.5 " +
                            "--snapshot-every-s 1 --out " + out().string());
    const double wall =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    ASSERT_EQ(r.code, 0) << r.output;
    const double scans = JsonNumber(r.output, "scans");
    EXPECT_GT(scans, 100) << r.output;           // 75 scans/s for 2.5 s, less the start-up
    EXPECT_LE(scans, 2.5 * 75 + 2) << r.output;  // paced, not as fast as possible
    EXPECT_GE(wall, 2.5);
    EXPECT_EQ(JsonNumber(r.output, "dropped"), 0);
    EXPECT_GT(JsonNumber(r.output, "rows_filtered"), 20) << r.output;
    ExpectOutputs(out(), static_cast<std::size_t>(scans));
}

TEST_F(LiveCommand, SigintWritesWhatWasReceived) {
    pid_t pid =
        Spawn({"live", "--scene", kCourse, "--motion", "T", "--realtime", "--out", out().string()});
    std::this_thread::sleep_for(std::chrono::milliseconds(2000));
    EXPECT_EQ(Stop(pid), 0);
    ASSERT_TRUE(fs::exists(out() / "run.h5"));
    EXPECT_GT(io::ReadRunFile(out() / "run.h5").scans.size(), 10U);
    EXPECT_TRUE(fs::exists(out() / "obstacle_elevation.tiff"));
}
#endif

}  // namespace
}  // namespace casmap
