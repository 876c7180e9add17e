// Pose files from hostile or careless sources: an endless stream, a folder, over-long lines
// (docs/limits.md).
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <filesystem>
#include <sstream>
#include <string>
#include <vector>

#include "casmap/core/input_error.hpp"
#include "casmap/drivers/pose_file.hpp"
#include "casmap/drivers/pose_stream.hpp"

namespace casmap::drivers {
namespace {
using ::testing::HasSubstr;

template <typename F>
std::string ErrorOf(F&& f) {
    try {
        f();
    } catch (const InputError& e) {
        return e.what();
    }
    return "no error";
}

TEST(PoseFileLimits, EndlessStreamWithoutNewlinesStopsAtTheLineLimit) {
    const std::string message = ErrorOf([] { (void)ReadPoseFile("/dev/zero"); });
    EXPECT_THAT(message, HasSubstr("/dev/zero:1: line (longer than 4096 bytes"));
}

TEST(PoseFileLimits, FollowingAnEndlessStreamStopsAtTheLineLimit) {
    PoseFileFollower follower("/dev/zero");
    std::vector<core::TimedPose> poses;
    EXPECT_THAT(ErrorOf([&] { follower.Poll(poses); }),
                HasSubstr("/dev/zero:1: line (longer than 4096 bytes"));
}

TEST(PoseFileLimits, AFolderIsNamedAsAFolder) {
    const std::string dir = testing::TempDir();
    EXPECT_THAT(ErrorOf([&] { (void)ReadPoseFile(dir); }), HasSubstr("is a folder, not a file"));
}

TEST(PoseFileLimits, StampErrorQuotesTheStampNotTheLastColumn) {
    std::istringstream in("1 0 0 0 0 0 0 1\n0.5 0 0 0 0 0 0 1\n");
    EXPECT_THAT(ErrorOf([&] { (void)ReadPoses(in, "p.txt"); }),
                HasSubstr("p.txt:2: stamp_s = 0.5 (strictly increasing)"));
}

TEST(PoseFileLimits, LastLineWithoutNewlineAndCommentsAreRead) {
    std::istringstream in("# header\n0 0 0 0 0 0 0 1 # first\n\n1 1 0 0 0 0 0 1");
    EXPECT_EQ(ReadPoses(in, "p.txt").size(), 2U);
}

}  // namespace
}  // namespace casmap::drivers
