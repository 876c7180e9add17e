#include "casmap/view/server.hpp"

#include <arpa/inet.h>
#include <httplib.h>
#include <sys/socket.h>

#include <chrono>
#include <condition_variable>
#include <mutex>
#include <thread>

#include "casmap/core/input_error.hpp"

namespace casmap::view {
namespace {

constexpr std::size_t kMaxTargetBytes = 4096;  // request line target (path + query)
constexpr std::size_t kMaxBodyBytes = 1024;    // GET and HEAD carry none

void Forward(const Site& site, const httplib::Request& req, httplib::Response& res) {
    Response out;
    if (req.target.size() > kMaxTargetBytes) {
        out = Response{414, "text/plain; charset=utf-8", "request target too long\n"};
    } else {
        Request in;
        in.method = req.method;
        in.path = req.path;
        for (const auto& [key, value] : req.params) {
            in.query.emplace(key, value);  // first value of a repeated key
        }
        try {
            out = site.Handle(in);
        } catch (const std::exception& e) {
            out = Response{500, "text/plain; charset=utf-8", std::string(e.what()) + "\n"};
        }
    }
    res.status = out.status;
    res.set_header("Cache-Control", "no-store");
    res.set_header("X-Content-Type-Options", "nosniff");
    // The page loads nothing from the network: only this server's own files.
    res.set_header("Content-Security-Policy",
                   "default-src 'self'; img-src 'self' data: blob:; object-src 'none'; "
                   "frame-ancestors 'none'");
    if (out.status == 405) {
        res.set_header("Allow", "GET, HEAD");
    }
    res.set_content(std::move(out.body), out.content_type.c_str());
}

}  // namespace

bool IsLoopback(const std::string& host) {
    if (host == "localhost" || host == "::1") {
        return true;
    }
    in_addr addr{};
    return inet_pton(AF_INET, host.c_str(), &addr) == 1 && (ntohl(addr.s_addr) >> 24) == 127U;
}

struct Server::Impl {
    Site site;
    ServerOptions options;
    httplib::Server http;
    std::thread thread;
    int port = 0;
    std::mutex mutex;
    std::condition_variable stopped_cv;
    bool stopped = false;

    Impl(const SiteOptions& s, const ServerOptions& o) : site(s), options(o) {}
};

Server::Server(const SiteOptions& site, const ServerOptions& options)
    : impl_(std::make_unique<Impl>(site, options)) {
    if (options.port < 0 || options.port > 65535) {
        throw MakeInputError("", "port", std::to_string(options.port), "allowed: 0..65535");
    }
    httplib::Server& http = impl_->http;
    // httplib's default sets SO_REUSEPORT, which lets a second server share a busy port: only
    // SO_REUSEADDR here, so a port in use is refused.
    http.set_socket_options([](int sock) {
        int yes = 1;
        setsockopt(sock, SOL_SOCKET, SO_REUSEADDR, &yes, sizeof(yes));
    });
    http.set_payload_max_length(kMaxBodyBytes);
    http.set_read_timeout(5, 0);
    http.set_write_timeout(10, 0);
    http.set_keep_alive_max_count(100);
    // Every request, whatever its method, goes to the site: it answers 405 to all but GET and
    // HEAD before any body is read.
    const Site& s = impl_->site;
    http.set_pre_routing_handler([&s](const httplib::Request& req, httplib::Response& res) {
        Forward(s, req, res);
        return httplib::Server::HandlerResponse::Handled;
    });
}

Server::~Server() { Stop(); }

void Server::Start() {
    Impl& impl = *impl_;
    const std::string& host = impl.options.host;
    in_addr v4{};
    in6_addr v6{};
    if (host != "localhost" && inet_pton(AF_INET, host.c_str(), &v4) != 1 &&
        inet_pton(AF_INET6, host.c_str(), &v6) != 1) {
        throw MakeInputError("", "host", host, "must be an IP address of this machine");
    }
    if (impl.options.port == 0) {
        impl.port = impl.http.bind_to_any_port(host);
        if (impl.port < 0) {
            impl.port = 0;
        }
    } else if (impl.http.bind_to_port(host, impl.options.port)) {
        impl.port = impl.options.port;
    }
    if (impl.port == 0) {
        throw MakeInputError("", "port", std::to_string(impl.options.port),
                             "cannot listen on " + host + ": port busy or not permitted");
    }
    impl.thread = std::thread([&impl] {
        impl.http.listen_after_bind();
        const std::lock_guard<std::mutex> lock(impl.mutex);
        impl.stopped = true;
        impl.stopped_cv.notify_all();
    });
    // httplib's stop() does nothing until listen has begun: wait for it, so that a Stop()
    // right after Start() cannot leave the thread listening.
    std::unique_lock<std::mutex> lock(impl.mutex);
    while (!impl.http.is_running() && !impl.stopped) {
        lock.unlock();
        std::this_thread::sleep_for(std::chrono::milliseconds(1));
        lock.lock();
    }
}

void Server::Stop() {
    if (impl_ && impl_->thread.joinable()) {
        impl_->http.stop();
        impl_->thread.join();
    }
}

void Server::Wait() {
    std::unique_lock<std::mutex> lock(impl_->mutex);
    impl_->stopped_cv.wait(lock, [this] { return impl_->stopped || impl_->port == 0; });
}

int Server::port() const { return impl_->port; }

const Site& Server::site() const { return impl_->site; }

std::string Server::Url() const {
    const std::string& host = impl_->options.host;
    const std::string shown = host.find(':') != std::string::npos ? "[" + host + "]" : host;
    return "http://" + shown + ":" + std::to_string(impl_->port) + "/";
}

}  // namespace casmap::view
