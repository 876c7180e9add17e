#pragma once

// Live pose streams for `casmap live` (docs/pose-file.md "Live pose streams"): the pose-file
// records (stamp_s x_m y_m z_m qx qy qz qw) arriving while a scanner streams, from
//  - a pose file read as it grows (a robot's logger appending lines), or
//  - a datagram socket on the loopback: UDP 127.0.0.1:PORT or a UNIX-domain datagram socket,
//    each datagram carrying one or more complete records.
// Poll() never blocks.

#include <cstdint>
#include <string>
#include <vector>

#include "casmap/core/trajectory.hpp"

namespace casmap::drivers {

struct PoseStreamCounters {
    std::uint64_t poses = 0;         // delivered
    std::uint64_t out_of_order = 0;  // stamp not after the previous one: dropped (sockets)
};

class PoseStream {
public:
    virtual ~PoseStream() = default;
    /// Appends the poses that arrived since the last call, stamps strictly increasing.
    /// Throws InputError naming the source and line for a malformed record.
    virtual void Poll(std::vector<core::TimedPose>& out) = 0;
    [[nodiscard]] virtual std::string name() const = 0;
    [[nodiscard]] const PoseStreamCounters& counters() const { return counters_; }

protected:
    /// Adds a parsed pose if it is after the previous one; else counts it (returns false).
    bool Accept(const core::TimedPose& p, std::vector<core::TimedPose>& out);
    PoseStreamCounters counters_;
    double last_stamp_s_ = -1e300;
};

/// Follows a pose file as it grows: complete lines are parsed as they appear; a file that
/// does not exist yet is waited for; a file replaced (new inode, e.g. written by rename) is
/// reopened and its poses up to the last stamp seen are skipped. A stamp that is not after
/// the previous one is an InputError (the file format's rule).
class PoseFileFollower final : public PoseStream {
public:
    explicit PoseFileFollower(std::string path);
    ~PoseFileFollower() override;
    PoseFileFollower(const PoseFileFollower&) = delete;
    PoseFileFollower& operator=(const PoseFileFollower&) = delete;
    void Poll(std::vector<core::TimedPose>& out) override;
    [[nodiscard]] std::string name() const override { return path_; }

private:
    std::string path_;
    int fd_ = -1;
    std::uint64_t inode_ = 0;
    std::string partial_;  // bytes after the last newline
    int line_no_ = 0;
    bool replaced_ = false;  // skipping poses already delivered from the previous file
};

/// Binds a datagram socket: "udp:PORT" (127.0.0.1 only) or "unix:PATH" (the path must not
/// exist; removed on destruction). Throws InputError for a malformed spec, a port in use or
/// a path that exists. Datagrams whose stamps go backwards are dropped and counted.
class PoseSocket final : public PoseStream {
public:
    explicit PoseSocket(const std::string& spec);
    ~PoseSocket() override;
    PoseSocket(const PoseSocket&) = delete;
    PoseSocket& operator=(const PoseSocket&) = delete;
    void Poll(std::vector<core::TimedPose>& out) override;
    [[nodiscard]] std::string name() const override { return spec_; }
    [[nodiscard]] int port() const { return port_; }  // the bound UDP port (0 for unix)

private:
    std::string spec_;
    std::string unix_path_;
    int fd_ = -1;
    int port_ = 0;
    std::uint64_t datagrams_ = 0;
};

}  // namespace casmap::drivers
