#pragma once

#include <CLI/CLI.hpp>

#include "apps/casmap/flag_checks.hpp"

namespace casmap::app {

// Commands are thin clients of the pipeline library: flags -> option structs -> one pipeline
// call -> print.

/// Options every subcommand shares.
struct CommonOptions {
    int threads = 0;  // 0 = all cores; results never depend on it
};

/// Each Add*Command registers one subcommand on `app`; its callback throws InputError on bad
/// input (main() prints it and exits 2) and returns normally on success.
/// A command registers itself by adding one line to kCommands in main.cpp.
/// Adds the shared --threads option to a subcommand.
inline void AddThreadsOption(CLI::App* sub, CommonOptions& common) {
    sub->add_option("--threads", common.threads, "worker threads (0 = all cores)")
        ->check(ThreadsCheck());
}

using AddCommandFn = void (*)(CLI::App& app, CommonOptions& common);

}  // namespace casmap::app
