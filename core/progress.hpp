#pragma once

// How libraries report progress: a callback, never a drawing. The caller decides what to do
// with it (a terminal bar in apps/casmap, a Python callable, nothing).

#include <cstddef>
#include <functional>
#include <mutex>

namespace casmap::core {

/// Called with `done` of `total` units of work finished (done is increasing, at most total).
/// Libraries call it under their own lock, so it is never called concurrently, but it may be
/// called from a worker thread. An empty ProgressFn means "no reporting".
using ProgressFn = std::function<void(std::size_t done, std::size_t total)>;

/// The adapter a library's parallel loop uses: counts finished units and forwards the count
/// to a ProgressFn, one call at a time. Does nothing when the function is empty.
class ProgressCounter {
public:
    ProgressCounter(ProgressFn fn, std::size_t total) : fn_(std::move(fn)), total_(total) {}

    /// Marks `n` more units done and reports the new count.
    void Advance(std::size_t n = 1) {
        if (!fn_) {
            return;
        }
        const std::lock_guard<std::mutex> lock(mutex_);
        done_ += n;
        fn_(done_, total_);
    }

private:
    ProgressFn fn_;
    std::size_t total_ = 0;
    std::size_t done_ = 0;
    std::mutex mutex_;
};

}  // namespace casmap::core
