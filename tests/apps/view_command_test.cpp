// casmap view: a bad DIR or a busy port is exit 2 with one line (the serving itself is
// tested in tests/view/ and in the browser by scripts/test-view.sh).
#include <arpa/inet.h>
#include <gtest/gtest.h>
#include <netinet/in.h>
#include <sys/socket.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "tests/apps/cli_runner.hpp"
#include "tests/temp_dir.hpp"

namespace casmap::test {
namespace {
namespace fs = std::filesystem;

int Lines(const std::string& text) {
    int n = 0;
    for (const char c : text) {
        n += c == '\n' ? 1 : 0;
    }
    return n;
}

TEST(ViewCommand, MissingDirIsExit2NamingIt) {
    const Result r = Casmap("view /nonexistent/casmap_view_dir --port 0");
    EXPECT_EQ(r.code, 2) << r.output;
    EXPECT_EQ(Lines(r.output), 1) << r.output;
    EXPECT_NE(r.output.find("/nonexistent/casmap_view_dir"), std::string::npos) << r.output;
}

TEST(ViewCommand, FolderWithoutMarkerIsExit2) {
    const casmap::test::TempDir tmp("view_cli_empty");
    const fs::path& dir = tmp.Path();
    const Result r = Casmap("view " + dir.string() + " --port 0");
    EXPECT_EQ(r.code, 2) << r.output;
    EXPECT_EQ(Lines(r.output), 1) << r.output;
    EXPECT_NE(r.output.find("bench.json"), std::string::npos) << r.output;
}

TEST(ViewCommand, BusyPortIsExit2NamingPort) {
    const casmap::test::TempDir tmp("view_cli_busy");
    const fs::path& dir = tmp.Path();
    std::ofstream(dir / "bench.json") << R"({"runs": []})";
    // Hold a loopback port.
    const int sock = socket(AF_INET, SOCK_STREAM, 0);
    ASSERT_GE(sock, 0);
    sockaddr_in addr{};
    addr.sin_family = AF_INET;
    addr.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
    addr.sin_port = 0;
    ASSERT_EQ(bind(sock, reinterpret_cast<sockaddr*>(&addr), sizeof(addr)), 0);
    ASSERT_EQ(listen(sock, 1), 0);
    socklen_t len = sizeof(addr);
    ASSERT_EQ(getsockname(sock, reinterpret_cast<sockaddr*>(&addr), &len), 0);
    const int port = ntohs(addr.sin_port);
    const Result r = Casmap("view " + dir.string() + " --port " + std::to_string(port));
    close(sock);
    EXPECT_EQ(r.code, 2) << r.output;
    EXPECT_EQ(Lines(r.output), 1) << r.output;
    EXPECT_NE(r.output.find("--port"), std::string::npos) << r.output;
}

}  // namespace
}  // namespace casmap::test
