#include "casmap/io/rig_config.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <yaml-cpp/yaml.h>

#include <filesystem>
#include <fstream>
#include <set>
#include <string>

#include "casmap/core/input_error.hpp"
#include "tests/temp_dir.hpp"

namespace casmap::io {
namespace {

using testing::HasSubstr;

std::string SourceDir() { return CASMAP_SOURCE_DIR; }

/// Writes `text` to a fresh file under the test temp dir and returns its path.
std::string WriteTemp(const std::string& name, const std::string& text) {
    const std::string path =
        (casmap::test::MakeTempDir("rig_config_test") / ("rig_config_test_" + name + ".yaml"))
            .string();
    std::ofstream(path) << text;
    return path;
}

void ExpectError(const std::string& name, const std::string& text, const std::string& message) {
    const std::string path = WriteTemp(name, text);
    EXPECT_THAT([&] { (void)LoadRigConfig(path); },
                testing::ThrowsMessage<InputError>(HasSubstr(path + ":" + message)))
        << text;
}

void CollectKeys(const YAML::Node& node, const std::string& prefix, std::set<std::string>& out) {
    for (const auto& entry : node) {
        const std::string key = prefix + entry.first.as<std::string>();
        out.insert(key);
        if (entry.second.IsMap()) {
            CollectKeys(entry.second, key + ".", out);
        }
    }
}

TEST(RigConfig, ExamplesHoldTheDefaults) {
    const std::string defaults = RigConfigToYaml(RigConfig{});
    for (const char* file : {"/config/rig_table.yaml", "/config/rig_vehicle.yaml"}) {
        EXPECT_EQ(RigConfigToYaml(LoadRigConfig(SourceDir() + file)), defaults) << file;
    }
}

TEST(RigConfig, ExamplesListEveryKeyOfTheirSections) {
    std::set<std::string> all;
    CollectKeys(YAML::Load(RigConfigToYaml(RigConfig{})), "", all);
    const std::pair<const char*, const char*> files[] = {{"/config/rig_table.yaml", "table"},
                                                         {"/config/rig_vehicle.yaml", "vehicle"}};
    for (const auto& [file, section] : files) {
        std::set<std::string> listed;
        CollectKeys(YAML::LoadFile(SourceDir() + file), "", listed);
        for (const std::string& key : all) {
            if (key.rfind(section, 0) == 0 || key.rfind("pose_error", 0) == 0) {
                EXPECT_TRUE(listed.count(key)) << file << " lacks " << key;
            }
        }
    }
}

TEST(RigConfig, EffectiveYamlReadsBackToTheSameValues) {
    RigConfig c;
    c.table.speed_m_s = 0.8;
    c.table.pitch_to_roll_m = Eigen::Vector3d(0.01, -0.02, 0.1 / 3.0);
    c.table.roll_profile.shape = rig::ProfileShape::kTriangle;
    c.table.compliance.enabled = true;
    c.table.course.lateral_offset_m = -0.25;
    c.vehicle.start_xy_m = Eigen::Vector2d(0.5, -1.5);
    c.vehicle.output_decimation = 4;
    c.pose_error.enabled = true;
    c.pose_error.seed = 18446744073709551557ULL;
    c.pose_error.attitude_bias_deg = Eigen::Vector3d(0.1, 0.2, 0.3);
    const std::string text = RigConfigToYaml(c);
    const RigConfig back = LoadRigConfig(WriteTemp("roundtrip", text));
    EXPECT_EQ(RigConfigToYaml(back), text);
    EXPECT_EQ(back.table.pitch_to_roll_m.z(), 0.1 / 3.0);  // exact, not rounded
    EXPECT_EQ(back.pose_error.seed, 18446744073709551557ULL);
    EXPECT_EQ(back.table.roll_profile.shape, rig::ProfileShape::kTriangle);
}

TEST(RigConfig, MissingSectionsAndEmptyFileAreDefaults) {
    const RigConfig c = LoadRigConfig(WriteTemp("partial", "table:\n  speed_m_s: 0.5\n"));
    EXPECT_EQ(c.table.speed_m_s, 0.5);
    EXPECT_EQ(c.table.mount_pitch_deg, rig::TableConfig{}.mount_pitch_deg);
    EXPECT_EQ(RigConfigToYaml(LoadRigConfig(WriteTemp("empty", ""))), RigConfigToYaml(RigConfig{}));
}

TEST(RigConfig, RejectsUnknownKeysWithLineAndColumn) {
    ExpectError("unknown", "table:\n  speed_ms: 1\n", "2:3: table.speed_ms (unknown key");
    ExpectError("unknown_top", "tabel:\n  speed_m_s: 1\n", "1:1: tabel (unknown key");
    ExpectError("unknown_nested", "table:\n  course:\n    start_x: 1\n",
                "3:5: table.course.start_x (unknown key");
}

TEST(RigConfig, RejectsWrongTypesWithLineAndColumn) {
    ExpectError("type", "table:\n  speed_m_s: fast\n", "2:14: table.speed_m_s = fast (wrong type)");
    ExpectError("vector", "table:\n  pitch_to_roll_m: [0, 0]\n",
                "2:20: table.pitch_to_roll_m (must be a list of 3 numbers)");
    ExpectError("shape", "table:\n  roll_profile:\n    shape: square\n",
                "3:12: table.roll_profile.shape = square (allowed: sinusoid, triangle)");
    ExpectError("section", "table:\n  course: 5\n", "2:11: table.course (must be a mapping)");
}

TEST(RigConfig, RejectsValuesBeyondTheRigLimitsNamingTheField) {
    ExpectError("speed", "table:\n  speed_m_s: 1.5\n", "2:14: table.speed_m_s = 1.5 (allowed");
    ExpectError("roll", "table:\n  roll_profile:\n    amplitude_deg: 20\n",
                "3:20: table.roll_profile.amplitude_deg = 20");
    ExpectError("rate", "table:\n  pitch_profile:\n    period_s: 1\n",
                "3:15: table.pitch_profile.period_s = 1 (peak rate");
    ExpectError("vehicle", "vehicle:\n  mount_pitch_deg: 60\n",
                "2:20: vehicle.mount_pitch_deg = 60");
    ExpectError("jitter", "pose_error:\n  position_jitter_m: -0.1\n",
                "2:22: pose_error.position_jitter_m = -0.1");
}

TEST(RigConfig, MissingFileIsAnInputError) {
    EXPECT_THROW((void)LoadRigConfig("/nonexistent/rig.yaml"), InputError);
}

}  // namespace
}  // namespace casmap::io
