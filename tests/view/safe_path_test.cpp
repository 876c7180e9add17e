#include "casmap/view/safe_path.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <string>

#include "tests/view/test_dir.hpp"

namespace casmap::view {
namespace {
namespace fs = std::filesystem;

class SafePath : public ::testing::Test {
protected:
    void SetUp() override {
        base_ = test::FreshDir("safe");
        root_ = base_ / "root";
        test::WriteText(root_ / "runs" / "a.txt", "a");
        test::WriteText(base_ / "secret.txt", "outside");
        root_ = fs::canonical(root_);
    }
    void TearDown() override { fs::remove_all(base_); }
    fs::path base_;
    fs::path root_;
};

TEST_F(SafePath, FileBelowRootResolves) {
    const ResolvedPath r = ResolveUnder(root_, "runs/a.txt");
    ASSERT_EQ(r.verdict, PathVerdict::kOk);
    EXPECT_EQ(r.path, root_ / "runs" / "a.txt");
}

TEST_F(SafePath, EmptyPathIsTheRoot) {
    const ResolvedPath r = ResolveUnder(root_, "");
    ASSERT_EQ(r.verdict, PathVerdict::kOk);
    EXPECT_EQ(r.path, root_);
}

TEST_F(SafePath, DotDotIsRefusedAnywhere) {
    EXPECT_EQ(ResolveUnder(root_, "..").verdict, PathVerdict::kBadPath);
    EXPECT_EQ(ResolveUnder(root_, "../secret.txt").verdict, PathVerdict::kBadPath);
    EXPECT_EQ(ResolveUnder(root_, "runs/../../secret.txt").verdict, PathVerdict::kBadPath);
    // Even when it would come back inside.
    EXPECT_EQ(ResolveUnder(root_, "runs/../runs/a.txt").verdict, PathVerdict::kBadPath);
    EXPECT_EQ(ResolveUnder(root_, "runs/..").verdict, PathVerdict::kBadPath);
}

TEST_F(SafePath, AbsoluteBackslashAndNulAreRefused) {
    EXPECT_EQ(ResolveUnder(root_, (base_ / "secret.txt").string()).verdict, PathVerdict::kBadPath);
    EXPECT_EQ(ResolveUnder(root_, "runs\\a.txt").verdict, PathVerdict::kBadPath);
    EXPECT_EQ(ResolveUnder(root_, std::string("runs/a.txt\0x", 12)).verdict, PathVerdict::kBadPath);
    EXPECT_EQ(ResolveUnder(root_, std::string(kMaxPathBytes + 1, 'a')).verdict,
              PathVerdict::kBadPath);
}

TEST_F(SafePath, SymlinkOutOfRootIsRefused) {
    fs::create_symlink(base_ / "secret.txt", root_ / "leak.txt");
    fs::create_directory_symlink(base_, root_ / "up");
    EXPECT_EQ(ResolveUnder(root_, "leak.txt").verdict, PathVerdict::kOutside);
    EXPECT_EQ(ResolveUnder(root_, "up/secret.txt").verdict, PathVerdict::kOutside);
    EXPECT_EQ(ResolveUnder(root_, "up").verdict, PathVerdict::kOutside);
}

TEST_F(SafePath, SymlinkInsideRootResolvesToItsTarget) {
    fs::create_symlink(root_ / "runs" / "a.txt", root_ / "alias.txt");
    const ResolvedPath r = ResolveUnder(root_, "alias.txt");
    ASSERT_EQ(r.verdict, PathVerdict::kOk);
    EXPECT_EQ(r.path, root_ / "runs" / "a.txt");
}

TEST_F(SafePath, MissingAndDanglingAreMissing) {
    EXPECT_EQ(ResolveUnder(root_, "runs/none.txt").verdict, PathVerdict::kMissing);
    fs::create_symlink(base_ / "nowhere", root_ / "dangling");
    EXPECT_EQ(ResolveUnder(root_, "dangling").verdict, PathVerdict::kMissing);
}

TEST(IsInside, ComparesComponentsNotPrefixes) {
    EXPECT_TRUE(IsInside("/srv/out", "/srv/out"));
    EXPECT_TRUE(IsInside("/srv/out", "/srv/out/bench.json"));
    EXPECT_FALSE(IsInside("/srv/out", "/srv/outside/bench.json"));
    EXPECT_FALSE(IsInside("/srv/out", "/srv"));
}

}  // namespace
}  // namespace casmap::view
