#include "casmap/io/sensor_config.hpp"

#include <array>
#include <charconv>
#include <cmath>
#include <string>
#include <string_view>
#include <variant>

#include "casmap/core/input_error.hpp"
#include "casmap/io/yaml_emit.hpp"
#include "casmap/io/yaml_util.hpp"

namespace casmap::io {
namespace {

using sensor_models::Lms200Config;
using sensor_models::ReturnAlgorithm;

/// Fields that are not a plain double, int or bool of the struct.
enum class Special : std::uint8_t { kRangeMode, kRangeUnits, kReturnAlgorithm, kSunDirection };

using Target =
    std::variant<double Lms200Config::*, int Lms200Config::*, bool Lms200Config::*, Special>;

struct Field {
    std::string_view key;
    Target target;
};

// The file format: every field of Lms200Config in the order of the struct.
const std::array kFields = {
    Field{"angular_resolution_deg", &Lms200Config::angular_resolution_deg},
    Field{"field_of_view_deg", &Lms200Config::field_of_view_deg},
    Field{"range_mode_m", Special::kRangeMode},
    Field{"range_units", Special::kRangeUnits},
    Field{"ideal", &Lms200Config::ideal},
    Field{"max_trace_range_m", &Lms200Config::max_trace_range_m},
    Field{"spot_diameter_at_exit_m", &Lms200Config::spot_diameter_at_exit_m},
    Field{"divergence_rad", &Lms200Config::divergence_rad},
    Field{"subrays_per_pulse", &Lms200Config::subrays_per_pulse},
    Field{"rotate_pattern_per_pulse", &Lms200Config::rotate_pattern_per_pulse},
    Field{"echo_width_m", &Lms200Config::echo_width_m},
    Field{"lobe_bound_fraction", &Lms200Config::lobe_bound_fraction},
    Field{"return_algorithm", Special::kReturnAlgorithm},
    Field{"compact_spread_m", &Lms200Config::compact_spread_m},
    Field{"r10_m", &Lms200Config::r10_m},
    Field{"r10_reflectivity", &Lms200Config::r10_reflectivity},
    Field{"soft_threshold", &Lms200Config::soft_threshold},
    Field{"soft_edge_db", &Lms200Config::soft_edge_db},
    Field{"low_signal_fraction", &Lms200Config::low_signal_fraction},
    Field{"min_range_m", &Lms200Config::min_range_m},
    Field{"retro_gain", &Lms200Config::retro_gain},
    Field{"saturation_peak", &Lms200Config::saturation_peak},
    Field{"noise_enabled", &Lms200Config::noise_enabled},
    Field{"noise_sigma0_mm_units_m", &Lms200Config::noise_sigma0_mm_units_m},
    Field{"noise_sigma0_cm_units_m", &Lms200Config::noise_sigma0_cm_units_m},
    Field{"noise_sigma_cap_factor", &Lms200Config::noise_sigma_cap_factor},
    Field{"bias_enabled", &Lms200Config::bias_enabled},
    Field{"material_bias_max_mm_units_m", &Lms200Config::material_bias_max_mm_units_m},
    Field{"material_bias_max_cm_units_m", &Lms200Config::material_bias_max_cm_units_m},
    Field{"dark_bias_m", &Lms200Config::dark_bias_m},
    Field{"dark_bias_reflectivity", &Lms200Config::dark_bias_reflectivity},
    Field{"drift_enabled", &Lms200Config::drift_enabled},
    Field{"drift_amplitude_m", &Lms200Config::drift_amplitude_m},
    Field{"drift_time_constant_s", &Lms200Config::drift_time_constant_s},
    Field{"wrap_enabled", &Lms200Config::wrap_enabled},
    Field{"p_wrap", &Lms200Config::p_wrap},
    Field{"spikes_enabled", &Lms200Config::spikes_enabled},
    Field{"p_short", &Lms200Config::p_short},
    Field{"p_rand", &Lms200Config::p_rand},
    Field{"dropout_enabled", &Lms200Config::dropout_enabled},
    Field{"p_dropout", &Lms200Config::p_dropout},
    Field{"sun_enabled", &Lms200Config::sun_enabled},
    Field{"sun_direction_world", Special::kSunDirection},
    Field{"sun_cone_deg", &Lms200Config::sun_cone_deg},
    Field{"sun_irradiance_w_m2", &Lms200Config::sun_irradiance_w_m2},
    Field{"p_sun", &Lms200Config::p_sun},
    Field{"mixed_tolerance_m", &Lms200Config::mixed_tolerance_m},
    Field{"target_min_weight", &Lms200Config::target_min_weight},
};

const std::string kPath = "lms200";

std::string AllowedKeys() {
    std::string list;
    for (const Field& f : kFields) {
        list += (list.empty() ? "" : ", ") + std::string(f.key);
    }
    return list;
}

const Field* FindField(std::string_view key) {
    for (const Field& f : kFields) {
        if (f.key == key) {
            return &f;
        }
    }
    return nullptr;
}

std::string Shown(const YAML::Node& node) {
    if (node.IsScalar()) {
        return node.Scalar();
    }
    return node.IsNull() ? "null" : node.IsMap() ? "<map>" : "<sequence>";
}

/// Sets one field from its YAML value; InputError at `where` naming the field otherwise.
void SetField(Lms200Config& c, const Field& f, const YAML::Node& value, const std::string& where) {
    const std::string field = kPath + "." + std::string(f.key);
    const auto fail = [&](const std::string& rule) {
        return MakeInputError(where, field, Shown(value), rule);
    };
    try {
        if (const auto* d = std::get_if<double Lms200Config::*>(&f.target)) {
            c.*(*d) = value.as<double>();
        } else if (const auto* i = std::get_if<int Lms200Config::*>(&f.target)) {
            c.*(*i) = value.as<int>();
        } else if (const auto* b = std::get_if<bool Lms200Config::*>(&f.target)) {
            c.*(*b) = value.as<bool>();
        } else {
            switch (std::get<Special>(f.target)) {
                case Special::kRangeMode: {
                    const int m = value.as<int>();
                    if (m != 8 && m != 16 && m != 32) {
                        throw fail("allowed: 8, 16, 32");
                    }
                    c.format.mode = m == 8    ? core::RangeMode::k8m
                                    : m == 16 ? core::RangeMode::k16m
                                              : core::RangeMode::k32m;
                    break;
                }
                case Special::kRangeUnits: {
                    const std::string u = value.as<std::string>();
                    if (!value.IsScalar() || (u != "mm" && u != "cm")) {
                        throw fail("allowed: mm, cm");
                    }
                    c.format.units =
                        u == "mm" ? core::RangeUnits::kMillimetre : core::RangeUnits::kCentimetre;
                    break;
                }
                case Special::kReturnAlgorithm: {
                    const std::string a = value.as<std::string>();
                    if (!value.IsScalar() || (a != "waveform" && a != "auto")) {
                        throw fail("allowed: waveform, auto");
                    }
                    c.return_algorithm =
                        a == "waveform" ? ReturnAlgorithm::kWaveform : ReturnAlgorithm::kAuto;
                    break;
                }
                case Special::kSunDirection: {
                    if (!value.IsSequence() || value.size() != 3) {
                        throw fail("must be a sequence of three numbers [x, y, z]");
                    }
                    c.sun_direction_world = {value[0].as<double>(), value[1].as<double>(),
                                             value[2].as<double>()};
                    break;
                }
            }
        }
    } catch (const YAML::Exception&) {
        throw fail("wrong type");
    }
}

/// Validate() with its InputError re-thrown at the offending key's place ("lms200.<field> = ...
/// " names the field; a field the file does not set is a default: the file alone is named).
void ValidateAt(const Lms200Config& c,
                const std::string& file,
                const YAML::Node* map,
                const std::string& flag_where) {
    try {
        c.Validate();
    } catch (const InputError& e) {
        const std::string message = e.what();
        std::string where = flag_where;
        const std::string prefix = kPath + ".";
        if (map != nullptr && message.rfind(prefix, 0) == 0) {
            const std::string key =
                message.substr(prefix.size(), message.find_first_of(" (") - prefix.size());
            where = file;
            for (const auto& entry : *map) {
                if (entry.first.as<std::string>() == key) {
                    where = Where(file, entry.first);
                }
            }
        }
        throw InputError(where.empty() ? message : where + ": " + message);
    }
}

}  // namespace

sensor_models::Lms200Config LoadLms200Config(const std::string& path) {
    const YAML::Node root = LoadYamlFile(path);
    Lms200Config c;
    if (root.IsNull()) {  // an empty file: the defaults
        ValidateAt(c, path, nullptr, path);
        return c;
    }
    if (!root.IsMap()) {
        throw MakeInputError(Where(path, root), kPath, "", "must be a mapping of lms200 keys");
    }
    for (const auto& entry : root) {
        const std::string key = entry.first.as<std::string>();
        const Field* f = FindField(key);
        if (f == nullptr) {
            throw MakeInputError(Where(path, entry.first), kPath + "." + key, "",
                                 "unknown key; allowed: " + AllowedKeys());
        }
        SetField(c, *f, entry.second, Where(path, entry.second));
    }
    ValidateAt(c, path, &root, path);
    return c;
}

void EmitLms200Config(YAML::Emitter& out, const sensor_models::Lms200Config& c) {
    out << YAML::BeginMap;
    for (const Field& f : kFields) {
        const std::string key(f.key);
        out << YAML::Key << key << YAML::Value;
        if (const auto* d = std::get_if<double Lms200Config::*>(&f.target)) {
            out << core::FormatNumber(c.*(*d));
        } else if (const auto* i = std::get_if<int Lms200Config::*>(&f.target)) {
            out << c.*(*i);
        } else if (const auto* b = std::get_if<bool Lms200Config::*>(&f.target)) {
            out << (c.*(*b) ? "true" : "false");
        } else {
            switch (std::get<Special>(f.target)) {
                case Special::kRangeMode:
                    out << (c.format.mode == core::RangeMode::k8m    ? "8"
                            : c.format.mode == core::RangeMode::k16m ? "16"
                                                                     : "32");
                    break;
                case Special::kRangeUnits:
                    out << (c.format.units == core::RangeUnits::kMillimetre ? "mm" : "cm");
                    break;
                case Special::kReturnAlgorithm:
                    out << (c.return_algorithm == ReturnAlgorithm::kWaveform ? "waveform" : "auto");
                    break;
                case Special::kSunDirection:
                    out << YAML::Flow << YAML::BeginSeq;
                    for (int k = 0; k < 3; ++k) {
                        out << core::FormatNumber(c.sun_direction_world[k]);
                    }
                    out << YAML::EndSeq;
                    break;
            }
        }
    }
    out << YAML::EndMap;
}

std::string Lms200ConfigToYaml(const sensor_models::Lms200Config& c) {
    YAML::Emitter out;
    EmitLms200Config(out, c);
    return EmittedText(out);
}

void ApplyLms200ConfigOverrides(sensor_models::Lms200Config& config,
                                const std::vector<std::string>& assignments,
                                const std::string& flag) {
    for (const std::string& a : assignments) {
        const std::size_t eq = a.find('=');
        if (eq == std::string::npos) {
            throw MakeInputError("", flag, a, "expected NAME=VALUE");
        }
        const std::string key = a.substr(0, eq);
        std::string text = a.substr(eq + 1);
        const Field* f = FindField(key);
        if (f == nullptr) {
            throw MakeInputError("", flag, key, "unknown key; allowed: " + AllowedKeys());
        }
        if (std::holds_alternative<Special>(f->target) &&
            std::get<Special>(f->target) == Special::kSunDirection && !text.empty() &&
            text.front() != '[') {
            text = "[" + text + "]";  // X,Y,Z
        }
        YAML::Node value;
        try {
            value = YAML::Load(text);
        } catch (const YAML::Exception&) {
            throw MakeInputError(flag, kPath + "." + key, text, "not a YAML value");
        }
        SetField(config, *f, value, flag);
    }
    ValidateAt(config, "", nullptr, flag);
}

}  // namespace casmap::io
