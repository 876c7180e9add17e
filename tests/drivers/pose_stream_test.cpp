#include "casmap/drivers/pose_stream.hpp"

#include <arpa/inet.h>
#include <gtest/gtest.h>
#include <netinet/in.h>
#include <sys/socket.h>
#include <sys/un.h>
#include <unistd.h>

#include <cstring>
#include <filesystem>
#include <fstream>
#include <string>

#include "casmap/core/input_error.hpp"

namespace casmap::drivers {
namespace {
namespace fs = std::filesystem;

fs::path TempPath(const std::string& name) {
    return fs::path(testing::TempDir()) / (name + "_" + std::to_string(getpid()));
}

std::string Line(double t) { return std::to_string(t) + " 1 2 0.5 0 0 0 1\n"; }

TEST(PoseFileFollower, ReadsCompleteLinesAsTheFileGrows) {
    const fs::path path = TempPath("follow.txt");
    fs::remove(path);
    PoseFileFollower f(path.string());
    std::vector<core::TimedPose> got;
    f.Poll(got);  // not there yet: nothing, no error
    EXPECT_TRUE(got.empty());
    std::ofstream out(path);
    out << "# header\n" << Line(1.0) << "2.0 1 2";  // the second line is still being written
    out.flush();
    f.Poll(got);
    ASSERT_EQ(got.size(), 1U);
    EXPECT_DOUBLE_EQ(got[0].stamp_s, 1.0);
    EXPECT_DOUBLE_EQ(got[0].world_T_sensor.translation.y(), 2.0);
    out << " 0.5 0 0 0 1\n" << Line(3.0);
    out.flush();
    f.Poll(got);
    ASSERT_EQ(got.size(), 3U);
    EXPECT_DOUBLE_EQ(got[1].stamp_s, 2.0);
    EXPECT_DOUBLE_EQ(got[2].stamp_s, 3.0);
    EXPECT_EQ(f.counters().poses, 3U);
    fs::remove(path);
}

TEST(PoseFileFollower, AReplacedFileDeliversOnlyNewPoses) {
    const fs::path path = TempPath("replaced.txt");
    { std::ofstream(path) << Line(1.0) << Line(2.0); }
    PoseFileFollower f(path.string());
    std::vector<core::TimedPose> got;
    f.Poll(got);
    ASSERT_EQ(got.size(), 2U);
    const fs::path tmp = TempPath("replaced.tmp");
    { std::ofstream(tmp) << Line(1.0) << Line(2.0) << Line(3.0); }
    fs::rename(tmp, path);  // as an atomic writer replaces it
    f.Poll(got);
    ASSERT_EQ(got.size(), 3U);
    EXPECT_DOUBLE_EQ(got[2].stamp_s, 3.0);
    fs::remove(path);
}

TEST(PoseFileFollower, RejectsMalformedAndBackwardLinesNamingTheLine) {
    const fs::path path = TempPath("bad.txt");
    { std::ofstream(path) << Line(2.0) << Line(1.0); }
    PoseFileFollower f(path.string());
    std::vector<core::TimedPose> got;
    try {
        f.Poll(got);
        FAIL() << "accepted a stamp going backwards";
    } catch (const InputError& e) {
        EXPECT_NE(std::string(e.what()).find(path.string() + ":2"), std::string::npos) << e.what();
        EXPECT_NE(std::string(e.what()).find("stamp_s"), std::string::npos) << e.what();
    }
    { std::ofstream(path) << "1 2 3\n"; }
    PoseFileFollower g(path.string());
    EXPECT_THROW(g.Poll(got), InputError);
    fs::remove(path);
}

TEST(PoseSocket, ReceivesUdpDatagramsOnTheLoopback) {
    PoseSocket s("udp:0");
    ASSERT_GT(s.port(), 0);
    const int fd = ::socket(AF_INET, SOCK_DGRAM, 0);
    sockaddr_in addr{};
    addr.sin_family = AF_INET;
    addr.sin_port = htons(static_cast<std::uint16_t>(s.port()));
    addr.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
    const std::string two = Line(1.0) + Line(2.0);
    const std::string old = Line(1.5);  // behind the last one: dropped and counted
    for (const std::string* msg : {&two, &old}) {
        ASSERT_EQ(::sendto(fd, msg->data(), msg->size(), 0, reinterpret_cast<sockaddr*>(&addr),
                           sizeof(addr)),
                  static_cast<ssize_t>(msg->size()));
    }
    ::close(fd);
    std::vector<core::TimedPose> got;
    for (int i = 0; i < 100 && got.size() < 2; ++i) {
        s.Poll(got);
        usleep(1000);
    }
    s.Poll(got);
    ASSERT_EQ(got.size(), 2U);
    EXPECT_DOUBLE_EQ(got[1].stamp_s, 2.0);
    EXPECT_EQ(s.counters().out_of_order, 1U);
}

TEST(PoseSocket, ReceivesUnixDatagramsAndRemovesItsPath) {
    const fs::path path = TempPath("poses.sock");
    fs::remove(path);
    {
        PoseSocket s("unix:" + path.string());
        const int fd = ::socket(AF_UNIX, SOCK_DGRAM, 0);
        sockaddr_un addr{};
        addr.sun_family = AF_UNIX;
        std::strncpy(addr.sun_path, path.c_str(), sizeof(addr.sun_path) - 1);
        const std::string msg = Line(5.0);
        ASSERT_EQ(::sendto(fd, msg.data(), msg.size(), 0, reinterpret_cast<sockaddr*>(&addr),
                           sizeof(addr)),
                  static_cast<ssize_t>(msg.size()));
        ::close(fd);
        std::vector<core::TimedPose> got;
        s.Poll(got);
        ASSERT_EQ(got.size(), 1U);
        EXPECT_DOUBLE_EQ(got[0].stamp_s, 5.0);
        // A second socket on the same path is refused, not replaced.
        EXPECT_THROW(PoseSocket("unix:" + path.string()), InputError);
    }
    EXPECT_FALSE(fs::exists(path));
}

TEST(PoseSocket, RejectsAMalformedSpec) {
    for (const char* spec : {"tcp:5", "udp:", "udp:70000", "udp:x", "unix:"}) {
        try {
            PoseSocket s(spec);
            FAIL() << "accepted " << spec;
        } catch (const InputError& e) {
            EXPECT_NE(std::string(e.what()).find("pose socket"), std::string::npos) << e.what();
        }
    }
}

}  // namespace
}  // namespace casmap::drivers
