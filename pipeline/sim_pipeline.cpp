#include "casmap/pipeline/sim_pipeline.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <utility>

#include "casmap/core/input_error.hpp"
#include "casmap/core/parallel.hpp"
#include "casmap/core/text.hpp"
#include "casmap/io/rig_config.hpp"
#include "casmap/io/sensor_config.hpp"
#include "casmap/io/yaml_emit.hpp"
#include "casmap/pipeline/map_run.hpp"
#include "casmap/sensor_models/lms200_model.hpp"
#include "casmap/sim/ground_truth.hpp"
#include "casmap/sim/simulator.hpp"

namespace casmap::pipeline {
namespace {

double ParseDouble(const std::string& text, const std::string& field, const std::string& value) {
    const std::optional<double> v = core::ParseFiniteDouble(text);
    if (!v) {
        throw MakeInputError("", field, value, "must be a finite number");
    }
    return *v;
}

Eigen::Vector3d ParseVector3(const std::string& text, const std::string& field) {
    const std::optional<std::vector<double>> v = core::ParseNumberList(text, 3);
    if (!v) {
        throw MakeInputError("", field, text, "must be three numbers X,Y,Z");
    }
    return {(*v)[0], (*v)[1], (*v)[2]};
}

/// --pose-error NAME=VALUE: the fields of rig::PoseErrorConfig (vectors as X,Y,Z).
void SetPoseError(rig::PoseErrorConfig& cfg, const std::string& assignment) {
    const std::size_t eq = assignment.find('=');
    const std::string field = "pose_error";
    if (eq == std::string::npos) {
        throw MakeInputError("", field, assignment, "expected NAME=VALUE");
    }
    const std::string name = assignment.substr(0, eq);
    const std::string value = assignment.substr(eq + 1);
    const std::string where = field + " " + name;
    if (name == "position_bias_m") {
        cfg.position_bias_m = ParseVector3(value, where);
    } else if (name == "attitude_bias_deg") {
        cfg.attitude_bias_deg = ParseVector3(value, where);
    } else if (name == "position_random_walk_m_per_sqrt_s") {
        cfg.position_random_walk_m_per_sqrt_s = ParseDouble(value, where, value);
    } else if (name == "attitude_random_walk_deg_per_sqrt_s") {
        cfg.attitude_random_walk_deg_per_sqrt_s = ParseDouble(value, where, value);
    } else if (name == "position_jitter_m") {
        cfg.position_jitter_m = ParseDouble(value, where, value);
    } else if (name == "attitude_jitter_deg") {
        cfg.attitude_jitter_deg = ParseDouble(value, where, value);
    } else if (name == "seed") {
        std::uint64_t seed = 0;
        const auto [ptr, ec] = std::from_chars(value.data(), value.data() + value.size(), seed);
        if (ec != std::errc() || ptr != value.data() + value.size()) {
            throw MakeInputError("", where, value, "must be a non-negative integer");
        }
        cfg.seed = seed;
    } else {
        throw MakeInputError("", field, name,
                             "allowed: position_bias_m, attitude_bias_deg, "
                             "position_random_walk_m_per_sqrt_s, "
                             "attitude_random_walk_deg_per_sqrt_s, position_jitter_m, "
                             "attitude_jitter_deg, seed");
    }
    cfg.enabled = true;
}

}  // namespace

rig::CourseConfig PaperCourse() {
    rig::CourseConfig course;
    course.start_x_m = 1.0;
    course.end_x_m = 6.0;
    course.lateral_offset_m = 0.0;
    course.width_m = 2.0;
    return course;
}

SimSetup ResolveSimSetup(const SimFlags& flags) {
    SimSetup s;
    s.scene_path = flags.scene_path;
    s.motion_name = flags.motion;
    s.seed = flags.seed;
    s.vehicle = flags.motion == "vehicle";
    if (!s.vehicle) {
        try {
            s.motion = rig::ParseMotion(flags.motion, "motion");
        } catch (const InputError&) {
            throw MakeInputError("", "motion", flags.motion, "allowed: T, TR, TP, TRP, vehicle");
        }
    }
    s.table.course = PaperCourse();
    s.pose_error.seed = flags.seed;
    if (!flags.rig_path.empty()) {
        // The rig file decides everything it can set, the course region and the pose-error
        // seed included.
        const io::RigConfig rig = io::LoadRigConfig(flags.rig_path);
        s.rig_path = flags.rig_path;
        s.table = rig.table;
        s.vehicle_config = rig.vehicle;
        s.pose_error = rig.pose_error;
    }
    if (flags.speed_m_s) {
        const double v = *flags.speed_m_s;
        const double limit =
            s.vehicle ? rig::VehicleLimits::kMaxSpeedMS : rig::TableLimits::kMaxSpeedMS;
        if (!(v > 0.0 && v <= limit)) {
            throw MakeInputError("", "speed_m_s", FormatNumber(v),
                                 "allowed: > 0 and <= " + FormatNumber(limit) + " m/s (the " +
                                     (s.vehicle ? "vehicle" : "table") + "'s limit)");
        }
        s.table.speed_m_s = v;
        s.vehicle_config.speed_m_s = v;
    }
    for (const std::string& a : flags.pose_error) {
        SetPoseError(s.pose_error, a);
    }
    s.pose_error.Validate();
    if (s.vehicle) {  // a rule broken by a flag's value (--speed) still names the rig file
        s.vehicle_config.Validate(s.rig_path);
    } else {
        s.table.Validate(s.rig_path);
    }
    if (!flags.sensor_path.empty()) {
        s.lms = io::LoadLms200Config(flags.sensor_path);
        s.sensor_path = flags.sensor_path;
    }
    s.lms.Validate();
    const rig::CourseConfig& c = s.table.course;
    s.grid.cell_m = 0.025;
    s.grid.x0_m = c.start_x_m;
    s.grid.y0_m = c.lateral_offset_m - 0.5 * c.width_m;
    s.grid.rows = static_cast<int>(std::lround((c.end_x_m - c.start_x_m) / s.grid.cell_m));
    s.grid.cols = static_cast<int>(std::lround(c.width_m / s.grid.cell_m));
    s.grid.Validate();
    return s;
}

std::string EffectiveConfigYaml(const SimSetup& s) {
    YAML::Emitter out;
    out << YAML::Comment("casmap simulate: the effective configuration of this run");
    out << YAML::BeginMap;
    out << YAML::Key << "scene" << YAML::Value << s.scene_path;
    out << YAML::Key << "motion" << YAML::Value << s.motion_name;
    out << YAML::Key << "seed" << YAML::Value << s.seed;
    out << YAML::Key << "grid" << YAML::Value;
    io::EmitGrid(out, s.grid);
    io::EmitPathOrNull(out, "rig_file", s.rig_path);
    io::EmitPathOrNull(out, "sensor_file", s.sensor_path);
    io::EmitCommentLine(out, "the LMS 200, every key, in the format of config/lms200.yaml");
    out << YAML::Key << "sensor" << YAML::Value;
    io::EmitLms200Config(out, s.lms);
    io::EmitCommentLine(out,
                        "the rig, every key, in the format of config/rig_table.yaml (table: "
                        "T/TR/TP/TRP; vehicle)");
    io::EmitRigConfig(out, io::RigConfig{s.table, s.vehicle_config, s.pose_error});
    out << YAML::EndMap;
    return io::EmittedText(out);
}

core::Trajectory RigTrajectory(const SimSetup& setup, const core::Scene& scene) {
    if (setup.vehicle) {
        return rig::SimulateVehicle(scene, setup.vehicle_config);
    }
    return rig::SimulateTable(setup.table, setup.motion);
}

namespace {
std::size_t ScanCountFor(const sensor_models::Lms200Model& model,
                         const core::Trajectory& trajectory) {
    if (trajectory.size() < 2) {
        return 0;
    }
    // Interleaved resolutions (0.5, 0.25 deg) take their beams out of angle order: the
    // latest beam is not the last one.
    double latest = 0.0;
    for (std::size_t i = 0; i < model.BeamCount(); ++i) {
        latest = std::max(latest, model.BeamTimeOffsetS(i));
    }
    const double span = trajectory.EndTime() - trajectory.StartTime() - latest;
    if (span < 0.0) {
        return 0;
    }
    auto count = static_cast<std::size_t>(std::floor(span / model.ScanPeriodS())) + 1;
    // The quotient may round up across an integer: keep the last scan's latest beam within the
    // trajectory with the very expression sim::CastScan checks.
    const double start = trajectory.StartTime();
    while (count > 0 && !(start + static_cast<double>(count - 1) * model.ScanPeriodS() + latest <=
                          trajectory.EndTime())) {
        --count;
    }
    return count;
}
}  // namespace

std::size_t ScanCount(const SimSetup& setup, const core::Trajectory& trajectory) {
    return ScanCountFor(sensor_models::Lms200Model(setup.lms, setup.seed), trajectory);
}

SimulatedRun SimulateRun(const SimSetup& setup,
                         const core::Scene& scene,
                         const sim::World& world,
                         core::Trajectory true_poses,
                         const SimulateRunOptions& options) {
    const sensor_models::Lms200Model model(setup.lms, setup.seed);
    sim::SimulateOptions sim_options;
    sim_options.start_s = true_poses.empty() ? 0.0 : true_poses.StartTime();
    sim_options.period_s = model.ScanPeriodS();
    sim_options.scan_count = ScanCountFor(model, true_poses);
    sim_options.threads = options.threads;
    sim_options.progress = options.progress;
    std::vector<sim::ScanResult> results = sim::Simulate(world, model, true_poses, sim_options);
    SimulatedRun out;
    io::RunData& run = out.run;
    run.scans.reserve(results.size());
    run.truth.reserve(results.size());
    for (sim::ScanResult& r : results) {
        run.scans.push_back(std::move(r.scan));
        run.truth.push_back(std::move(r.truth));
    }
    run.poses =
        setup.pose_error.enabled ? rig::ApplyPoseError(true_poses, setup.pose_error) : true_poses;
    out.true_poses = std::move(true_poses);
    run.format = setup.lms.format;
    run.seed = setup.seed;
    run.config_yaml = EffectiveConfigYaml(setup);
    run.maps.grid = setup.grid;
    if (options.truth) {
        run.maps.truth_m = sim::GroundTruthElevation(scene, setup.grid, options.threads);
    }
    return out;
}

}  // namespace casmap::pipeline
