#include "casmap/pipeline/dataset_setup.hpp"

#include <cmath>
#include <numbers>

namespace casmap::pipeline {
namespace {

constexpr double kDegToRad = std::numbers::pi / 180.0;
// The vehicle's scanner stands about this high above the ground plus its mount height
// (wheel radius + suspension rest length of rig::VehicleConfig's defaults).
constexpr double kVehicleBaseHeightM = 0.27;
constexpr double kVehicleMountXM = 0.4;  // rig::VehicleConfig::mount_xyz_m.x()

bool IsVehicle(const scenegen::DomainDraw& d) { return d.motion == "vehicle"; }

// Horizontal distance from the vehicle's scanner to where its scan plane meets the ground.
double VehicleLookahead(const scenegen::DomainDraw& d) {
    return (kVehicleBaseHeightM + d.vehicle_mount_height_m) /
           std::tan(d.mount_pitch_deg * kDegToRad);
}

rig::CourseConfig Course(const scenegen::DatasetSpec& spec, const scenegen::DomainDraw& d) {
    rig::CourseConfig c;
    c.start_x_m = spec.region_start_x_m;
    c.end_x_m = spec.region_start_x_m + spec.region_length_m;
    c.lateral_offset_m = d.lateral_offset_m;
    c.width_m = spec.region_width_m;
    return c;
}

void SetSensor(const scenegen::DomainDraw& d, sensor_models::Lms200Config& lms) {
    lms.angular_resolution_deg = d.angular_resolution_deg;
    lms.field_of_view_deg = d.field_of_view_deg;
    lms.format.mode = d.range_mode == "16m"   ? core::RangeMode::k16m
                      : d.range_mode == "32m" ? core::RangeMode::k32m
                                              : core::RangeMode::k8m;
    lms.format.units =
        d.range_mode == "80m" ? core::RangeUnits::kCentimetre : core::RangeUnits::kMillimetre;
    lms.noise_sigma0_mm_units_m = d.noise_sigma0_m;
    lms.noise_sigma0_cm_units_m = 2.0 * d.noise_sigma0_m;  // the defaults' cm/mm ratio
    lms.divergence_rad = d.divergence_rad;
    lms.echo_width_m = d.echo_width_m;
    lms.lobe_bound_fraction = d.lobe_bound_fraction;
    lms.p_short = d.p_short;
    lms.p_dropout = d.p_dropout;
}

}  // namespace

scenegen::SceneGenConfig SampleSceneConfig(const scenegen::DatasetSpec& spec,
                                           const scenegen::DomainDraw& d) {
    scenegen::SceneGenConfig s = spec.scene;
    const rig::CourseConfig c = Course(spec, d);
    const double half = 0.5 * c.width_m;
    s.region_min_xy_m = {c.start_x_m, c.lateral_offset_m - half};
    s.region_max_xy_m = {c.end_x_m, c.lateral_offset_m + half};
    const double margin_y = 1.0;
    double ground_start = -1.0;  // the table's scanner starts near x = 0
    if (IsVehicle(d)) {
        const double look = VehicleLookahead(d);
        const double chassis_start = c.start_x_m - look - kVehicleMountXM - d.speed_m_s - 0.3;
        ground_start = std::min(ground_start, chassis_start - 1.5);
        // The lane the vehicle drives: no obstacles on it up to where the chassis stops.
        s.keep_out_min_xy_m = {ground_start, c.lateral_offset_m - 0.55};
        s.keep_out_max_xy_m = {c.end_x_m - look + 1.0, c.lateral_offset_m + 0.55};
    }
    s.ground_min_xy_m = {ground_start, s.region_min_xy_m.y() - margin_y};
    s.ground_max_xy_m = {c.end_x_m + 1.5, s.region_max_xy_m.y() + margin_y};
    return s;
}

SimSetup SampleSetup(const scenegen::DatasetSpec& spec,
                     const scenegen::DomainDraw& d,
                     const std::string& scene_path) {
    SimSetup s;
    s.scene_path = scene_path;
    s.motion_name = d.motion;
    s.vehicle = IsVehicle(d);
    s.seed = d.sensor_seed;
    s.table.course = Course(spec, d);
    s.table.output_decimation = spec.outputs.pose_decimation;
    s.vehicle_config.output_decimation = spec.outputs.pose_decimation;
    if (s.vehicle) {
        rig::VehicleConfig& v = s.vehicle_config;
        const double look = VehicleLookahead(d);
        v.speed_m_s = d.speed_m_s;
        v.mount_pitch_deg = d.mount_pitch_deg;
        v.mount_xyz_m.z() = d.vehicle_mount_height_m;
        v.start_xy_m = {s.table.course.start_x_m - look - kVehicleMountXM - d.speed_m_s - 0.3,
                        d.lateral_offset_m};
        v.end_x_m = s.table.course.end_x_m - look + 0.3;
    } else {
        rig::TableConfig& t = s.table;
        s.motion = rig::ParseMotion(d.motion, "domain.motion");
        t.speed_m_s = d.speed_m_s;
        t.sensor_height_m = d.sensor_height_m;
        t.mount_pitch_deg = d.mount_pitch_deg;
        const auto shape = [](bool triangle) {
            return triangle ? rig::ProfileShape::kTriangle : rig::ProfileShape::kSinusoid;
        };
        t.roll_profile = {shape(d.roll_triangle), 0.0, d.roll_amplitude_deg, d.roll_period_s, 0.0};
        t.pitch_profile = {shape(d.pitch_triangle), d.pitch_center_deg, d.pitch_amplitude_deg,
                           d.pitch_period_s, 0.0};
    }
    SetSensor(d, s.lms);
    rig::PoseErrorConfig& e = s.pose_error;
    e.enabled = d.pose_error;
    e.seed = d.pose_error_seed;
    if (d.pose_error) {
        e.position_bias_m = d.position_bias_m;
        e.attitude_bias_deg = d.attitude_bias_deg;
        e.position_jitter_m = d.position_jitter_m;
        e.attitude_jitter_deg = d.attitude_jitter_deg;
    }
    const std::string where = "dataset sample";
    e.Validate(where);
    if (s.vehicle) {
        s.vehicle_config.Validate(where);
    } else {
        s.table.Validate(where);
    }
    s.lms.Validate();
    const rig::CourseConfig& c = s.table.course;
    s.grid.cell_m = spec.cell_m;
    s.grid.x0_m = c.start_x_m;
    s.grid.y0_m = c.lateral_offset_m - 0.5 * c.width_m;
    s.grid.rows = static_cast<int>(std::lround((c.end_x_m - c.start_x_m) / s.grid.cell_m));
    s.grid.cols = static_cast<int>(std::lround(c.width_m / s.grid.cell_m));
    s.grid.Validate();
    return s;
}

}  // namespace casmap::pipeline
