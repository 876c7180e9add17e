#pragma once

// A live session (`casmap live`, pipeline/live.hpp) set up from plain options: the active
// window and the session limits, the CAS parameters by name, and the scan source with its pose
// stream. The source is an LMS 200 on a serial device (a real scanner or `casmap serve`) with a
// pose file or socket, in every build; or, in simulator builds, the run `casmap simulate` makes
// for a scene and motion, paced in real time or not. Errors are InputErrors naming the options
// field ("device / scene", "poses / poses_socket", "baud", ...) without a `where`.

#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "casmap/drivers/pose_stream.hpp"
#include "casmap/pipeline/live.hpp"

namespace casmap::pipeline {

struct LiveOptions {
    // The source: a scanner on a serial device with exactly one pose stream ...
    std::string device;
    int baud = 500000;         ///< rate the driver switches the scanner to
    std::string poses;         ///< pose file followed as it grows (docs/pose-file.md)
    std::string poses_socket;  ///< pose records on "udp:PORT" or "unix:PATH" datagrams
    // ... or the simulator (simulator builds): the run of `casmap simulate` with these settings.
    std::string scene;
    std::string motion;               ///< T, TR, TP, TRP or vehicle
    std::optional<double> speed_m_s;  ///< the rig's default when unset
    std::uint64_t seed = 1;
    std::string rig;        ///< rig YAML; empty: the defaults
    bool realtime = false;  ///< pace the simulated scans at the scanner's 75 Hz
    // The session.
    std::string out;        ///< output folder
    int window_rows = 200;  ///< R, along travel
    int window_cols = 400;  ///< C, across
    int m = 0;  ///< 0: the window's default, or for a simulated rig LookAheadRows (0.3 m)
    double obstacle_cell_m = 0.1;
    double snapshot_every_s = 2.0;   ///< 0: only at exit
    double duration_s = 0.0;         ///< 0: no limit
    std::uint64_t scans = 0;         ///< stop after this many scans received; 0: no limit
    double timeout_s = 10.0;         ///< connecting, and the longest wait for a scan
    double pose_tolerance_s = 0.05;  ///< largest pose gap a scan may span
    std::string mapper = "paper";    ///< paper (Eq. 1-6) | consensus (mapper/consensus.hpp)
    std::string prefilter = "none";  ///< none | sweep_jump (mapper/sweep_jump_stream.hpp)
    /// NAME=VALUE (mapper::FilterParams' names): CAS parameters, and those of the mapper mode
    /// and pre-filter chosen (consensus.<f>, sweep_jump.<f>; another stage's is an error).
    std::vector<std::string> cas;

    /// The source's checks (one source; a scanner with one pose stream and an LMS baud; a scene
    /// with a motion, in simulator builds only): InputError naming the field, no `where`. The
    /// session's numbers are checked by LiveConfig::Validate() inside MakeLiveSetup.
    void Validate() const;
};

/// "R,C" (two integers: window rows along travel, columns across) -> options.window_rows,
/// window_cols; InputError naming `field` otherwise (the sizes are checked by MakeLiveSetup).
void ParseWindowSize(std::string_view text,
                     LiveOptions& options,
                     const std::string& field = "window");

/// What RunLive takes: the configuration, the scans and the poses.
struct LiveSetup {
    LiveConfig config;
    std::unique_ptr<LiveScanSource> scans;
    std::unique_ptr<drivers::PoseStream> poses;
};

/// The session of `options` (nothing connects yet: RunLive starts the source). A simulated
/// source is simulated here on `threads` threads (0: all cores); its window is anchored at the
/// simulated map's grid origin, m follows the rig's height and pitch unless set, and Eq. 8's v
/// is the rig's cruise speed. CAS parameters go through mapper::FilterParams (their cell and
/// increment become the window's); mapping-stage parameters through ApplyStageSettings
/// (map_run.hpp), as `casmap map --set`. InputError for bad options ("mapper", "prefilter",
/// "set" for an assignment of a stage not chosen, the parameter for a bad value); a scene in a
/// build without the simulator is one ("scene ... built without the simulator; use device").
[[nodiscard]] LiveSetup MakeLiveSetup(const LiveOptions& options, int threads);

/// The message of a session that timed out (LiveResult::timed_out): what was waited for and
/// where what was received went.
[[nodiscard]] std::string LiveTimeoutMessage(const LiveResult& result,
                                             const std::string& source_name,
                                             double timeout_s);

/// The one-line JSON summary of a session (the line `casmap live` prints at the end).
[[nodiscard]] std::string LiveSummaryJson(const LiveResult& result);

}  // namespace casmap::pipeline
