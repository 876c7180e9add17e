#pragma once

// The fixture of the `casmap serve` + `casmap record` CLI tests (serve_record_command_test.cpp,
// serve_record_map_test.cpp): a scratch folder and a `casmap serve` process started in the
// background and stopped with SIGINT. A named (not anonymous) namespace: both files register
// tests of the one suite ServeRecordCommand, which GoogleTest requires to share one fixture type.
#include <gtest/gtest.h>
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <string>
#include <thread>
#include <vector>

extern char** environ;

namespace casmap::test {

class ServeRecordCommand : public ::testing::Test {
protected:
    void SetUp() override {
        dir_ = std::filesystem::path(::testing::TempDir()) /
               ("casmap_serve_record_" + std::to_string(getpid()));
        std::filesystem::remove_all(dir_);
        std::filesystem::create_directories(dir_);
    }
    void TearDown() override {
        StopServe();
        std::filesystem::remove_all(dir_);
    }
    /// Starts `casmap serve ARGS` in the background.
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
    /// Waits until serve has made its link (true), or has exited or 30 s passed (false). A
    /// condition, not a time: on a loaded machine serve may take seconds to read its run file.
    bool WaitForLink(const std::filesystem::path& link) {
        const auto until = std::chrono::steady_clock::now() + std::chrono::seconds(30);
        while (std::chrono::steady_clock::now() < until) {
            if (std::filesystem::is_symlink(link)) {
                return true;
            }
            int status = 0;
            if (serve_pid_ <= 0 || waitpid(serve_pid_, &status, WNOHANG) == serve_pid_) {
                serve_pid_ = -1;
                return false;  // serve ended (bad input, or its own error)
            }
            std::this_thread::sleep_for(std::chrono::milliseconds(10));
        }
        return false;
    }
    std::filesystem::path dir_;
    pid_t serve_pid_ = -1;
};

}  // namespace casmap::test
