#include "apps/casmap/view_start.hpp"

#include <cstdio>

#include "apps/casmap/flag_names.hpp"

namespace casmap::app {

std::unique_ptr<view::Server> StartViewServer(const std::string& command,
                                              const std::string& dir,
                                              std::optional<view::FolderKind> kind,
                                              const std::string& host,
                                              int port) {
    view::SiteOptions site;
    site.dir = dir;
    site.web_dir = view::FindWebDir();
    site.kind = kind;
    std::unique_ptr<view::Server> server;
    WithCommandLineFlags({{"port", "--port"}, {"host", "--host"}}, [&] {
        server = std::make_unique<view::Server>(site, view::ServerOptions{host, port});
        server->Start();
    });
    if (!view::IsLoopback(host)) {
        std::fprintf(stderr,
                     "casmap %s: warning: --host %s makes %s readable by anyone who can reach "
                     "this machine\n",
                     command.c_str(), host.c_str(), dir.c_str());
    }
    return server;
}

}  // namespace casmap::app
