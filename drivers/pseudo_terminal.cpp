#include "casmap/drivers/pseudo_terminal.hpp"

#include <fcntl.h>
#include <stdlib.h>
#include <sys/ioctl.h>
#include <sys/stat.h>
#include <termios.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <system_error>

#include "casmap/core/input_error.hpp"
#include "casmap/drivers/serial_port.hpp"

namespace casmap::drivers {
namespace {
[[noreturn]] void ThrowErrno(const std::string& what) {
    throw std::system_error(errno, std::generic_category(), what);
}
}  // namespace

PseudoTerminal::~PseudoTerminal() { Close(); }

void PseudoTerminal::Open(const std::string& link_path, int baud) {
    Close();
    master_ = posix_openpt(O_RDWR | O_NOCTTY | O_NONBLOCK | O_CLOEXEC);
    if (master_ < 0) {
        ThrowErrno("posix_openpt");
    }
    char name[128];
    if (grantpt(master_) != 0 || unlockpt(master_) != 0 ||
        ptsname_r(master_, name, sizeof(name)) != 0) {
        const int e = errno;
        Close();
        throw std::system_error(e, std::generic_category(), "grantpt/unlockpt/ptsname");
    }
    slave_path_ = name;
    keeper_ = open(name, O_RDWR | O_NOCTTY | O_NONBLOCK | O_CLOEXEC);
    if (keeper_ < 0) {
        const int e = errno;
        Close();
        throw std::system_error(e, std::generic_category(), "open " + slave_path_);
    }
    MakeRaw(keeper_, baud);
    if (!link_path.empty()) {
        struct stat st {};
        if (lstat(link_path.c_str(), &st) == 0 && !S_ISLNK(st.st_mode)) {
            Close();
            throw MakeInputError(link_path, "link_path", "", "exists and is not a symlink");
        }
        const std::string tmp = link_path + ".tmp" + std::to_string(getpid());
        unlink(tmp.c_str());
        if (symlink(slave_path_.c_str(), tmp.c_str()) != 0 ||
            rename(tmp.c_str(), link_path.c_str()) != 0) {
            const int e = errno;
            unlink(tmp.c_str());
            Close();
            if (e == ENOENT || e == ENOTDIR || e == EACCES || e == EROFS || e == EISDIR) {
                throw MakeInputError(link_path, "link_path", "",
                                     std::string("cannot create the link: ") + std::strerror(e));
            }
            throw std::system_error(e, std::generic_category(), "symlink " + link_path);
        }
        link_path_ = link_path;
    }
}

void PseudoTerminal::Close() {
    if (!link_path_.empty()) {
        unlink(link_path_.c_str());
        link_path_.clear();
    }
    if (keeper_ >= 0) {
        close(keeper_);
        keeper_ = -1;
    }
    if (master_ >= 0) {
        close(master_);
        master_ = -1;
    }
}

int PseudoTerminal::ClientBaud() const {
    termios tio{};
    if (master_ < 0 || tcgetattr(master_, &tio) != 0) {
        return 0;
    }
    return BaudOfSpeed(static_cast<unsigned>(cfgetospeed(&tio)));
}

}  // namespace casmap::drivers

namespace casmap::drivers {
int PseudoTerminal::Unread() const {
    int n = 0;
    if (keeper_ < 0 || ioctl(keeper_, FIONREAD, &n) != 0) {
        return 0;
    }
    return n;
}
}  // namespace casmap::drivers
