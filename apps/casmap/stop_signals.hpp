#pragma once

// SIGINT and SIGTERM end a long-running command cleanly (live, record, serve): while a
// StopSignals lives they set g_stop_requested instead of killing the process.

#include <atomic>
#include <csignal>

namespace casmap::app {

inline std::atomic<bool> g_stop_requested{false};

extern "C" inline void OnStopSignal(int /*signal*/) { g_stop_requested = true; }

class StopSignals {
public:
    StopSignals() {
        g_stop_requested = false;
        std::signal(SIGINT, OnStopSignal);
        std::signal(SIGTERM, OnStopSignal);
    }
    ~StopSignals() {
        std::signal(SIGINT, SIG_DFL);
        std::signal(SIGTERM, SIG_DFL);
    }
    StopSignals(const StopSignals&) = delete;
    StopSignals& operator=(const StopSignals&) = delete;
};

}  // namespace casmap::app
