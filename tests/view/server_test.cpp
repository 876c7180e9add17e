#include "casmap/view/server.hpp"

#include <gtest/gtest.h>
#include <httplib.h>

#include <filesystem>
#include <string>

#include "casmap/core/input_error.hpp"
#include "tests/view/test_dir.hpp"

namespace casmap::view {
namespace {
namespace fs = std::filesystem;

class ServerTest : public ::testing::Test {
protected:
    void SetUp() override {
        dir_ = test::FreshDir("server");
        test::WriteText(dir_ / "bench.json", R"({"runs": []})");
    }
    void TearDown() override { fs::remove_all(dir_); }
    [[nodiscard]] SiteOptions Options() const {
        return SiteOptions{dir_, fs::path(CASMAP_SOURCE_DIR) / "view" / "web", {}};
    }
    fs::path dir_;
};

TEST_F(ServerTest, ServesOverHttpOnLoopback) {
    Server server(Options(), ServerOptions{"127.0.0.1", 0});
    server.Start();
    ASSERT_GT(server.port(), 0);
    httplib::Client client("127.0.0.1", server.port());
    const httplib::Result r = client.Get("/files/bench.json");
    ASSERT_TRUE(r);
    EXPECT_EQ(r->status, 200);
    EXPECT_EQ(r->body, R"({"runs": []})");
    EXPECT_EQ(r->get_header_value("Cache-Control"), "no-store");
    const httplib::Result head = client.Head("/files/bench.json");
    ASSERT_TRUE(head);
    EXPECT_EQ(head->status, 200);
    EXPECT_TRUE(head->body.empty());
    server.Stop();
}

TEST_F(ServerTest, RefusesWritesAndLongTargets) {
    Server server(Options(), ServerOptions{"127.0.0.1", 0});
    server.Start();
    httplib::Client client("127.0.0.1", server.port());
    const httplib::Result post = client.Post("/files/bench.json", "x", "text/plain");
    ASSERT_TRUE(post);
    EXPECT_EQ(post->status, 405);
    const httplib::Result del = client.Delete("/files/bench.json");
    ASSERT_TRUE(del);
    EXPECT_EQ(del->status, 405);
    const httplib::Result longer = client.Get("/files/" + std::string(5000, 'a'));
    ASSERT_TRUE(longer);
    EXPECT_EQ(longer->status, 414);
    const httplib::Result dotdot = client.Get("/files/%2e%2e/bench.json");
    ASSERT_TRUE(dotdot);
    EXPECT_EQ(dotdot->status, 400);
    EXPECT_TRUE(fs::exists(dir_ / "bench.json"));
}

TEST_F(ServerTest, BusyPortIsAnInputErrorNamingPort) {
    Server first(Options(), ServerOptions{"127.0.0.1", 0});
    first.Start();
    Server second(Options(), ServerOptions{"127.0.0.1", first.port()});
    try {
        second.Start();
        FAIL() << "expected InputError";
    } catch (const InputError& e) {
        EXPECT_EQ(std::string(e.what()).rfind("port = ", 0), 0U) << e.what();  // a field, no flag
    }
}

TEST_F(ServerTest, HostMustBeAnAddress) {
    Server server(Options(), ServerOptions{"not a host", 0});
    EXPECT_THROW(server.Start(), InputError);
}

TEST(IsLoopback, KnowsLoopbackAddresses) {
    EXPECT_TRUE(IsLoopback("127.0.0.1"));
    EXPECT_TRUE(IsLoopback("127.1.2.3"));
    EXPECT_TRUE(IsLoopback("::1"));
    EXPECT_TRUE(IsLoopback("localhost"));
    EXPECT_FALSE(IsLoopback("0.0.0.0"));
    EXPECT_FALSE(IsLoopback("192.168.1.2"));
}

}  // namespace
}  // namespace casmap::view
