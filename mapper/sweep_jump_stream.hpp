#pragma once

// The sweep-jump pre-filter (mapper/sweep_jump.hpp) on a stream of scans, for live mapping:
// scan k is labelled once scan k + reach has arrived (reach 1, the default: one scan of
// latency), by the per-scan step of the offline SweepJumpLabels (SweepJumpScanLabels), so its
// labels are the offline filter's bit for bit; Finish() labels the scans still waiting as the
// offline filter labels a run's last scans (a missing later neighbour: that pair is skipped).
// The one input the offline filter takes from the whole run, the median gap between scans
// (a neighbour more than step + 0.5 median gaps away counts as missing), is here the median of
// the gaps between the scans pushed so far: the whole run's once the last scan has arrived,
// and the same as the offline one on a run of regular scans. docs/paper-notes.md
// "Sweep jump, live".

#include <cstddef>
#include <cstdint>
#include <deque>
#include <functional>
#include <optional>
#include <queue>
#include <vector>

#include "casmap/core/scan.hpp"
#include "casmap/core/trajectory.hpp"
#include "casmap/mapper/sweep_jump.hpp"

namespace casmap::mapper {

class SweepJumpStream {
public:
    /// A scan with its poses and its keep labels (1 keep, 0 reject), one per beam.
    struct Labelled {
        core::Scan scan;
        core::Trajectory poses;
        std::vector<std::uint8_t> keep;
    };

    explicit SweepJumpStream(const SweepJumpConfig& config);  // validates

    /// Adds the next scan, with poses covering its beams' times (kept with it until it has
    /// been labelled and is no longer a neighbour). Scans come in time order.
    void Push(core::Scan scan, core::Trajectory poses);
    /// No more scans: the ones still waiting are labelled without their missing later
    /// neighbours. A Push after Finish is an InputError.
    void Finish();
    /// The oldest labelled scan not yet taken, in push order; nullopt if none is ready.
    [[nodiscard]] std::optional<Labelled> Pop();

    [[nodiscard]] std::size_t waiting() const { return pushed_ - labelled_; }  // not labelled
    [[nodiscard]] double median_gap_s() const;  // of the gaps so far (0 before two scans)
    [[nodiscard]] const SweepJumpConfig& config() const { return config_; }

private:
    struct Entry {
        core::Scan scan;
        core::Trajectory poses;
        SweepJumpBeams beams;
    };
    void Label(std::size_t index);  // scan `index` (absolute) -> ready_
    void Trim();                    // drops entries no longer needed
    [[nodiscard]] const Entry* At(std::size_t index) const;

    SweepJumpConfig config_;
    std::deque<Entry> entries_;  // absolute indices first_ .. pushed_ - 1
    std::size_t first_ = 0;
    std::size_t pushed_ = 0;
    std::size_t labelled_ = 0;
    bool finished_ = false;
    std::deque<Labelled> ready_;
    // The running median of the gaps: low_ the smaller half (max-heap), high_ the rest
    // (min-heap) with |high_| = |low_| or |low_| + 1, so high_.top() is the sorted gaps' element
    // number n / 2 (0-based), the offline filter's nth_element median.
    std::priority_queue<double> low_;
    std::priority_queue<double, std::vector<double>, std::greater<>> high_;
};

}  // namespace casmap::mapper
