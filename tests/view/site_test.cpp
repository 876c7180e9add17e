#include "casmap/view/site.hpp"

#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <limits>
#include <nlohmann/json.hpp>
#include <string>

#include "casmap/core/input_error.hpp"
#include "casmap/io/image.hpp"
#include "casmap/io/run_file.hpp"
#include "tests/view/test_dir.hpp"

namespace casmap::view {
namespace {
namespace fs = std::filesystem;

const fs::path kWeb = fs::path(CASMAP_SOURCE_DIR) / "view" / "web";

core::MapF RampMap(int rows, int cols) {
    core::MapF map(rows, cols);
    for (int r = 0; r < rows; ++r) {
        for (int c = 0; c < cols; ++c) {
            map.at(r, c) = 0.01F * static_cast<float>(r * cols + c);
        }
    }
    map.at(0, 1) = std::numeric_limits<float>::quiet_NaN();
    return map;
}

/// Decodes EncodeMap's bytes.
core::MapF Decode(const std::string& body) {
    EXPECT_EQ(body.substr(0, 4), "CMF1");
    std::uint32_t rows = 0;
    std::uint32_t cols = 0;
    std::memcpy(&rows, body.data() + 4, 4);
    std::memcpy(&cols, body.data() + 8, 4);
    core::MapF map(static_cast<int>(rows), static_cast<int>(cols));
    EXPECT_EQ(body.size(), 12 + map.data.size() * 4);
    std::memcpy(map.data.data(), body.data() + 12, map.data.size() * 4);
    return map;
}

class SiteTest : public ::testing::Test {
protected:
    void SetUp() override {
        base_ = test::FreshDir("site");
        dir_ = base_ / "bench";
        test::WriteText(dir_ / "bench.json", R"({"runs": []})");
        test::WriteText(base_ / "secret.txt", "outside");
        fs::create_directories(dir_ / "runs" / "course04_T");
        io::WriteMapTiff(dir_ / "runs" / "course04_T" / "raw.tif", RampMap(5, 3));
    }
    void TearDown() override { fs::remove_all(base_); }
    [[nodiscard]] Site MakeSite() const { return Site(SiteOptions{dir_, kWeb, {}}); }
    static Response Get(const Site& site,
                        const std::string& path,
                        std::map<std::string, std::string> query = {}) {
        return site.Handle(Request{"GET", path, std::move(query)});
    }
    fs::path base_;
    fs::path dir_;
};

TEST_F(SiteTest, ServesThePageAndItsAssets) {
    const Site site = MakeSite();
    const Response page = Get(site, "/");
    EXPECT_EQ(page.status, 200);
    EXPECT_EQ(page.content_type, "text/html; charset=utf-8");
    EXPECT_NE(page.body.find("<html"), std::string::npos);
    EXPECT_EQ(Get(site, "/web/app.js").content_type, "text/javascript; charset=utf-8");
    EXPECT_EQ(Get(site, "/web/../bench.json").status, 400);
}

TEST_F(SiteTest, InfoNamesTheKind) {
    const nlohmann::json info = nlohmann::json::parse(Get(MakeSite(), "/api/info").body);
    EXPECT_EQ(info["kind"], "bench");
    EXPECT_EQ(info["name"], "bench");
}

TEST_F(SiteTest, ServesFilesUnderDirAsTheyAre) {
    const Response r = Get(MakeSite(), "/files/bench.json");
    EXPECT_EQ(r.status, 200);
    EXPECT_EQ(r.content_type, "application/json");
    EXPECT_EQ(r.body, R"({"runs": []})");
}

TEST_F(SiteTest, RefusesDotDotWith400) {
    const Site site = MakeSite();
    EXPECT_EQ(Get(site, "/files/../secret.txt").status, 400);
    EXPECT_EQ(Get(site, "/api/list", {{"path", ".."}}).status, 400);
    EXPECT_EQ(Get(site, "/api/map", {{"path", "runs/../../secret.txt"}}).status, 400);
}

TEST_F(SiteTest, RefusesSymlinksOutWith403AndHidesThemInListings) {
    fs::create_symlink(base_ / "secret.txt", dir_ / "leak.txt");
    const Site site = MakeSite();
    const Response r = Get(site, "/files/leak.txt");
    EXPECT_EQ(r.status, 403);
    EXPECT_EQ(r.body.find("outside\n"), std::string::npos);
    const nlohmann::json list = nlohmann::json::parse(Get(site, "/api/list").body);
    for (const auto& e : list["entries"]) {
        EXPECT_NE(e["name"], "leak.txt");
    }
    EXPECT_EQ(list["entries"].size(), 2U);  // bench.json, runs
}

// mtime_ns counts from 1970, as its name says (it was the file clock's count: negative).
TEST_F(SiteTest, ListingMtimeIsUnixTime) {
    const Site site = MakeSite();
    const nlohmann::json list = nlohmann::json::parse(Get(site, "/api/list").body);
    ASSERT_FALSE(list["entries"].empty());
    const std::int64_t now_ns = std::chrono::duration_cast<std::chrono::nanoseconds>(
                                    std::chrono::system_clock::now().time_since_epoch())
                                    .count();
    constexpr std::int64_t kDayNs = 86'400'000'000'000;
    for (const auto& e : list["entries"]) {
        const std::int64_t mtime = e["mtime_ns"].get<std::int64_t>();
        EXPECT_GT(mtime, now_ns - kDayNs) << e["name"];  // written by this test's fixture
        EXPECT_LT(mtime, now_ns + kDayNs) << e["name"];
    }
}

TEST_F(SiteTest, OnlyGetAndHead) {
    const Site site = MakeSite();
    for (const char* method : {"POST", "PUT", "DELETE", "PATCH", "OPTIONS"}) {
        EXPECT_EQ(site.Handle(Request{method, "/files/bench.json", {}}).status, 405) << method;
    }
    EXPECT_EQ(site.Handle(Request{"HEAD", "/files/bench.json", {}}).status, 200);
}

TEST_F(SiteTest, UnknownRouteAndFolderAre404) {
    const Site site = MakeSite();
    EXPECT_EQ(Get(site, "/nothing").status, 404);
    EXPECT_EQ(Get(site, "/files/missing.json").status, 404);
    EXPECT_EQ(Get(site, "/files/runs").status, 404);  // a folder is listed, not served
}

TEST_F(SiteTest, MapEndpointReturnsTheTiffValues) {
    const Response r = Get(MakeSite(), "/api/map", {{"path", "runs/course04_T/raw.tif"}});
    ASSERT_EQ(r.status, 200);
    const core::MapF back = Decode(r.body);
    const core::MapF want = RampMap(5, 3);
    ASSERT_EQ(back.rows, 5);
    ASSERT_EQ(back.cols, 3);
    EXPECT_TRUE(std::isnan(back.at(0, 1)));
    EXPECT_EQ(back.at(4, 2), want.at(4, 2));
    EXPECT_EQ(back.at(2, 0), want.at(2, 0));
}

TEST_F(SiteTest, MapOfANonTiffIs422) {
    EXPECT_EQ(Get(MakeSite(), "/api/map", {{"path", "bench.json"}}).status, 422);
}

TEST_F(SiteTest, RunFileLayersAndMaps) {
    io::RunData run;
    run.maps.grid = core::GridGeometry{1.0, -2.0, 0.025, 5, 3};
    run.maps.elevation_m = RampMap(5, 3);
    run.maps.filtered["cas"] = RampMap(5, 3);
    run.maps.cas_classes = core::Raster<std::uint8_t>(5, 3, 2);
    fs::create_directories(dir_ / "samples");
    io::WriteRunFile(dir_ / "samples" / "000000.h5", run);
    const Site site = MakeSite();
    const nlohmann::json info =
        nlohmann::json::parse(Get(site, "/api/run", {{"path", "samples/000000.h5"}}).body);
    EXPECT_EQ(info["grid"]["x0_m"], 1.0);
    EXPECT_EQ(info["grid"]["rows"], 5);
    EXPECT_EQ(info["layers"],
              nlohmann::json::array({"elevation_m", "filtered/cas", "cas_classes"}));
    const Response map =
        Get(site, "/api/runmap", {{"path", "samples/000000.h5"}, {"layer", "filtered/cas"}});
    ASSERT_EQ(map.status, 200);
    EXPECT_EQ(Decode(map.body).at(3, 2), RampMap(5, 3).at(3, 2));
    const Response classes =
        Get(site, "/api/runmap", {{"path", "samples/000000.h5"}, {"layer", "cas_classes"}});
    ASSERT_EQ(classes.status, 200);
    EXPECT_EQ(Decode(classes.body).at(4, 1), 2.0F);
    EXPECT_EQ(
        Get(site, "/api/runmap", {{"path", "samples/000000.h5"}, {"layer", "truth_m"}}).status,
        404);
}

TEST_F(SiteTest, LargeFilesAreRefused) {
    SiteOptions options{dir_, kWeb, {}};
    options.max_file_bytes = 4;
    EXPECT_EQ(Get(Site(options), "/files/bench.json").status, 413);
}

TEST(ClassifyFolder, TellsTheKindFromTheMarkerFile) {
    const fs::path dir = test::FreshDir("classify");
    test::WriteText(dir / "sweep" / "sweep.json", "{}");
    test::WriteText(dir / "data" / "manifest.jsonl", "");
    test::WriteText(dir / "live" / "status.json", "{}");
    EXPECT_EQ(ClassifyFolder(dir / "sweep"), FolderKind::kSweep);
    EXPECT_EQ(ClassifyFolder(dir / "data"), FolderKind::kDataset);
    EXPECT_EQ(ClassifyFolder(dir / "live"), FolderKind::kLive);
    fs::remove_all(dir);
}

TEST(ClassifyFolder, RejectsAFolderWithoutMarkerNamingIt) {
    const fs::path dir = test::FreshDir("empty");
    try {
        (void)ClassifyFolder(dir);
        FAIL() << "expected InputError";
    } catch (const InputError& e) {
        EXPECT_NE(std::string(e.what()).find(dir.string()), std::string::npos);
        EXPECT_NE(std::string(e.what()).find("bench.json"), std::string::npos);
    }
    EXPECT_THROW((void)ClassifyFolder(dir / "missing"), InputError);
    fs::remove_all(dir);
}

TEST(ClassifyFolder, ExplicitKindServesAFolderWithoutMarker) {
    const fs::path dir = test::FreshDir("live");
    const Site site(SiteOptions{dir, kWeb, FolderKind::kLive});
    EXPECT_EQ(site.kind(), FolderKind::kLive);
    fs::remove_all(dir);
}

}  // namespace
}  // namespace casmap::view
