#pragma once

// The HTTP server behind `casmap view` and `casmap live --view`: cpp-httplib on a background
// thread forwarding every request to a Site (site.hpp). Read-only, bounded requests, loopback
// unless the caller asks otherwise. httplib stays inside server.cpp.

#include <memory>
#include <string>

#include "casmap/view/site.hpp"

namespace casmap::view {

struct ServerOptions {
    std::string host = "127.0.0.1";  // bind address; anything but loopback exposes DIR
    int port = 8080;                 // 0 = any free port (see Server::port())
};

/// True for 127.0.0.0/8, ::1 and "localhost".
[[nodiscard]] bool IsLoopback(const std::string& host);

class Server {
public:
    /// Builds the site (throws InputError for a bad DIR or web folder); does not bind yet.
    Server(const SiteOptions& site, const ServerOptions& options);
    ~Server();
    Server(const Server&) = delete;
    Server& operator=(const Server&) = delete;

    /// Binds and serves on a background thread. Throws InputError naming --port (busy or
    /// not permitted) or --host (not an address of this machine).
    void Start();
    /// Stops serving and joins the thread (also done by the destructor).
    void Stop();
    /// Blocks until Stop() is called from another thread.
    void Wait();

    /// The bound port (the chosen one when ServerOptions::port was 0); 0 before Start().
    [[nodiscard]] int port() const;
    [[nodiscard]] const Site& site() const;
    /// "http://127.0.0.1:8080/".
    [[nodiscard]] std::string Url() const;

private:
    struct Impl;
    std::unique_ptr<Impl> impl_;
};

}  // namespace casmap::view
