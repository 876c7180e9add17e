#include "apps/casmap/progress_bar.hpp"

#include <unistd.h>

#include <cstdio>

namespace casmap::app {

ProgressBar::ProgressBar(std::string label)
    : label_(std::move(label)),
      enabled_(isatty(STDERR_FILENO) == 1),
      start_(std::chrono::steady_clock::now()),
      last_draw_(start_) {}

ProgressBar::~ProgressBar() { Finish(); }

core::ProgressFn ProgressBar::Fn() {
    return [this](std::size_t done, std::size_t total) { Update(done, total); };
}

void ProgressBar::Update(std::size_t done, std::size_t total) {
    const std::lock_guard<std::mutex> lock(mutex_);
    done_ = done;
    total_ = total;
    Draw(done_ >= total_);
}

void ProgressBar::Finish() {
    const std::lock_guard<std::mutex> lock(mutex_);
    if (enabled_ && drawn_ && !finished_) {
        Draw(true);
        std::fputc('\n', stderr);
    }
    finished_ = true;
}

void ProgressBar::Draw(bool force) {
    if (!enabled_ || finished_) {
        return;
    }
    const auto now = std::chrono::steady_clock::now();
    if (!force && now - last_draw_ < std::chrono::milliseconds(100)) {
        return;
    }
    last_draw_ = now;
    drawn_ = true;
    constexpr int kWidth = 30;
    const double fraction =
        total_ == 0 ? 1.0 : static_cast<double>(done_) / static_cast<double>(total_);
    const int filled = static_cast<int>(fraction * kWidth);
    const double elapsed = std::chrono::duration<double>(now - start_).count();
    std::fprintf(stderr, "\r%s [%.*s%*s] %zu/%zu %5.1fs", label_.c_str(), filled,
                 "##############################", kWidth - filled, "", done_, total_, elapsed);
    std::fflush(stderr);
}

}  // namespace casmap::app
