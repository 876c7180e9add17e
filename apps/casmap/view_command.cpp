// casmap view DIR [--port P] [--host 127.0.0.1]
// A read-only local web page for what DIR holds: a benchmark (casmap bench), a sweep (casmap
// sweep), a dataset (casmap dataset) or a live run (casmap live). Serves until Ctrl-C. Binds to
// loopback unless --host says otherwise; a bad DIR or a busy port exits 2 with one line.
#include <cstdio>
#include <memory>
#include <string>

#include "apps/casmap/commands.hpp"
#include "apps/casmap/view_start.hpp"

namespace casmap::app {
namespace {

struct ViewOptions {
    std::string dir;
    std::string host = "127.0.0.1";
    int port = 8080;
};

void RunView(const ViewOptions& opt) {
    const auto server = StartViewServer("view", opt.dir, std::nullopt, opt.host, opt.port);
    std::printf("casmap view: %s (%s) at %s (Ctrl-C stops)\n", opt.dir.c_str(),
                view::ToString(server->site().kind()).c_str(), server->Url().c_str());
    std::fflush(stdout);
    server->Wait();
}

}  // namespace

void AddViewCommand(CLI::App& app, CommonOptions& /*common*/) {
    auto opt = std::make_shared<ViewOptions>();
    CLI::App* sub = app.add_subcommand(
        "view", "Local read-only web page for a bench, sweep, dataset or live folder");
    sub->add_option("DIR", opt->dir, "folder written by casmap bench, sweep, dataset or live")
        ->required();
    sub->add_option("--port", opt->port, "TCP port (0 = any free port)")->capture_default_str();
    sub->add_option("--host", opt->host, "bind address (not loopback: readable by others)")
        ->capture_default_str();
    sub->callback([opt] { RunView(*opt); });
}

}  // namespace casmap::app
