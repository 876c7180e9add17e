#pragma once

// Scan-clock synchronisation for a periodic scanner: the LMS 200 completes a sweep every
// ScanPeriodS(variant), so the true stamps lie on a grid t0 + k * T. The host only sees
// arrival times, late by a one-sided, jittery latency. ScanClock estimates the phase t0 with a
// lower-envelope (minimum-latency) filter over the scans of the last `window_s` seconds,
// gives every scan its grid index k and stamps it t0 + k * T (docs/drivers.md).

#include <cstdint>
#include <deque>
#include <vector>

namespace casmap::drivers {

struct ScanClockConfig {
    double period_s = 1.0 / 75.0;  // T: seconds between completed sweeps
    double window_s = 2.0;         // scans whose latency bounds the phase (lower envelope)
    /// Grid slot of a scan: k = floor((latest - t0) / T + guard). Latencies are >= 0, so the
    /// window [t0 + (k - guard) T, t0 + (k + 1 - guard) T) accepts up to (1 - guard) T late.
    double guard = 0.25;
    int warmup_scans = 8;  // the first scans use guard 0.5 (round): the phase is still coarse
    /// After warm-up, a scan implying a phase more than this earlier than the envelope is
    /// taken as a late scan in the wrong slot (or a clock step) and kept out of the envelope ...
    double max_step_s = 0.001;
    /// ... unless `confirm_scans` consecutive scans agree: then the clock stepped, the window
    /// restarts from them.
    int confirm_scans = 3;
    /// Throws InputError naming the field.
    void Validate() const;
};

class ScanClock {
public:
    explicit ScanClock(ScanClockConfig config = {});

    /// Forgets the phase (a reconnect: the scanner's mirror restarted).
    void Reset();
    /// `latest_s` = the latest plausible stamp of a scan (arrival - transmission - sweep), in
    /// arrival order. Returns the synchronised stamp t0 + k * T with t0 the current estimate,
    /// never earlier than or equal to the previous stamp (+1 us if the phase moved back).
    [[nodiscard]] double Stamp(double latest_s);
    /// Same, for a scan whose grid index the scanner told (the real-time scan index, unwrapped
    /// by the caller): only the phase is estimated, the lower envelope of latest_s - k T over
    /// the window. Works however many sweeps the line skips (e.g. 38400 baud).
    [[nodiscard]] double StampIndexed(double latest_s, std::int64_t k);

    /// Grid index of the last stamped scan, counted from the first scan since Reset (skipped
    /// sweeps skip indices).
    [[nodiscard]] std::int64_t last_index() const { return last_k_; }
    /// Grid period T (s).
    [[nodiscard]] double period_s() const { return config_.period_s; }
    /// Current phase estimate t0 (the stamp of index 0).
    [[nodiscard]] double phase_s() const { return anchor_s_ + phase_rel_s_; }
    /// Scans stamped since Reset.
    [[nodiscard]] std::uint64_t scans() const { return count_; }
    /// Scans kept out of the envelope as outliers (see ScanClockConfig::max_step_s).
    [[nodiscard]] std::uint64_t outliers() const { return outliers_; }

private:
    struct Sample {
        double latest_rel_s;  // latest - anchor
        double residual_s;    // latest - anchor - k T
    };
    ScanClockConfig config_;
    double anchor_s_ = 0.0;  // first scan's latest stamp; keeps the arithmetic small
    double phase_rel_s_ = 0.0;
    std::int64_t last_k_ = 0;
    std::uint64_t count_ = 0;
    std::uint64_t outliers_ = 0;
    int early_run_ = 0;
    std::deque<Sample> window_;
    double last_stamp_s_ = 0.0;  // kept across Reset: stamps increase for the whole session
    bool stamped_any_ = false;

    [[nodiscard]] double StampOnGrid(double latest_s);
};

/// A telegram of one read from the line, in order.
struct ReadTelegram {
    double arrival_s = 0.0;  // the read's time less 10 / baud per byte after it in the read
    bool periodic = false;   // a measured-value telegram (one per telegram period)
};

/// Bounds the arrival of each periodic telegram followed by another in the same read by that
/// one's arrival less `period_s`: the scanner sends one per period, when its sweep is
/// complete, and the line is free then. A backlog read at once (the host stalled) so keeps the
/// line's timing instead of looking late by the stall.
void BoundArrivalsInRead(std::vector<ReadTelegram>& telegrams, double period_s);

/// Grid slots of the scans held during a ScanClock's warm-up, placed again once its phase
/// `phase_s` is known: `k` holds the clock's slots (the last one stays, the clock goes on from
/// it); going back, each scan takes the slot its `latest_s` allows (latency up to 1 - guard
/// periods) when that is later than the clock's, never earlier, and before the next scan's.
/// A scan more than half a period late in the warm-up pushes the slots after it; once the
/// phase has moved a period back, the scans before it would otherwise be a period early.
void ReslotHeldScans(std::vector<std::int64_t>& k,
                     const std::vector<double>& latest_s,
                     double phase_s,
                     const ScanClockConfig& config);

}  // namespace casmap::drivers
