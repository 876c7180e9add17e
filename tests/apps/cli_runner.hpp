#pragma once

// Runs the built casmap binary (CASMAP_EXE) for the CLI tests and captures what it prints.
#include <sys/wait.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

namespace casmap::test {

struct Result {
    int code = -1;       // exit status, -1 if the process did not exit normally
    std::string output;  // stdout and stderr together
};

/// Runs `cmd` through the shell with stderr folded into stdout.
inline Result Shell(const std::string& cmd) {
    Result r;
    FILE* pipe = popen((cmd + " 2>&1").c_str(), "r");
    char buffer[4096];
    while (pipe != nullptr && fgets(buffer, sizeof(buffer), pipe) != nullptr) {
        r.output += buffer;
    }
    const int status = pipe != nullptr ? pclose(pipe) : -1;
    r.code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    return r;
}

/// The whole text of a file ("" if it cannot be read).
inline std::string ReadText(const std::filesystem::path& path) {
    std::ifstream in(path, std::ios::binary);
    std::ostringstream s;
    s << in.rdbuf();
    return s.str();
}

/// Runs `casmap ARGS`.
inline Result Casmap(const std::string& args) {
    return Shell(std::string(CASMAP_EXE) + " " + args);
}

}  // namespace casmap::test
