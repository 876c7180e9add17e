// `--sensor FILE` of the simulator commands: runs the built binary (skips itself when it was
// built without the simulator) with LMS 200 config files written here.
#include <gtest/gtest.h>
#include <sys/wait.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
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

bool HaveSimulator() { return Casmap("--help").output.find("\n  scan ") != std::string::npos; }

fs::path Write(const std::string& name, const std::string& text) {
    const fs::path path =
        casmap::test::MakeTempDir("sensor_option") / ("casmap_sensor_option_" + name);
    std::ofstream(path) << text;
    return path;
}

// A wall whose face is 12 m straight ahead: beyond the 8 m mode, within the 16 m mode.
fs::path FarWallScene() {
    return Write("scene.yaml",
                 "objects:\n"
                 "  - name: wall\n"
                 "    box: {size_m: [1, 40, 4]}\n"
                 "    pose: {xyz_m: [12.5, 0, 1], rpy_deg: [0, 0, 0]}\n");
}

// Item `index` of `"key": [a, b, ...]` in the printed JSON.
std::string Item(const std::string& json, const std::string& key, std::size_t index) {
    const std::size_t at = json.find("\"" + key + "\": [");
    if (at == std::string::npos) {
        return "<no " + key + ">";
    }
    const std::size_t begin = json.find('[', at) + 1;
    std::stringstream in(json.substr(begin, json.find(']', begin) - begin));
    std::string item;
    for (std::size_t i = 0; std::getline(in, item, ',') && i < index; ++i) {
    }
    return item.substr(item.find_first_not_of(' '));
}

TEST(SensorOption, ScanWithA16mSensorFileReportsTheFarWall) {
    if (!HaveSimulator()) {
        GTEST_SKIP() << "built without the simulator";
    }
    const std::string scan = "scan --scene " + FarWallScene().string() + " --pose 0,0,1,0,0,0";
    const std::string sensor = Write("16m.yaml", "range_mode_m: 16\nideal: true\n").string();
    // Beam 90 looks straight ahead (1 deg, 180 deg: the defaults the file keeps).
    const Result by_default = Casmap(scan + " --ideal");
    ASSERT_EQ(by_default.code, 0) << by_default.output;
    EXPECT_EQ(Item(by_default.output, "raw", 90), "8183");  // 8 m mode: value > maximum
    const Result with_file = Casmap(scan + " --sensor " + sensor);
    ASSERT_EQ(with_file.code, 0) << with_file.output;
    EXPECT_EQ(Item(with_file.output, "raw", 90), "12000");  // 12 m in mm, 14-bit mode
    EXPECT_EQ(Item(with_file.output, "ranges_m", 90), "12.000000");
    // An explicit flag overrides the file.
    const Result overridden = Casmap(scan + " --sensor " + sensor + " --range-mode 8");
    ASSERT_EQ(overridden.code, 0) << overridden.output;
    EXPECT_EQ(Item(overridden.output, "raw", 90), "8183");
}

TEST(SensorOption, BadSensorFileExitsWithCodeTwoAndOneLine) {
    if (!HaveSimulator()) {
        GTEST_SKIP() << "built without the simulator";
    }
    const std::string scene = FarWallScene().string();
    const std::string bad_value = Write("bad_value.yaml", "ideal: true\np_dropout: 2\n").string();
    const std::string bad_key = Write("bad_key.yaml", "r10_m: 10\nr11_m: 3\n").string();
    const std::string out =
        (casmap::test::MakeTempDir("sensor_option") / "casmap_sensor_option_bad.h5").string();
    const std::pair<std::string, std::string> cases[] = {
        {"scan --scene " + scene + " --pose 0,0,1,0,0,0 --sensor " + bad_value,
         bad_value + ":2:1: lms200.p_dropout = 2"},
        {"simulate --scene " + scene + " --motion T --out " + out + " --sensor " + bad_key,
         bad_key + ":2:1: lms200.r11_m (unknown key"},
        {"mixed-pixels --readings 10 --sensor " + bad_value, bad_value + ":2:1: lms200.p_dropout"},
    };
    for (const auto& [args, message] : cases) {
        const Result r = Casmap(args);
        EXPECT_EQ(r.code, 2) << args << "\n" << r.output;
        EXPECT_NE(r.output.find(message), std::string::npos) << r.output;
        EXPECT_EQ(r.output.find('\n'), r.output.size() - 1) << "one line: " << r.output;
    }
    EXPECT_FALSE(fs::exists(out));
}

TEST(SensorOption, SimulateRecordsTheSensorConfigItUsed) {
    if (!HaveSimulator()) {
        GTEST_SKIP() << "built without the simulator";
    }
    const std::string sensor = Write("seven.yaml", "subrays_per_pulse: 7\np_dropout: 0.01\n");
    const fs::path out = casmap::test::MakeTempDir("sensor_option") / "casmap_sensor_option_run.h5";
    const std::string scene = std::string(CASMAP_SOURCE_DIR) + "/scenes/courses/course01.yaml";
    const Result r = Casmap("simulate --scene " + scene + " --motion T --seed 3 --threads 1" +
                            " --sensor " + sensor + " --out " + out.string());
    ASSERT_EQ(r.code, 0) << r.output;
    std::ifstream in(out.string() + ".config.yaml");
    std::stringstream text;
    text << in.rdbuf();
    const std::string config = text.str();
    EXPECT_NE(config.find("sensor_file: " + sensor + "\n"), std::string::npos) << config;
    EXPECT_NE(config.find("\n  subrays_per_pulse: 7\n"), std::string::npos) << config;
    EXPECT_NE(config.find("\n  p_dropout: 0.01\n"), std::string::npos) << config;
    // The recorded section, un-indented, is itself a sensor file giving the same config.
    std::string section;
    std::stringstream lines(config.substr(config.find("\nsensor:\n") + 9));
    for (std::string line; std::getline(lines, line) && line.rfind("  ", 0) == 0;) {
        section += line.substr(2) + "\n";
    }
    const std::string recorded = Write("recorded.yaml", section).string();
    const std::string scan = "scan --scene " + FarWallScene().string() + " --pose 0,0,1,0,0,0";
    const Result a = Casmap(scan + " --sensor " + sensor);
    const Result b = Casmap(scan + " --sensor " + recorded);
    EXPECT_EQ(a.code, 0) << a.output;
    EXPECT_EQ(a.output, b.output);
}

}  // namespace
}  // namespace casmap
