#include "casmap/mapper/sweep_jump_stream.hpp"

#include <cmath>
#include <utility>

#include "casmap/core/input_error.hpp"

namespace casmap::mapper {

SweepJumpStream::SweepJumpStream(const SweepJumpConfig& config) : config_(config) {
    config_.Validate();
}

double SweepJumpStream::median_gap_s() const { return high_.empty() ? 0.0 : high_.top(); }

void SweepJumpStream::Push(core::Scan scan, core::Trajectory poses) {
    if (finished_) {
        throw MakeInputError("sweep_jump stream", "scan", std::to_string(scan.stamp_s),
                             "pushed after Finish()");
    }
    if (!entries_.empty()) {
        const double gap = std::abs(scan.stamp_s - entries_.back().scan.stamp_s);
        // Insert, then rebalance so high_ holds ceil(n / 2) gaps.
        if (high_.empty() || gap >= high_.top()) {
            high_.push(gap);
        } else {
            low_.push(gap);
        }
        if (high_.size() > low_.size() + 1) {
            low_.push(high_.top());
            high_.pop();
        } else if (low_.size() > high_.size()) {
            high_.push(low_.top());
            low_.pop();
        }
    }
    SweepJumpBeams beams = SweepJumpWorldBeams(scan, poses);
    entries_.push_back({std::move(scan), std::move(poses), std::move(beams)});
    ++pushed_;
    const auto reach = static_cast<std::size_t>(config_.reach);
    while (labelled_ + reach < pushed_) {
        Label(labelled_);
        ++labelled_;
    }
    Trim();
}

void SweepJumpStream::Finish() {
    finished_ = true;
    while (labelled_ < pushed_) {
        Label(labelled_);
        ++labelled_;
    }
    Trim();
}

std::optional<SweepJumpStream::Labelled> SweepJumpStream::Pop() {
    if (ready_.empty()) {
        return std::nullopt;
    }
    Labelled out = std::move(ready_.front());
    ready_.pop_front();
    return out;
}

const SweepJumpStream::Entry* SweepJumpStream::At(std::size_t index) const {
    return index >= first_ && index < pushed_ ? &entries_[index - first_] : nullptr;
}

void SweepJumpStream::Label(std::size_t index) {
    const auto reach = static_cast<std::size_t>(config_.reach);
    std::vector<SweepJumpNeighbour> before(reach);
    std::vector<SweepJumpNeighbour> after(reach);
    for (std::size_t step = 1; step <= reach; ++step) {
        if (index >= step) {
            const Entry* e = At(index - step);
            before[step - 1] = {&e->scan, &e->beams};
        }
        // Not yet arrived: only at Finish(), when it never will (the run's end).
        if (const Entry* e = At(index + step); e != nullptr) {
            after[step - 1] = {&e->scan, &e->beams};
        }
    }
    const Entry& cur = *At(index);
    ready_.push_back(
        {cur.scan, cur.poses,
         SweepJumpScanLabels(cur.scan, cur.beams, before, after, median_gap_s(), config_)});
}

void SweepJumpStream::Trim() {
    // Scan j is still needed while it is unlabelled or a neighbour of one: j >= labelled_ - reach.
    const auto reach = static_cast<std::size_t>(config_.reach);
    while (!entries_.empty() && first_ + reach < labelled_) {
        entries_.pop_front();
        ++first_;
    }
}

}  // namespace casmap::mapper
