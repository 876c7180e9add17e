#pragma once

#include <string>

namespace casmap::drivers {

/// A pseudo-terminal master with a stable symlink to its slave. The slave is kept open by the
/// owner (so reads on the master never fail with EIO while no client has it open) and is in raw
/// mode from the start (no echo, no CR/LF translation).
class PseudoTerminal {
public:
    PseudoTerminal() = default;
    ~PseudoTerminal();
    PseudoTerminal(const PseudoTerminal&) = delete;
    PseudoTerminal& operator=(const PseudoTerminal&) = delete;

    /// posix_openpt + grantpt + unlockpt; raw slave at `baud`; symlink `link_path` -> slave
    /// (replaced atomically; "" = no link). Throws std::system_error, or InputError if the
    /// link path exists and is not a symlink.
    void Open(const std::string& link_path, int baud);
    /// Closes both sides (clients see a hang-up) and removes the link.
    void Close();
    [[nodiscard]] bool IsOpen() const { return master_ >= 0; }
    [[nodiscard]] int master_fd() const { return master_; }
    [[nodiscard]] const std::string& slave_path() const { return slave_path_; }
    /// The client's terminal speed as baud (read from the master side), 0 if unknown.
    [[nodiscard]] int ClientBaud() const;
    /// Bytes written to the master that the client has not read yet.
    [[nodiscard]] int Unread() const;

private:
    int master_ = -1;
    int keeper_ = -1;  // our own slave fd
    std::string slave_path_;
    std::string link_path_;
};

}  // namespace casmap::drivers
