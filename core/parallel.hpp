#pragma once

#include <cstddef>
#include <functional>

namespace casmap::core {

/// Number of worker threads for `requested` (0 = all hardware threads), at least 1.
[[nodiscard]] int ResolveThreads(int requested);

/// Calls fn(i) for i in [0, n) on up to `threads` threads. Items are independent; results must
/// be written to per-item slots so the outcome does not depend on the thread count.
/// The first exception thrown by fn is rethrown after all threads stop.
void ParallelFor(std::size_t n, int threads, const std::function<void(std::size_t)>& fn);

}  // namespace casmap::core
