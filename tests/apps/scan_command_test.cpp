// `casmap scan`: runs the built binary on a scene written here (a floor and a box whose face is
// at x = 2.5 m) and checks the JSON it prints against closed-form ranges.
#include <gtest/gtest.h>
#include <sys/wait.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <sstream>
#include <string>
#include <vector>

#include "tests/apps/cli_runner.hpp"
#include "tests/temp_dir.hpp"

namespace casmap {
namespace {
namespace fs = std::filesystem;

using test::Casmap;
using test::Result;

fs::path SceneFile() {
    const fs::path path = casmap::test::MakeTempDir("scan_cmd") / "casmap_scan_cmd_scene.yaml";
    std::ofstream(path) << "objects:\n"
                           "  - name: floor\n"
                           "    box: {size_m: [40, 40, 0.02]}\n"
                           "    pose: {xyz_m: [0, 0, -0.01], rpy_deg: [0, 0, 0]}\n"
                           "  - name: wall\n"
                           "    box: {size_m: [1, 4, 2]}\n"
                           "    pose: {xyz_m: [3, 0, 0.5], rpy_deg: [0, 0, 0]}\n";
    return path;
}

// The items of `"key": [a, b, ...]` in the printed JSON, as strings.
std::vector<std::string> Field(const std::string& json, const std::string& key) {
    const std::size_t at = json.find("\"" + key + "\": [");
    if (at == std::string::npos) {
        return {};
    }
    const std::size_t begin = json.find('[', at) + 1;
    const std::string body = json.substr(begin, json.find(']', begin) - begin);
    std::vector<std::string> items;
    std::stringstream in(body);
    std::string item;
    while (std::getline(in, item, ',')) {
        items.push_back(item.substr(item.find_first_not_of(' ')));
    }
    return items;
}

TEST(ScanCommand, IdealRangesMatchTheClosedForm) {
    const Result r =
        Casmap("scan --scene " + SceneFile().string() + " --pose 0,0,0.5,0,0,0 --ideal");
    ASSERT_EQ(r.code, 0) << r.output;
    const auto angles = Field(r.output, "angles_deg");
    const auto ranges = Field(r.output, "ranges_m");
    const auto status = Field(r.output, "status");
    const auto labels = Field(r.output, "labels");
    ASSERT_EQ(angles.size(), 181U);
    ASSERT_EQ(ranges.size(), 181U);
    ASSERT_EQ(status.size(), 181U);
    ASSERT_EQ(labels.size(), 181U);
    int checked = 0;
    for (std::size_t i = 0; i < 181; ++i) {
        const double phi = (std::stod(angles[i])) * std::numbers::pi / 180.0;
        EXPECT_NEAR(std::stod(angles[i]), -90.0 + static_cast<double>(i), 1e-9);
        if (std::abs(2.5 * std::tan(phi)) < 1.95 && std::cos(phi) > 0.1) {
            EXPECT_NEAR(std::stod(ranges[i]), 2.5 / std::cos(phi), 1e-3) << i;
            EXPECT_EQ(status[i], "\"ok\"");
            EXPECT_EQ(labels[i], "\"valid\"");
            ++checked;
        } else if (std::abs(2.5 * std::tan(phi)) > 2.05 || std::cos(phi) < 0.0) {
            EXPECT_EQ(ranges[i], "null") << i;  // horizontal beams miss the wall
            EXPECT_EQ(labels[i], "\"no_target\"");
        }
    }
    EXPECT_GT(checked, 60);
}

TEST(ScanCommand, SameSeedSameScanOtherSeedOtherNoise) {
    const std::string base = "scan --scene " + SceneFile().string() + " --pose 0,0,0.5,0,0,0";
    const Result a = Casmap(base + " --seed 7");
    const Result b = Casmap(base + " --seed 7");
    const Result c = Casmap(base + " --seed 8");
    ASSERT_EQ(a.code, 0) << a.output;
    EXPECT_EQ(a.output, b.output);
    EXPECT_NE(a.output, c.output);
    // Noisy ranges stay within a few centimetres of the truth and are whole millimetres.
    const auto ranges = Field(a.output, "ranges_m");
    ASSERT_EQ(ranges.size(), 181U);
    EXPECT_NEAR(std::stod(ranges[90]), 2.5, 0.05);
    EXPECT_EQ(ranges[90].size(), std::string("2.500").size());
}

TEST(ScanCommand, BadPoseExitsWithCodeTwoAndOneLine) {
    const Result r = Casmap("scan --scene " + SceneFile().string() + " --pose 0,0,0.5,0,0");
    EXPECT_EQ(r.code, 2);
    EXPECT_NE(r.output.find("--pose"), std::string::npos) << r.output;
    EXPECT_EQ(std::count(r.output.begin(), r.output.end(), '\n'), 1) << r.output;
    const Result text = Casmap("scan --scene " + SceneFile().string() + " --pose 0,0,x,0,0,0");
    EXPECT_EQ(text.code, 2) << text.output;
}

TEST(ScanCommand, MissingSceneExitsWithCodeTwo) {
    const Result r = Casmap("scan --scene /nonexistent/scene.yaml --pose 0,0,0.5,0,0,0");
    EXPECT_EQ(r.code, 2) << r.output;
    EXPECT_NE(r.output.find("scene.yaml"), std::string::npos) << r.output;
}

}  // namespace
}  // namespace casmap
