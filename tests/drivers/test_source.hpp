#pragma once

// A deterministic ScanSource for the driver tests: sweep i has beam 0 = i (mm), so every
// received scan names the sweep it came from; the other beams are seeded ranges in mm plus a
// few special codes.

#include <chrono>
#include <condition_variable>
#include <map>
#include <mutex>
#include <random>
#include <set>

#include "casmap/drivers/scan_codec.hpp"
#include "casmap/drivers/virtual_lms200.hpp"

namespace casmap::drivers::testing {

class NumberedSource : public ScanSource {
public:
    explicit NumberedSource(std::uint64_t count = 1000000) : count_(count) {}

    std::optional<core::Scan> Sweep(std::uint64_t index, const Variant& variant) override {
        if (index >= count_) {
            return std::nullopt;
        }
        return Make(index, variant);
    }
    [[nodiscard]] bool Supports(const Variant& variant) const override { return variant.IsValid(); }

    /// The scan of sweep `index` as a real scanner would put it on the line (quantised to mm).
    static core::Scan Make(std::uint64_t index, const Variant& variant) {
        std::mt19937 rng(static_cast<unsigned>(index * 7919 + 17));
        core::Scan scan;
        scan.start_angle_rad = StartAngleRad(variant);
        scan.beams.resize(static_cast<std::size_t>(variant.BeamCount()));
        const core::Lms200Format mm{};
        for (std::size_t i = 0; i < scan.beams.size(); ++i) {
            std::uint16_t raw = static_cast<std::uint16_t>(rng() % 8000);
            if (i == 0) {
                raw = static_cast<std::uint16_t>(index % 8000);
            } else if (rng() % 20 == 0) {
                raw = mm.CodeFor(static_cast<core::BeamStatus>(1 + rng() % 6));
            }
            scan.beams[i] = mm.Decode(raw);
        }
        return scan;
    }

private:
    std::uint64_t count_;
};

/// Records which sweeps the virtual scanner put on the line, intact or not.
struct SentLog {
    std::mutex mutex;
    std::set<std::uint64_t> intact;
    std::set<std::uint64_t> damaged;
    std::map<std::uint64_t, double> beam0_wall_s;
    std::map<std::uint64_t, std::uint64_t> connection;  // SentScan::connection
    std::condition_variable recorded;
    void Record(const SentScan& s) {
        {
            std::lock_guard lock(mutex);
            (s.intact ? intact : damaged).insert(s.index);
            beam0_wall_s[s.index] = s.beam0_wall_s;
            connection[s.index] = s.connection;
        }
        recorded.notify_all();
    }
    /// When beam 0 of sweep `index` was measured. The scanner reports a telegram after its last
    /// byte is written, so the client may have it first: wait (at most 2 s) for the report.
    double Beam0(std::uint64_t index) {
        std::unique_lock lock(mutex);
        recorded.wait_for(lock, std::chrono::seconds(2),
                          [&] { return beam0_wall_s.count(index) == 1; });
        return beam0_wall_s.at(index);
    }
};

}  // namespace casmap::drivers::testing
