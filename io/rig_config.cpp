#include "casmap/io/rig_config.hpp"

#include <cmath>
#include <cstdio>
#include <functional>
#include <map>
#include <set>
#include <string>
#include <vector>

#include "casmap/core/input_error.hpp"
#include "casmap/io/yaml_emit.hpp"
#include "casmap/io/yaml_util.hpp"

namespace casmap::io {
namespace {

using rig::AngleProfile;
using rig::ProfileShape;

// One list of keys per struct, shared by the reader and the writer (Visit* below), so the
// loader, the effective-config writer and the example files cannot drift apart.

template <typename V>
void VisitProfile(V& v, AngleProfile& p) {
    v.Shape("shape", p.shape);
    v.Number("center_deg", p.center_deg);
    v.Number("amplitude_deg", p.amplitude_deg);
    v.Number("period_s", p.period_s);
    v.Number("phase_deg", p.phase_deg);
}

template <typename V>
void VisitTable(V& v, rig::TableConfig& c) {
    v.Number("physics_rate_hz", c.physics_rate_hz);
    v.Int("output_decimation", c.output_decimation);
    v.Number("speed_m_s", c.speed_m_s);
    v.Number("speed_ramp_s", c.speed_ramp_s);
    v.Number("sensor_height_m", c.sensor_height_m);
    v.Number("mount_pitch_deg", c.mount_pitch_deg);
    v.Vector("pitch_to_roll_m", c.pitch_to_roll_m);
    v.Number("roll_to_sensor_m", c.roll_to_sensor_m);
    v.Number("max_range_m", c.max_range_m);
    v.Section("course", [&] {
        v.Number("start_x_m", c.course.start_x_m);
        v.Number("end_x_m", c.course.end_x_m);
        v.Number("lateral_offset_m", c.course.lateral_offset_m);
        v.Number("width_m", c.course.width_m);
    });
    v.Section("roll_profile", [&] { VisitProfile(v, c.roll_profile); });
    v.Section("pitch_profile", [&] { VisitProfile(v, c.pitch_profile); });
    v.Section("compliance", [&] {
        v.Bool("enabled", c.compliance.enabled);
        v.Number("natural_frequency_hz", c.compliance.natural_frequency_hz);
        v.Number("damping_ratio", c.compliance.damping_ratio);
    });
}

template <typename V>
void VisitVehicle(V& v, rig::VehicleConfig& c) {
    v.Number("physics_rate_hz", c.physics_rate_hz);
    v.Int("output_decimation", c.output_decimation);
    v.Number("speed_m_s", c.speed_m_s);
    v.Number("speed_ramp_s", c.speed_ramp_s);
    v.Vector("start_xy_m", c.start_xy_m);
    v.Number("end_x_m", c.end_x_m);
    v.Number("settle_s", c.settle_s);
    v.Number("chassis_mass_kg", c.chassis_mass_kg);
    v.Vector("chassis_size_m", c.chassis_size_m);
    v.Number("wheelbase_m", c.wheelbase_m);
    v.Number("track_m", c.track_m);
    v.Number("wheel_radius_m", c.wheel_radius_m);
    v.Number("suspension_rest_m", c.suspension_rest_m);
    v.Number("suspension_travel_m", c.suspension_travel_m);
    v.Number("suspension_stiffness", c.suspension_stiffness);
    v.Number("suspension_compression", c.suspension_compression);
    v.Number("suspension_relaxation", c.suspension_relaxation);
    v.Number("wheel_friction", c.wheel_friction);
    v.Number("speed_kp_n_per_m_s", c.speed_kp_n_per_m_s);
    v.Number("speed_ki_n_per_m", c.speed_ki_n_per_m);
    v.Number("max_drive_force_n", c.max_drive_force_n);
    v.Vector("mount_xyz_m", c.mount_xyz_m);
    v.Number("mount_pitch_deg", c.mount_pitch_deg);
}

template <typename V>
void VisitPoseError(V& v, rig::PoseErrorConfig& c) {
    v.Bool("enabled", c.enabled);
    v.Seed("seed", c.seed);
    v.Vector("position_bias_m", c.position_bias_m);
    v.Vector("attitude_bias_deg", c.attitude_bias_deg);
    v.Number("position_random_walk_m_per_sqrt_s", c.position_random_walk_m_per_sqrt_s);
    v.Number("attitude_random_walk_deg_per_sqrt_s", c.attitude_random_walk_deg_per_sqrt_s);
    v.Number("position_jitter_m", c.position_jitter_m);
    v.Number("attitude_jitter_deg", c.attitude_jitter_deg);
}

template <typename V>
void VisitRig(V& v, RigConfig& c) {
    v.Section("table", [&] { VisitTable(v, c.table); });
    v.Section("vehicle", [&] { VisitVehicle(v, c.vehicle); });
    v.Section("pose_error", [&] { VisitPoseError(v, c.pose_error); });
}

/// Reads values from YAML, remembering where each field sat for later rule violations.
class Reader {
public:
    Reader(std::string file, const YAML::Node& root) : file_(std::move(file)) {
        stack_.push_back({root, ""});
        known_.emplace_back();
    }

    void Section(const char* key, const std::function<void()>& body) {
        Expect(key);
        const YAML::Node node = Current()[key];
        if (!node) {
            return;
        }
        const std::string path = Path(key);
        if (!node.IsMap()) {
            throw MakeInputError(Where(file_, node), path, "", "must be a mapping");
        }
        Known(key, node);
        stack_.push_back({node, path});
        known_.emplace_back();
        body();
        RejectUnknown();
        stack_.pop_back();
        known_.pop_back();
    }
    void Number(const char* key, double& out) { Read(key, out); }
    void Int(const char* key, int& out) { Read(key, out); }
    void Bool(const char* key, bool& out) { Read(key, out); }
    void Seed(const char* key, std::uint64_t& out) { Read(key, out); }
    template <int N>
    void Vector(const char* key, Eigen::Matrix<double, N, 1>& out) {
        Expect(key);
        const YAML::Node node = Current()[key];
        if (!node) {
            return;
        }
        Known(key, node);
        if (!node.IsSequence() || node.size() != static_cast<std::size_t>(N)) {
            throw MakeInputError(Where(file_, node), Path(key), "",
                                 "must be a list of " + std::to_string(N) + " numbers");
        }
        for (int i = 0; i < N; ++i) {
            const YAML::Node element = node[static_cast<std::size_t>(i)];
            try {
                out[i] = element.as<double>();
            } catch (const YAML::Exception&) {
                throw MakeInputError(Where(file_, element),
                                     Path(key) + "[" + std::to_string(i) + "]",
                                     element.IsScalar() ? element.Scalar() : "", "wrong type");
            }
        }
    }
    void Shape(const char* key, ProfileShape& out) {
        std::string text = rig::ProfileShapeName(out);
        Read(key, text);
        if (text != "sinusoid" && text != "triangle") {
            throw MakeInputError(where_.at(Path(key)), Path(key), text,
                                 "allowed: sinusoid, triangle");
        }
        out = rig::ParseProfileShape(text, Path(key));
    }

    void RejectUnknown() {
        const YAML::Node& node = Current();
        for (const auto& entry : node) {
            const std::string key = entry.first.as<std::string>();
            if (known_.back().count(key) == 0) {
                std::string allowed;
                for (const std::string& k : expected_.at(stack_.back().path)) {
                    allowed += (allowed.empty() ? "" : ", ") + k;
                }
                throw MakeInputError(Where(file_, entry.first), Path(key.c_str()), "",
                                     "unknown key; allowed: " + allowed);
            }
        }
    }

    /// "file:line:col" of a field read from the file, else just the file (a default).
    [[nodiscard]] std::string WhereOf(const std::string& field) const {
        const auto it = where_.find(field);
        return it == where_.end() ? file_ : it->second;
    }

private:
    struct Frame {
        YAML::Node node;
        std::string path;
    };

    const YAML::Node& Current() const { return stack_.back().node; }
    std::string Path(const char* key) const {
        return stack_.back().path.empty() ? key : stack_.back().path + "." + key;
    }
    void Known(const char* key, const YAML::Node& node) {
        known_.back().insert(key);
        where_[Path(key)] = Where(file_, node);
    }
    void Expect(const char* key) { expected_[stack_.back().path].push_back(key); }
    template <typename T>
    void Read(const char* key, T& out) {
        Expect(key);
        const YAML::Node node = Current()[key];
        if (node) {
            Known(key, node);
            ReadOptional(file_, Current(), stack_.back().path, key, out);
        }
    }

    std::string file_;
    std::vector<Frame> stack_;
    std::vector<std::set<std::string>> known_;
    std::map<std::string, std::vector<std::string>> expected_;
    std::map<std::string, std::string> where_;
};

/// Emits the same keys with yaml-cpp's emitter, numbers through core::FormatNumber.
class Writer {
public:
    explicit Writer(YAML::Emitter& out) : out_(out) {}

    void Section(const char* key, const std::function<void()>& body) {
        out_ << YAML::Key << key << YAML::Value << YAML::BeginMap;
        body();
        out_ << YAML::EndMap;
    }
    void Number(const char* key, double& v) { EmitNumber(out_, key, v); }
    void Int(const char* key, int& v) { out_ << YAML::Key << key << YAML::Value << v; }
    void Bool(const char* key, bool& v) {
        out_ << YAML::Key << key << YAML::Value << (v ? "true" : "false");
    }
    void Seed(const char* key, std::uint64_t& v) { out_ << YAML::Key << key << YAML::Value << v; }
    template <int N>
    void Vector(const char* key, Eigen::Matrix<double, N, 1>& v) {
        out_ << YAML::Key << key << YAML::Value << YAML::Flow << YAML::BeginSeq;
        for (int i = 0; i < N; ++i) {
            out_ << core::FormatNumber(v[i]);
        }
        out_ << YAML::EndSeq;
    }
    void Shape(const char* key, ProfileShape& v) {
        out_ << YAML::Key << key << YAML::Value << std::string(rig::ProfileShapeName(v));
    }

private:
    YAML::Emitter& out_;
};

}  // namespace

RigConfig LoadRigConfig(const std::string& path) {
    const YAML::Node root = LoadYamlFile(path);
    RigConfig config;
    if (root.IsNull()) {
        return config;  // an empty file: all defaults
    }
    if (!root.IsMap()) {
        throw MakeInputError(Where(path, root), "rig config", "", "must be a mapping");
    }
    Reader reader(path, root);
    VisitRig(reader, config);
    reader.RejectUnknown();
    try {  // the configs' own Validate(); the message gains the key's file:line:col
        config.table.Validate();
        config.vehicle.Validate();
        config.pose_error.Validate();
    } catch (const InputError& e) {
        throw MakeInputError(reader.WhereOf(e.field()), e.field(), e.value(), e.rule());
    }
    return config;
}

void EmitRigConfig(YAML::Emitter& out, const RigConfig& config) {
    RigConfig copy = config;  // the visitor is shared with the reader, which writes
    Writer writer(out);
    VisitRig(writer, copy);
}

std::string RigConfigToYaml(const RigConfig& config) {
    YAML::Emitter out;
    out << YAML::BeginMap;
    EmitRigConfig(out, config);
    out << YAML::EndMap;
    return EmittedText(out);
}

}  // namespace casmap::io
