#include "casmap/io/sensor_config.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <yaml-cpp/yaml.h>

#include <fstream>
#include <set>
#include <string>

#include "casmap/core/input_error.hpp"
#include "tests/temp_dir.hpp"

namespace casmap::io {
namespace {

using sensor_models::Lms200Config;
using testing::HasSubstr;

std::string WriteTemp(const std::string& name, const std::string& text) {
    const std::string path =
        (casmap::test::MakeTempDir("sensor_config_test") / ("sensor_config_test_" + name + ".yaml"))
            .string();
    std::ofstream(path) << text;
    return path;
}

/// Loading `text` throws an InputError whose message contains `path` + `message`.
void ExpectError(const std::string& name, const std::string& text, const std::string& message) {
    const std::string path = WriteTemp(name, text);
    EXPECT_THAT([&] { (void)LoadLms200Config(path); },
                testing::ThrowsMessage<InputError>(HasSubstr(path + message)))
        << text;
}

TEST(SensorConfig, DefaultsAreValidAndTheExampleHoldsThem) {
    EXPECT_NO_THROW(Lms200Config{}.Validate());
    const std::string example = std::string(CASMAP_SOURCE_DIR) + "/config/lms200.yaml";
    EXPECT_EQ(Lms200ConfigToYaml(LoadLms200Config(example)), Lms200ConfigToYaml(Lms200Config{}));
    // The example lists every key the writer writes, and nothing else.
    std::set<std::string> written;
    std::set<std::string> listed;
    for (const auto& e : YAML::Load(Lms200ConfigToYaml(Lms200Config{}))) {
        written.insert(e.first.as<std::string>());
    }
    for (const auto& e : YAML::LoadFile(example)) {
        listed.insert(e.first.as<std::string>());
    }
    EXPECT_EQ(written, listed);
    EXPECT_EQ(written.size(), 48U);  // the 47 fields of Lms200Config, format split in two
}

TEST(SensorConfig, EmptyFileGivesTheDefaults) {
    EXPECT_EQ(Lms200ConfigToYaml(LoadLms200Config(WriteTemp("empty", ""))),
              Lms200ConfigToYaml(Lms200Config{}));
}

TEST(SensorConfig, WrittenYamlLoadsBackToTheSameConfig) {
    Lms200Config c;  // every field away from its default
    c.angular_resolution_deg = 0.25;
    c.field_of_view_deg = 100.0;
    c.format.mode = core::RangeMode::k16m;
    c.format.units = core::RangeUnits::kCentimetre;
    c.ideal = true;
    c.max_trace_range_m = 80.5;
    c.spot_diameter_at_exit_m = 0.1 / 3.0;  // not a short decimal: exercises exact output
    c.divergence_rad = 0.0031;
    c.subrays_per_pulse = 37;
    c.rotate_pattern_per_pulse = false;
    c.echo_width_m = 0.7;
    c.lobe_bound_fraction = 0.2;
    c.return_algorithm = sensor_models::ReturnAlgorithm::kWaveform;
    c.compact_spread_m = 0.1;
    c.r10_m = 12.0;
    c.r10_reflectivity = 0.2;
    c.soft_threshold = false;
    c.soft_edge_db = 2.5;
    c.low_signal_fraction = 0.25;
    c.min_range_m = 0.3;
    c.retro_gain = 250.0;
    c.saturation_peak = 3e4;
    c.noise_enabled = false;
    c.noise_sigma0_mm_units_m = 0.007;
    c.noise_sigma0_cm_units_m = 0.02;
    c.noise_sigma_cap_factor = 3.0;
    c.bias_enabled = false;
    c.material_bias_max_mm_units_m = 0.02;
    c.material_bias_max_cm_units_m = 0.05;
    c.dark_bias_m = -0.004;
    c.dark_bias_reflectivity = 0.4;
    c.drift_enabled = true;
    c.drift_amplitude_m = 0.02;
    c.drift_time_constant_s = 1800.0;
    c.wrap_enabled = false;
    c.p_wrap = 0.5;
    c.spikes_enabled = false;
    c.p_short = 1e-3;
    c.p_rand = 2.5e-7;
    c.dropout_enabled = false;
    c.p_dropout = 0.01;
    c.sun_enabled = true;
    c.sun_direction_world = {0.3, -0.2, 1.0 / 7.0};
    c.sun_cone_deg = 3.0;
    c.sun_irradiance_w_m2 = 800.0;
    c.p_sun = 0.02;
    c.mixed_tolerance_m = 0.05;
    c.target_min_weight = 0.75;
    ASSERT_NO_THROW(c.Validate());
    const std::string text = Lms200ConfigToYaml(c);
    const Lms200Config back = LoadLms200Config(WriteTemp("round_trip", text));
    EXPECT_EQ(Lms200ConfigToYaml(back), text);
    // Bit-exact values, not just equal text.
    EXPECT_EQ(back.spot_diameter_at_exit_m, c.spot_diameter_at_exit_m);
    EXPECT_EQ(back.p_rand, c.p_rand);
    EXPECT_EQ(back.sun_direction_world, c.sun_direction_world);
    EXPECT_EQ(back.format, c.format);
    EXPECT_EQ(back.return_algorithm, c.return_algorithm);
    EXPECT_EQ(back.subrays_per_pulse, 37);
    EXPECT_TRUE(back.ideal);
    // The text differs from the defaults' in every line.
    std::istringstream a(text);
    std::istringstream d(Lms200ConfigToYaml(Lms200Config{}));
    int lines = 0;
    for (std::string x, y; std::getline(a, x) && std::getline(d, y); ++lines) {
        EXPECT_NE(x, y);
    }
    EXPECT_EQ(lines, 48);
}

TEST(SensorConfig, UnknownKeyIsNamedWithLineAndColumn) {
    ExpectError("unknown", "r10_m: 10\n  \nr11_m: 3\n",
                ":3:1: lms200.r11_m (unknown key; allowed:");
}

TEST(SensorConfig, WrongTypeIsNamedWithLineAndColumn) {
    ExpectError("type_int", "ideal: true\nsubrays_per_pulse: many\n",
                ":2:20: lms200.subrays_per_pulse = many (wrong type)");
    ExpectError("type_bool", "noise_enabled: 3\n", ":1:16: lms200.noise_enabled = 3 (wrong type)");
    ExpectError("type_vector", "sun_direction_world: [1, x, 0]\n",
                ":1:22: lms200.sun_direction_world = <sequence> (wrong type)");
    ExpectError("not_a_map", "- r10_m\n", ":1:1: lms200 (must be a mapping");
}

TEST(SensorConfig, OutOfRangeValueNamesTheField) {
    // Validate()'s rule, placed at the key.
    ExpectError("range", "# a comment\nr10_m: 10\np_dropout: 1.5\n",
                ":3:1: lms200.p_dropout = 1.5 (allowed: 0..1)");
    ExpectError("subrays", "subrays_per_pulse: 12\n",
                ":1:1: lms200.subrays_per_pulse = 12 (allowed: 1, 7, 19, 37)");
    // Values the file format itself restricts.
    ExpectError("mode", "range_mode_m: 12\n",
                ":1:15: lms200.range_mode_m = 12 (allowed: 8, 16, 32)");
    ExpectError("units", "range_units: m\n", ":1:14: lms200.range_units = m (allowed: mm, cm)");
    ExpectError("vector", "sun_direction_world: [1, 0]\n",
                ":1:22: lms200.sun_direction_world = <sequence> (must be a sequence of three");
    // A default made invalid by another key: the field is named, the file without a line.
    ExpectError("cross", "angular_resolution_deg: 0.25\n",
                ": lms200.field_of_view_deg = 180 (0.25 deg resolution needs the 100 deg");
}

TEST(SensorConfig, MissingFileIsAnInputError) {
    EXPECT_THROW((void)LoadLms200Config(testing::TempDir() + "/no_such_sensor.yaml"), InputError);
}

TEST(SensorConfig, OverridesSetKeysAndValidate) {
    Lms200Config c;
    ApplyLms200ConfigOverrides(
        c,
        {"range_mode_m=16", "sun_direction_world=1,0,1", "return_algorithm=waveform", "p_rand=0"},
        "--sensor-set");
    EXPECT_EQ(c.format.mode, core::RangeMode::k16m);
    EXPECT_EQ(c.sun_direction_world, Eigen::Vector3d(1.0, 0.0, 1.0));
    EXPECT_EQ(c.return_algorithm, sensor_models::ReturnAlgorithm::kWaveform);
    EXPECT_EQ(c.p_rand, 0.0);
    const auto error = [](const std::string& a, const std::string& message) {
        Lms200Config d;
        EXPECT_THAT([&] { ApplyLms200ConfigOverrides(d, {a}, "--sensor-set"); },
                    testing::ThrowsMessage<InputError>(HasSubstr(message)))
            << a;
    };
    error("p_rand=2", "--sensor-set: lms200.p_rand = 2 (allowed: 0..1)");
    error("foo=1", "--sensor-set = foo (unknown key");
    error("r10_m", "--sensor-set = r10_m (expected NAME=VALUE)");
    error("ideal=maybe", "--sensor-set: lms200.ideal = maybe (wrong type)");
}

}  // namespace
}  // namespace casmap::io
