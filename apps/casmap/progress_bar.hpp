#pragma once

// The terminal progress bar of the CLI: it draws the core::ProgressFn reports of a library
// call on stderr, only when stderr is a terminal (quiet in pipes and CI).

#include <chrono>
#include <cstddef>
#include <mutex>
#include <string>

#include "casmap/core/progress.hpp"

namespace casmap::app {

class ProgressBar {
public:
    explicit ProgressBar(std::string label);
    ~ProgressBar();
    ProgressBar(const ProgressBar&) = delete;
    ProgressBar& operator=(const ProgressBar&) = delete;

    /// The callback to hand to a library call; valid while this bar lives.
    [[nodiscard]] core::ProgressFn Fn();
    /// Draws `done` of `total` (at most every 100 ms unless finished).
    void Update(std::size_t done, std::size_t total);
    /// Draws the final state and ends the line.
    void Finish();

private:
    void Draw(bool force);

    std::string label_;
    std::size_t total_ = 0;
    std::size_t done_ = 0;
    bool enabled_ = false;
    bool drawn_ = false;
    bool finished_ = false;
    std::chrono::steady_clock::time_point start_;
    std::chrono::steady_clock::time_point last_draw_;
    std::mutex mutex_;
};

}  // namespace casmap::app
