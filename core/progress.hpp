#pragma once

#include <chrono>
#include <cstddef>
#include <mutex>
#include <string>

namespace casmap::core {

/// A progress bar on stderr, drawn only when stderr is a terminal (quiet in pipes and CI).
/// Thread-safe: workers call Advance().
class Progress {
public:
    Progress(std::string label, std::size_t total);
    ~Progress();
    Progress(const Progress&) = delete;
    Progress& operator=(const Progress&) = delete;

    void Advance(std::size_t n = 1);
    void Finish();

private:
    void Draw(bool force);

    std::string label_;
    std::size_t total_ = 0;
    std::size_t done_ = 0;
    bool enabled_ = false;
    bool finished_ = false;
    std::chrono::steady_clock::time_point start_;
    std::chrono::steady_clock::time_point last_draw_;
    std::mutex mutex_;
};

}  // namespace casmap::core
