#include "casmap/drivers/scan_clock.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "casmap/core/check.hpp"
#include "casmap/core/input_error.hpp"
#include "casmap/core/text.hpp"

namespace casmap::drivers {

void ScanClockConfig::Validate() const {
    const core::Check check("scan clock");
    check.That(period_s > 0.0, "period_s", period_s, "must be > 0");
    check.That(window_s > 0.0, "window_s", window_s, "must be > 0");
    check.That(guard >= 0.0 && guard < 1.0, "guard", guard, "0 <= guard < 1");
    check.That(max_step_s > 0.0, "max_step_s", max_step_s, "must be > 0");
    check.That(confirm_scans >= 1, "confirm_scans", confirm_scans, ">= 1");
    check.That(warmup_scans >= 0, "warmup_scans", warmup_scans, ">= 0");
}

ScanClock::ScanClock(ScanClockConfig config) : config_(config) { config_.Validate(); }

void ScanClock::Reset() {
    anchor_s_ = 0.0;
    phase_rel_s_ = 0.0;
    last_k_ = 0;
    count_ = 0;
    early_run_ = 0;
    window_.clear();
}

double ScanClock::Stamp(double latest_s) {
    // Sweeps are sequential, so a later scan never gets an earlier or equal stamp (run files
    // require strictly increasing stamps). Without this, a phase estimate that moves back by
    // more than one period (a clock step under heavy host latency) stamped a scan before its
    // predecessor. 1 us keeps the order without moving the stamp measurably.
    double stamp = StampOnGrid(latest_s);
    if (stamped_any_ && !(stamp > last_stamp_s_)) {
        stamp = last_stamp_s_ + 1e-6;
    }
    stamped_any_ = true;
    last_stamp_s_ = stamp;
    return stamp;
}

double ScanClock::StampOnGrid(double latest_s) {
    const double period = config_.period_s;
    if (count_ == 0) {
        anchor_s_ = latest_s;
        phase_rel_s_ = 0.0;
        last_k_ = 0;
        window_.push_back({0.0, 0.0});
        ++count_;
        return anchor_s_;
    }
    const double x = latest_s - anchor_s_;
    const double guard =
        count_ < static_cast<std::uint64_t>(config_.warmup_scans) ? 0.5 : config_.guard;
    auto k = static_cast<std::int64_t>(std::floor((x - phase_rel_s_) / period + guard));
    const std::int64_t previous_k = last_k_;
    if (k <= previous_k) {
        k = previous_k + 1;  // two scans in one slot: the earlier one was late, the phase moves
    }
    const double residual = x - static_cast<double>(k) * period;
    last_k_ = k;
    ++count_;
    const bool warm = count_ > static_cast<std::uint64_t>(config_.warmup_scans);
    if (warm && residual < phase_rel_s_ - config_.max_step_s) {
        if (++early_run_ < config_.confirm_scans) {
            // Most likely a scan late by more than (1 - guard) T: it belongs one slot earlier
            // (if that slot is free) and says nothing about the envelope.
            ++outliers_;
            if (k - 1 > previous_k) {
                last_k_ = --k;
            }
            return anchor_s_ + phase_rel_s_ + static_cast<double>(k) * period;
        }
        window_.clear();  // consistently earlier: the clock stepped back
    }
    early_run_ = 0;
    window_.push_back({x, residual});
    while (window_.size() > 1 && window_.front().latest_rel_s < x - config_.window_s) {
        window_.pop_front();
    }
    double phase = residual;
    for (const Sample& s : window_) {
        phase = std::min(phase, s.residual_s);
    }
    phase_rel_s_ = phase;
    return anchor_s_ + phase_rel_s_ + static_cast<double>(k) * period;
}

double ScanClock::StampIndexed(double latest_s, std::int64_t k) {
    const double period = config_.period_s;
    if (count_ == 0) {
        anchor_s_ = latest_s - static_cast<double>(k) * period;
        phase_rel_s_ = 0.0;
        window_.clear();
    }
    const double x = latest_s - anchor_s_;
    const double residual = x - static_cast<double>(k) * period;
    last_k_ = k;
    ++count_;
    window_.push_back({x, residual});
    while (window_.size() > 1 && window_.front().latest_rel_s < x - config_.window_s) {
        window_.pop_front();
    }
    double phase = residual;
    for (const Sample& s : window_) {
        phase = std::min(phase, s.residual_s);
    }
    phase_rel_s_ = phase;
    return anchor_s_ + phase_rel_s_ + static_cast<double>(k) * period;
}

void BoundArrivalsInRead(std::vector<ReadTelegram>& telegrams, double period_s) {
    for (std::size_t i = telegrams.size(); i-- > 1;) {
        if (telegrams[i - 1].periodic && telegrams[i].periodic) {
            telegrams[i - 1].arrival_s =
                std::min(telegrams[i - 1].arrival_s, telegrams[i].arrival_s - period_s);
        }
    }
}

void ReslotHeldScans(std::vector<std::int64_t>& k,
                     const std::vector<double>& latest_s,
                     double phase_s,
                     const ScanClockConfig& config) {
    for (std::size_t i = k.size(); i-- > 1;) {
        const auto own = static_cast<std::int64_t>(
            std::floor((latest_s[i - 1] - phase_s) / config.period_s + config.guard));
        k[i - 1] = std::min(std::max(own, k[i - 1]), k[i] - 1);
    }
}

}  // namespace casmap::drivers
