#include "casmap/io/output_set.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "casmap/core/input_error.hpp"
#include "casmap/io/atomic_file.hpp"
#include "tests/temp_dir.hpp"

namespace casmap::io {
namespace {
namespace fs = std::filesystem;
using ::testing::HasSubstr;

fs::path FreshDir(const std::string& name) {
    return casmap::test::MakeTempDir("output_set_" + name);
}

std::string Slurp(const fs::path& p) {
    std::ifstream in(p);
    return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

// The PID of a process that has exited (and been reaped).
long DeadPid() {
    const pid_t child = fork();
    if (child == 0) {
        _exit(0);
    }
    int status = 0;
    waitpid(child, &status, 0);
    return static_cast<long>(child);
}

TEST(OutputSet, PublishesEveryOutputAndLeavesNoTemporary) {
    const fs::path dir = FreshDir("publish");
    {
        OutputSet set;
        std::ofstream(set.AddFile(dir / "run.h5.config.yaml", "config")) << "config";
        std::ofstream(set.AddFile(dir / "run.h5", "--out")) << "run";
        EXPECT_FALSE(fs::exists(dir / "run.h5"));
        set.Publish();
    }
    EXPECT_EQ(Slurp(dir / "run.h5"), "run");
    EXPECT_EQ(Slurp(dir / "run.h5.config.yaml"), "config");
    EXPECT_EQ(std::distance(fs::directory_iterator(dir), fs::directory_iterator()), 2);
}

TEST(OutputSet, UnpublishedSetRemovesItsTemporariesAndKeepsOldOutputs) {
    const fs::path dir = FreshDir("abandon");
    std::ofstream(dir / "run.h5") << "old";
    {
        OutputSet set;
        std::ofstream(set.AddFile(dir / "run.h5", "--out")) << "new";
        (void)set.AddFolder(dir / "sheets", "sheets");
    }  // an exception between AddFile and Publish ends here
    EXPECT_EQ(Slurp(dir / "run.h5"), "old");
    EXPECT_EQ(std::distance(fs::directory_iterator(dir), fs::directory_iterator()), 1);
}

TEST(OutputSet, BadPathsFailBeforeAnyWork) {
    const fs::path dir = FreshDir("bad");
    OutputSet set;
    EXPECT_THAT([&] { (void)set.AddFile(dir / "missing" / "run.h5", "--out"); },
                ::testing::ThrowsMessage<InputError>(HasSubstr("missing does not exist")));
    EXPECT_THAT([&] { (void)set.AddFile(dir, "--png"); },
                ::testing::ThrowsMessage<InputError>(HasSubstr("--png (is a folder, not a file)")));
    (void)set.AddFile(dir / "a.tiff", "--out");
    EXPECT_THAT([&] { (void)set.AddFile(dir / "." / "a.tiff", "--png"); },
                ::testing::ThrowsMessage<InputError>(HasSubstr("is also the output of --out")));
    if (geteuid() != 0) {  // root writes anywhere
        fs::create_directories(dir / "ro");
        chmod((dir / "ro").c_str(), 0555);
        EXPECT_THAT([&] { (void)set.AddFile(dir / "ro" / "x", "--out"); },
                    ::testing::ThrowsMessage<InputError>(HasSubstr("is not writable")));
    }
}

// The message says why the folder is unusable: "does not exist" for a file in the way or a
// folder that could not be created sent users looking for a missing folder.
TEST(OutputSet, UnusableFolderSaysWhy) {
    const fs::path dir = FreshDir("why");
    std::ofstream(dir / "afile") << "x";
    EXPECT_THAT([&] { CheckOutputPath(dir / "afile" / "e.tiff", "--out"); },
                ::testing::ThrowsMessage<InputError>(
                    HasSubstr("--out (" + (dir / "afile").string() + " is not a folder)")));
    EXPECT_THAT([&] { CheckOutputPath(dir / "afile" / "e.tiff", "--out", true); },
                ::testing::ThrowsMessage<InputError>(HasSubstr("afile is not a folder)")));
    EXPECT_THAT([&] { CheckOutputPath(dir / "afile" / "sub" / "e.tiff", "--out", true); },
                ::testing::ThrowsMessage<InputError>(HasSubstr(
                    "folder " + (dir / "afile" / "sub").string() + " cannot be created: ")));
    EXPECT_THAT([&] { CheckOutputPath(dir / "gone" / "e.tiff", "--out"); },
                ::testing::ThrowsMessage<InputError>(HasSubstr("gone does not exist)")));
    CheckOutputPath(dir / "new" / "e.tiff", "--out", true);
    EXPECT_TRUE(fs::is_directory(dir / "new"));
}

TEST(OutputSet, FolderReplacesTheOldFolderWhole) {
    const fs::path dir = FreshDir("folder");
    fs::create_directories(dir / "bench" / "runs");
    std::ofstream(dir / "bench" / "bench.json") << "old";
    std::ofstream(dir / "bench" / "runs" / "old.h5") << "old";
    OutputSet set;
    const fs::path tmp = set.AddFolder(dir / "bench", "--out");
    fs::create_directories(tmp / "runs");
    std::ofstream(tmp / "runs" / "new.h5") << "new";
    EXPECT_TRUE(fs::exists(dir / "bench" / "bench.json"));  // untouched until published
    set.Publish();
    EXPECT_FALSE(fs::exists(dir / "bench" / "bench.json"));
    EXPECT_FALSE(fs::exists(dir / "bench" / "runs" / "old.h5"));
    EXPECT_TRUE(fs::exists(dir / "bench" / "runs" / "new.h5"));
    EXPECT_EQ(std::distance(fs::directory_iterator(dir), fs::directory_iterator()), 1);
}

TEST(OutputSet, StaleTemporariesOfDeadProcessesAreRemoved) {
    const fs::path dir = FreshDir("stale");
    const std::string dead = ".run.h5.tmp" + std::to_string(DeadPid());
    const std::string alive = ".run.h5.tmp" + std::to_string(static_cast<long>(getppid()));
    std::ofstream(dir / dead) << "x";
    fs::create_directories(dir / (".bench.tmp" + std::to_string(DeadPid())) / "runs");
    std::ofstream(dir / alive) << "x";
    std::ofstream(dir / ".notes.tmpfile") << "x";  // not ours: no PID
    WriteTextAtomically(dir / "other.txt", "text");
    EXPECT_FALSE(fs::exists(dir / dead));
    EXPECT_TRUE(fs::exists(dir / alive));
    EXPECT_TRUE(fs::exists(dir / ".notes.tmpfile"));
    EXPECT_EQ(std::distance(fs::directory_iterator(dir), fs::directory_iterator()), 3);
}

}  // namespace
}  // namespace casmap::io
