#pragma once

// Recording an LMS 200 (a real one, or `casmap serve`) into a run file (`casmap record`).
// Every input is checked before connecting; a scanner that is absent or fails during the
// start-up is retried with back-off (0.1 s doubling to 1 s) until `timeout_s`. Recording stops
// after `scans` or `duration_s`, when `stop` says so, or (with an error) after `timeout_s`
// without a scan. Whatever was received is written even when something fails afterwards.

#include <cstddef>
#include <functional>
#include <string>

#include "casmap/drivers/lms200_driver.hpp"

namespace casmap::pipeline {

struct RecordOptions {
    std::string device;
    int baud = 38400;
    std::size_t scans = 0;    ///< stop after this many (0: no limit)
    double duration_s = 0.0;  ///< stop after this long (0: no limit)
    std::string out;          ///< run file to write (HDF5)
    std::string variant;      ///< "ANGLE,RES_DEG" (e.g. "180,0.5"); empty: the scanner's
    std::string poses;        ///< pose file read when recording ends, stored as /poses
    double timeout_s = 10.0;
    std::string stamps = "scan-clock";  ///< or "arrival"
    std::string mode = "continuous";    ///< drivers::ParseOutputMode's syntax
    bool realtime_indices = false;

    /// Every check done before the scanner is touched: InputErrors naming the field ("out",
    /// "timeout_s", ...; `where` is the file for out/poses, empty otherwise).
    void Validate() const;
};

/// What the recording received, reported before the run file is written.
struct RecordStats {
    std::size_t scans = 0;
    drivers::DriverCounters counters;
    int connect_attempts = 0;
    double scans_per_second = 0.0;  ///< (scans - 1) / (last - first stamp); 0 if < 2 scans
};

/// Validates `options`, records, calls `report` (if set) once recording ended, then writes the run
/// file (or, if `out` fails, a rescue file in the system's temporary folder named in the error).
/// `stop_requested` (if set) is polled about every 0.2 s. Throws after writing what was
/// received when no scan came for `timeout_s`, or when nothing was received.
void Record(const RecordOptions& options,
            const std::function<bool()>& stop_requested,
            const std::function<void(const RecordStats&)>& report);

}  // namespace casmap::pipeline
