#pragma once

// A virtual LMS 200 streaming a run (`casmap serve`): the scans of a run file, or (simulator
// builds) of a run simulated at start-up, served on a pseudo-terminal by drivers::VirtualLms200
// until the run is exhausted or `stop` becomes true. Every input is checked before serving.
// `poses_out` receives the run's poses re-stamped into the system clock of the served sweeps
// (docs/pose-file.md), written on another thread once the first sweep went out so the
// real-time loop never waits for the disk. Nothing is printed: the caller hears of the start
// through a callback and gets the counters back.

#include <atomic>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <optional>
#include <string>

#include "casmap/drivers/virtual_lms200.hpp"

namespace casmap::pipeline {

struct ServeOptions {
    std::string run;  ///< run file (HDF5) whose scans to serve, or a scene to simulate:
    std::string scene;
    std::string motion;               ///< T, TR, TP, TRP or vehicle
    std::optional<double> speed_m_s;  ///< the rig's default when unset
    std::uint64_t seed = 1;
    std::string rig;     ///< rig YAML; empty: the defaults
    std::string link;    ///< stable symlink to the pseudo-terminal; empty: none
    int baud = 9600;     ///< power-on rate (the client switches it)
    std::string faults;  ///< drivers::ParseFaults: "crc=P,garbage=P,drop=P,collide=P,disconnect=S"
    std::string poses_out;  ///< pose file to write; empty: none
    std::string eeprom;     ///< file keeping the scanner's configuration (0x77) across restarts

    /// Every check done before anything is loaded or served: InputErrors naming the field
    /// ("run / scene", "baud", "faults", "poses_out", "eeprom"; output files as their `where`).
    void Validate() const;
};

/// What is served, once the pseudo-terminal exists.
struct ServeStarted {
    std::string device;  ///< the slave side of the pseudo-terminal
    std::size_t scans = 0;
    drivers::Variant variant;
};

struct ServeResult {
    drivers::VirtualLms200Stats stats;
    std::string poses_out_error;  ///< why `poses_out` could not be written; empty if it was
};

/// Checks, loads (or simulates, on `threads` threads) the run, opens the pseudo-terminal, calls
/// `on_started` (if set), serves until the run is exhausted or `stop`, and returns the
/// scanner's counters (and whether the pose file failed, e.g. its folder went away).
ServeResult Serve(const ServeOptions& options,
                  int threads,
                  const std::atomic<bool>& stop,
                  const std::function<void(const ServeStarted&)>& on_started);

/// The one-line JSON of the counters (the line `casmap serve` prints on exit).
[[nodiscard]] std::string ServeStatsJson(const drivers::VirtualLms200Stats& stats);

}  // namespace casmap::pipeline
