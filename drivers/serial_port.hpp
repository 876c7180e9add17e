#pragma once

// POSIX serial port in raw 8N1 mode (termios), no flow control, with poll()-based timeouts.

#include <cstddef>
#include <cstdint>
#include <span>
#include <stdexcept>
#include <string>

namespace casmap::drivers {

/// The device went away (hang-up, EIO, closed pty) or an I/O call failed. The driver reacts
/// by reconnecting; InputError is reserved for bad paths and baud rates.
class SerialError : public std::runtime_error {
public:
    explicit SerialError(const std::string& message) : std::runtime_error(message) {}
};

/// termios speed constant for a baud rate, or 0 if the rate has none.
[[nodiscard]] unsigned SpeedConstant(int baud);
/// Baud rate of a termios speed constant, or 0.
[[nodiscard]] int BaudOfSpeed(unsigned speed);

/// Puts an open terminal fd into raw 8N1 mode at `baud` (no echo, no CR/LF translation,
/// no flow control, VMIN = VTIME = 0). Throws SerialError.
void MakeRaw(int fd, int baud);

class SerialPort {
public:
    /// Opens `path` (O_RDWR | O_NOCTTY | O_NONBLOCK) in raw mode at `baud` and flushes it.
    /// Throws InputError if the path does not exist, is not a terminal, or `baud` has no
    /// termios constant; SerialError for other failures.
    SerialPort(const std::string& path, int baud);
    ~SerialPort();
    SerialPort(const SerialPort&) = delete;
    SerialPort& operator=(const SerialPort&) = delete;

    /// Changes the line rate (after draining output). Throws InputError / SerialError.
    void SetBaud(int baud);
    [[nodiscard]] int baud() const { return baud_; }
    [[nodiscard]] const std::string& path() const { return path_; }

    /// Writes all bytes, waiting at most `timeout_s` in total. Throws SerialError on failure or
    /// timeout.
    void Write(std::span<const std::uint8_t> bytes, double timeout_s);
    /// Writes one byte at a time with `gap_s` between bytes (as sicktoolbox does).
    void WriteSlowly(std::span<const std::uint8_t> bytes, double gap_s);
    /// Reads what is available into `buffer`, waiting at most `timeout_s` for the first byte.
    /// Returns 0 on timeout. Throws SerialError if the device hung up or failed.
    [[nodiscard]] std::size_t Read(std::span<std::uint8_t> buffer, double timeout_s);
    /// Discards unread input and unsent output (tcflush TCIOFLUSH).
    void Flush();

private:
    std::string path_;
    int fd_ = -1;
    int baud_ = 0;
};

}  // namespace casmap::drivers
