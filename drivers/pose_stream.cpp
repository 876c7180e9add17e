#include "casmap/drivers/pose_stream.hpp"

#include <arpa/inet.h>
#include <fcntl.h>
#include <netinet/in.h>
#include <sys/socket.h>
#include <sys/stat.h>
#include <sys/un.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <optional>

#include "casmap/core/input_error.hpp"
#include "casmap/core/limits.hpp"
#include "casmap/drivers/pose_file.hpp"

namespace casmap::drivers {

bool PoseStream::Accept(const core::TimedPose& p, std::vector<core::TimedPose>& out) {
    if (!(p.stamp_s > last_stamp_s_)) {
        ++counters_.out_of_order;
        return false;
    }
    last_stamp_s_ = p.stamp_s;
    out.push_back(p);
    ++counters_.poses;
    return true;
}

PoseFileFollower::PoseFileFollower(std::string path) : path_(std::move(path)) {
    if (path_.empty()) {
        throw MakeInputError("command line", "pose file", "", "must not be empty");
    }
}

PoseFileFollower::~PoseFileFollower() {
    if (fd_ >= 0) {
        ::close(fd_);
    }
}

void PoseFileFollower::Poll(std::vector<core::TimedPose>& out) {
    struct stat st {};
    if (::stat(path_.c_str(), &st) == 0 && fd_ >= 0 && st.st_ino != inode_) {
        ::close(fd_);  // replaced: read the new file, skipping what was delivered
        fd_ = -1;
        replaced_ = true;
    }
    if (fd_ < 0) {
        fd_ = ::open(path_.c_str(), O_RDONLY | O_CLOEXEC);
        if (fd_ < 0) {
            return;  // not there yet
        }
        struct stat opened {};
        ::fstat(fd_, &opened);
        inode_ = opened.st_ino;
        partial_.clear();
        line_no_ = 0;
    }
    char buf[65536];
    // At most 1 MiB per poll (an endless source such as /dev/zero must not keep us here), and
    // no line longer than the pose-file line limit (docs/limits.md).
    for (std::size_t total = 0; total < (std::size_t{1} << 20);) {
        const ssize_t n = ::read(fd_, buf, sizeof(buf));
        if (n <= 0) {
            break;
        }
        partial_.append(buf, static_cast<std::size_t>(n));
        total += static_cast<std::size_t>(n);
        const std::size_t last_nl = partial_.rfind('\n');
        const std::size_t tail =
            last_nl == std::string::npos ? partial_.size() : partial_.size() - last_nl - 1;
        if (tail > core::limits::kMaxPoseLineBytes) {
            throw MakeInputError(path_ + ":" + std::to_string(line_no_ + 1), "line", "",
                                 "longer than " + std::to_string(core::limits::kMaxPoseLineBytes) +
                                     " bytes, see docs/limits.md");
        }
    }
    std::size_t start = 0;
    for (std::size_t nl = partial_.find('\n'); nl != std::string::npos;
         nl = partial_.find('\n', start)) {
        ++line_no_;
        const std::string where = path_ + ":" + std::to_string(line_no_);
        const std::optional<core::TimedPose> p =
            ParsePoseLine(partial_.substr(start, nl - start), where);
        start = nl + 1;
        if (!p) {
            continue;
        }
        if (replaced_ && p->stamp_s <= last_stamp_s_) {
            continue;  // delivered from the file this one replaced
        }
        if (!Accept(*p, out)) {
            char stamp[64];
            std::snprintf(stamp, sizeof(stamp), "%.17g", p->stamp_s);
            throw MakeInputError(where, "stamp_s", stamp, "strictly increasing");
        }
    }
    partial_.erase(0, start);
}

PoseSocket::PoseSocket(const std::string& spec) : spec_(spec) {
    const auto fail = [&](const std::string& rule) {
        if (fd_ >= 0) {
            ::close(fd_);
        }
        throw MakeInputError("command line", "pose socket", spec, rule);
    };
    if (spec.rfind("udp:", 0) == 0) {
        char* end = nullptr;
        const long port = std::strtol(spec.c_str() + 4, &end, 10);
        if (end == spec.c_str() + 4 || *end != '\0' || port < 0 || port > 65535) {
            fail("udp:PORT with PORT in 0..65535 (0: any free port)");
        }
        fd_ = ::socket(AF_INET, SOCK_DGRAM | SOCK_NONBLOCK | SOCK_CLOEXEC, 0);
        sockaddr_in addr{};
        addr.sin_family = AF_INET;
        addr.sin_port = htons(static_cast<std::uint16_t>(port));
        addr.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
        if (fd_ < 0 || ::bind(fd_, reinterpret_cast<sockaddr*>(&addr), sizeof(addr)) != 0) {
            fail(std::string("cannot bind 127.0.0.1: ") + std::strerror(errno));
        }
        socklen_t len = sizeof(addr);
        ::getsockname(fd_, reinterpret_cast<sockaddr*>(&addr), &len);
        port_ = ntohs(addr.sin_port);
    } else if (spec.rfind("unix:", 0) == 0) {
        unix_path_ = spec.substr(5);
        sockaddr_un addr{};
        if (unix_path_.empty() || unix_path_.size() >= sizeof(addr.sun_path)) {
            fail("unix:PATH with a path of 1.." + std::to_string(sizeof(addr.sun_path) - 1) +
                 " bytes");
        }
        fd_ = ::socket(AF_UNIX, SOCK_DGRAM | SOCK_NONBLOCK | SOCK_CLOEXEC, 0);
        addr.sun_family = AF_UNIX;
        std::memcpy(addr.sun_path, unix_path_.c_str(), unix_path_.size());
        if (fd_ < 0 || ::bind(fd_, reinterpret_cast<sockaddr*>(&addr), sizeof(addr)) != 0) {
            const std::string why = std::strerror(errno);
            unix_path_.clear();  // not ours to remove
            fail("cannot bind (an existing path is never replaced): " + why);
        }
    } else {
        fail("udp:PORT or unix:PATH");
    }
    // Room for bursts between polls (best effort: the kernel caps it at net.core.rmem_max).
    const int bytes = 1 << 22;
    ::setsockopt(fd_, SOL_SOCKET, SO_RCVBUF, &bytes, sizeof(bytes));
}

PoseSocket::~PoseSocket() {
    if (fd_ >= 0) {
        ::close(fd_);
    }
    if (!unix_path_.empty()) {
        ::unlink(unix_path_.c_str());
    }
}

void PoseSocket::Poll(std::vector<core::TimedPose>& out) {
    char buf[65536];
    for (;;) {
        const ssize_t n = ::recv(fd_, buf, sizeof(buf), 0);
        if (n <= 0) {
            return;  // EAGAIN: nothing more now
        }
        ++datagrams_;
        const std::string text(buf, static_cast<std::size_t>(n));
        std::size_t start = 0;
        int line = 0;
        while (start < text.size()) {
            std::size_t nl = text.find('\n', start);
            if (nl == std::string::npos) {
                nl = text.size();
            }
            ++line;
            const std::string where = spec_ + ": datagram " + std::to_string(datagrams_) +
                                      " line " + std::to_string(line);
            const std::optional<core::TimedPose> p =
                ParsePoseLine(text.substr(start, nl - start), where);
            if (p) {
                (void)Accept(*p, out);
            }
            start = nl + 1;
        }
    }
}

}  // namespace casmap::drivers
