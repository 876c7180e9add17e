#include "casmap/drivers/serial_port.hpp"

#include <fcntl.h>
#include <poll.h>
#include <sys/stat.h>
#include <termios.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <cstring>
#include <thread>

#include "casmap/core/input_error.hpp"

namespace casmap::drivers {
namespace {

std::string Errno(const std::string& what, const std::string& path) {
    return path + ": " + what + ": " + std::strerror(errno);
}

int PollMs(double timeout_s) {
    if (timeout_s <= 0.0) {
        return 0;
    }
    return static_cast<int>(timeout_s * 1000.0 + 0.999);
}

}  // namespace

unsigned SpeedConstant(int baud) {
    switch (baud) {
        case 9600:
            return B9600;
        case 19200:
            return B19200;
        case 38400:
            return B38400;
        case 57600:
            return B57600;
        case 115200:
            return B115200;
        case 500000:
            return B500000;
        default:
            return 0;
    }
}

int BaudOfSpeed(unsigned speed) {
    for (const int b : {9600, 19200, 38400, 57600, 115200, 500000}) {
        if (SpeedConstant(b) == speed) {
            return b;
        }
    }
    return 0;
}

void MakeRaw(int fd, int baud) {
    const unsigned speed = SpeedConstant(baud);
    if (speed == 0) {
        throw MakeInputError("", "baud", std::to_string(baud), "no termios rate");
    }
    termios tio{};
    if (tcgetattr(fd, &tio) != 0) {
        throw SerialError(Errno("tcgetattr", "fd " + std::to_string(fd)));
    }
    cfmakeraw(&tio);
    tio.c_cflag &= ~static_cast<tcflag_t>(CSTOPB | PARENB | CRTSCTS | CSIZE);
    tio.c_cflag |= CS8 | CLOCAL | CREAD;
    tio.c_iflag &= ~static_cast<tcflag_t>(IXON | IXOFF | IXANY);
    tio.c_cc[VMIN] = 0;
    tio.c_cc[VTIME] = 0;
    cfsetispeed(&tio, static_cast<speed_t>(speed));
    cfsetospeed(&tio, static_cast<speed_t>(speed));
    if (tcsetattr(fd, TCSANOW, &tio) != 0) {
        throw SerialError(Errno("tcsetattr", "fd " + std::to_string(fd)));
    }
}

SerialPort::SerialPort(const std::string& path, int baud) : path_(path) {
    if (SpeedConstant(baud) == 0) {
        throw MakeInputError(path, "baud", std::to_string(baud), "no termios rate");
    }
    struct stat st {};
    if (stat(path.c_str(), &st) != 0) {
        throw MakeInputError(path, "device", "",
                             std::string("cannot open: ") + std::strerror(errno));
    }
    if (!S_ISCHR(st.st_mode)) {
        throw MakeInputError(path, "device", "", "not a terminal (not a character device)");
    }
    fd_ = open(path.c_str(), O_RDWR | O_NOCTTY | O_NONBLOCK | O_CLOEXEC);
    if (fd_ < 0) {
        if (errno == ENOENT || errno == EACCES || errno == ENXIO) {
            throw MakeInputError(path, "device", "",
                                 std::string("cannot open: ") + std::strerror(errno));
        }
        throw SerialError(Errno("open", path));
    }
    if (isatty(fd_) == 0) {
        close(fd_);
        fd_ = -1;
        throw MakeInputError(path, "device", "", "not a terminal");
    }
    try {
        MakeRaw(fd_, baud);
    } catch (...) {
        close(fd_);
        fd_ = -1;
        throw;
    }
    baud_ = baud;
    Flush();
}

SerialPort::~SerialPort() {
    if (fd_ >= 0) {
        close(fd_);
    }
}

void SerialPort::SetBaud(int baud) {
    tcdrain(fd_);
    MakeRaw(fd_, baud);
    baud_ = baud;
}

void SerialPort::Write(std::span<const std::uint8_t> bytes, double timeout_s) {
    const auto deadline =
        std::chrono::steady_clock::now() + std::chrono::duration<double>(timeout_s);
    std::size_t done = 0;
    while (done < bytes.size()) {
        const ssize_t n = write(fd_, bytes.data() + done, bytes.size() - done);
        if (n > 0) {
            done += static_cast<std::size_t>(n);
            continue;
        }
        if (n < 0 && errno != EAGAIN && errno != EINTR) {
            throw SerialError(Errno("write", path_));
        }
        const double left =
            std::chrono::duration<double>(deadline - std::chrono::steady_clock::now()).count();
        if (left <= 0.0) {
            throw SerialError(path_ + ": write timed out");
        }
        pollfd p{fd_, POLLOUT, 0};
        if (poll(&p, 1, PollMs(left)) < 0 && errno != EINTR) {
            throw SerialError(Errno("poll", path_));
        }
        if ((p.revents & (POLLHUP | POLLERR | POLLNVAL)) != 0) {
            throw SerialError(path_ + ": device hung up");
        }
    }
}

void SerialPort::WriteSlowly(std::span<const std::uint8_t> bytes, double gap_s) {
    for (std::size_t i = 0; i < bytes.size(); ++i) {
        Write(bytes.subspan(i, 1), 1.0);
        if (gap_s > 0.0 && i + 1 < bytes.size()) {
            std::this_thread::sleep_for(std::chrono::duration<double>(gap_s));
        }
    }
}

std::size_t SerialPort::Read(std::span<std::uint8_t> buffer, double timeout_s) {
    pollfd p{fd_, POLLIN, 0};
    const int r = poll(&p, 1, PollMs(timeout_s));
    if (r < 0) {
        if (errno == EINTR) {
            return 0;
        }
        throw SerialError(Errno("poll", path_));
    }
    if (r == 0) {
        return 0;
    }
    if ((p.revents & POLLIN) == 0 && (p.revents & (POLLHUP | POLLERR | POLLNVAL)) != 0) {
        throw SerialError(path_ + ": device hung up");
    }
    const ssize_t n = read(fd_, buffer.data(), buffer.size());
    if (n > 0) {
        return static_cast<std::size_t>(n);
    }
    if (n == 0) {
        // In raw mode with VMIN = VTIME = 0 a read that finds no data returns 0, which on a
        // loaded machine happens even after poll() said POLLIN (the pty pushes its buffer
        // to the line discipline later). Only a hang-up reported by poll() is the end.
        if ((p.revents & POLLHUP) != 0) {
            throw SerialError(path_ + ": device hung up (end of file)");
        }
        return 0;
    }
    if (errno == EAGAIN || errno == EINTR) {
        return 0;
    }
    throw SerialError(Errno("read", path_));
}

void SerialPort::Flush() { tcflush(fd_, TCIOFLUSH); }

}  // namespace casmap::drivers
