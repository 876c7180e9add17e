// `casmap serve --run` and `casmap record` as processes talking through a pseudo-terminal:
// every recorded scan equals the served one value for value, the JSON line is complete, and
// bad input ends with exit 2 and no run file.
#include <gtest/gtest.h>
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <filesystem>
#include <map>
#include <numbers>
#include <string>
#include <thread>

#include "io/run_file.hpp"

extern char** environ;

namespace casmap {
namespace {
namespace fs = std::filesystem;

struct Result {
    int code = -1;
    std::string output;
};

Result Casmap(const std::string& args) {
    const std::string cmd = std::string(CASMAP_EXE) + " " + args + " 2>&1";
    Result r;
    FILE* pipe = popen(cmd.c_str(), "r");
    char buffer[4096];
    while (pipe != nullptr && fgets(buffer, sizeof(buffer), pipe) != nullptr) {
        r.output += buffer;
    }
    const int status = pipe != nullptr ? pclose(pipe) : -1;
    r.code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    return r;
}

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

TEST_F(ServeRecordCommand, BadInputIsExitTwoWithoutARunFile) {
    const fs::path out = dir_ / "rec.h5";
    Result r = Casmap("record --device /nonexistent/ttyX --out " + out.string());
    EXPECT_EQ(r.code, 2) << r.output;
    EXPECT_NE(r.output.find("/nonexistent/ttyX"), std::string::npos) << r.output;
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

}  // namespace
}  // namespace casmap
