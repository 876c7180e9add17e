// casmap: one CLI with subcommands wiring scenes, simulator, rigs, mapper, filters and drivers.
// Exit status: 0 success, 2 bad input (one line naming file, field and rule), 1 anything else.
#include <cstdio>
#include <exception>
#include <new>
#include <string>

#include "apps/casmap/commands.hpp"
#include "apps/casmap/flag_checks.hpp"
#include "casmap/core/input_error.hpp"

namespace casmap::app {
// Declarations of the subcommands (defined in *_command.cpp).
// BEGIN COMMAND DECLARATIONS
void AddMapCommand(CLI::App& app, CommonOptions& common);
#ifdef CASMAP_WITH_SIM
void AddSimulateCommand(CLI::App& app, CommonOptions& common);
void AddBenchCommand(CLI::App& app, CommonOptions& common);
void AddSweepCommand(CLI::App& app, CommonOptions& common);
#endif
#ifdef CASMAP_WITH_SIM
void AddTruthCommand(CLI::App& app, CommonOptions& common);
#endif
#ifdef CASMAP_WITH_SIM
void AddScanCommand(CLI::App& app, CommonOptions& common);
void AddMixedPixelsCommand(CLI::App& app, CommonOptions& common);
void AddDatasetCommand(CLI::App& app, CommonOptions& common);
#endif
void AddServeCommand(CLI::App& app, CommonOptions& common);
void AddRecordCommand(CLI::App& app, CommonOptions& common);
void AddFilterCommand(CLI::App& app, CommonOptions& common);
void AddDemoCommand(CLI::App& app, CommonOptions& common);
void AddLiveCommand(CLI::App& app, CommonOptions& common);
#ifdef CASMAP_WITH_VIEW
void AddViewCommand(CLI::App& app, CommonOptions& common);
#endif
// END COMMAND DECLARATIONS
}  // namespace casmap::app

int main(int argc, char** argv) {
    using namespace casmap::app;
    CLI::App app{"casmap: terrain mapping with 2-D laser rangefinders and the CAS filter"};
    app.require_subcommand(1);
    CommonOptions common;
    // BEGIN COMMAND REGISTRATION
    AddMapCommand(app, common);
#ifdef CASMAP_WITH_SIM
    AddSimulateCommand(app, common);
    AddBenchCommand(app, common);
    AddSweepCommand(app, common);
#endif
#ifdef CASMAP_WITH_SIM
    AddTruthCommand(app, common);
#endif
#ifdef CASMAP_WITH_SIM
    AddScanCommand(app, common);
    AddMixedPixelsCommand(app, common);
    AddDatasetCommand(app, common);
#endif
    AddServeCommand(app, common);
    AddRecordCommand(app, common);
    AddFilterCommand(app, common);
    AddDemoCommand(app, common);
    AddLiveCommand(app, common);
#ifdef CASMAP_WITH_VIEW
    AddViewCommand(app, common);
#endif
    // END COMMAND REGISTRATION
    AddFlagChecks(app);
    try {
        app.parse(argc, argv);
    } catch (const CLI::CallForHelp& e) {
        return app.exit(e);
    } catch (const CLI::CallForAllHelp& e) {
        return app.exit(e);
    } catch (const CLI::RuntimeError& e) {  // a command's own exit status (e.g. dataset)
        return e.get_exit_code();
    } catch (const CLI::ParseError& e) {
        std::fprintf(stderr, "casmap: %s\n", e.what());
        return 2;
    } catch (const casmap::InputError& e) {
        std::fprintf(stderr, "casmap: %s\n", e.what());
        return 2;
    } catch (const std::bad_alloc&) {
        // Sizes from files and flags are bounded (docs/limits.md); this is the machine's limit.
        std::fprintf(stderr, "casmap: error: out of memory (see docs/limits.md)\n");
        return 1;
    } catch (const std::exception& e) {
        std::fprintf(stderr, "casmap: error: %s\n", e.what());
        return 1;
    }
    return 0;
}
