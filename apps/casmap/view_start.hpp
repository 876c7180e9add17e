#pragma once

// Starting the page of `casmap view` (view/server.hpp) from a command: `casmap view` itself
// and `casmap live --view`.

#include <memory>
#include <optional>
#include <string>

#include "casmap/view/server.hpp"

namespace casmap::app {

/// Serves `dir` (as `kind`, or as classified) on host:port, started; warns on stderr
/// ("casmap <command>: warning: --host H makes DIR readable by anyone ...") when `host` is not
/// a loopback address.
[[nodiscard]] std::unique_ptr<view::Server> StartViewServer(const std::string& command,
                                                            const std::string& dir,
                                                            std::optional<view::FolderKind> kind,
                                                            const std::string& host,
                                                            int port);

}  // namespace casmap::app
