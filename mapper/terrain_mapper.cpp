#include "mapper/terrain_mapper.hpp"

#include <algorithm>
#include <cmath>
#include <optional>
#include <string>

#include "core/input_error.hpp"

namespace casmap::mapper {
namespace {

// cos(pitch) from R = Rz Ry Rx: the norm of (r21, r22) = (cp sr, cp cr); never below a tiny
// positive value so the pitch-90-degree singularity yields finite numbers.
double CosPitch(const Eigen::Matrix3d& r) { return std::max(std::hypot(r(2, 1), r(2, 2)), 1e-12); }

// Walks a trajectory with mostly increasing query times, so the per-beam pose lookup costs a
// few comparisons instead of a binary search. Interpolation is core::Interpolate (linear in
// position, slerp in orientation), the same as Trajectory::PoseAt.
class PoseCursor {
public:
    explicit PoseCursor(const core::Trajectory& trajectory) : samples_(trajectory.samples()) {}

    std::optional<core::Pose> At(double t) {
        if (samples_.empty() || !(t >= samples_.front().stamp_s) || t > samples_.back().stamp_s) {
            return std::nullopt;
        }
        if (samples_.size() == 1) {
            return samples_.front().world_T_sensor;
        }
        if (t < samples_[k_].stamp_s) {
            k_ = 0;  // went backwards: restart (rare)
        }
        while (k_ + 2 < samples_.size() && samples_[k_ + 1].stamp_s <= t) {
            ++k_;
        }
        const core::TimedPose& a = samples_[k_];
        const core::TimedPose& b = samples_[k_ + 1];
        const double u = (t - a.stamp_s) / (b.stamp_s - a.stamp_s);
        return core::Interpolate(a.world_T_sensor, b.world_T_sensor, u);
    }

private:
    const std::vector<core::TimedPose>& samples_;
    std::size_t k_ = 0;
};

}  // namespace

void TerrainMapperConfig::Validate() const {
    grid.Validate();
    if (!(std::isfinite(delta_l_m) && delta_l_m >= 0.0)) {
        throw MakeInputError("mapper", "delta_l_m", std::to_string(delta_l_m),
                             "must be finite and >= 0");
    }
    if (a < 1) {
        throw MakeInputError("mapper", "a", std::to_string(a), "must be a positive integer");
    }
    if (!(std::isfinite(scan_period_s) && scan_period_s > 0.0)) {
        throw MakeInputError("mapper", "scan_period_s", std::to_string(scan_period_s),
                             "must be finite and > 0");
    }
}

Eigen::Vector3d BeamToWorld(const core::Pose& world_T_sensor, double angle_rad, double range_m) {
    const Eigen::Vector3d p_sensor(range_m * std::cos(angle_rad), range_m * std::sin(angle_rad),
                                   0.0);
    return world_T_sensor * p_sensor;
}

ZPartials BeamZPartials(const Eigen::Matrix3d& r, double angle_rad, double range_m) {
    // Row 2 of Rz(y) Ry(p) Rx(r) is (-sp, cp sr, cp cr), so for the beam (l ca, l sa, 0):
    // z = oz + l (-sp ca + cp sr sa); yaw does not enter.
    const double ca = std::cos(angle_rad);
    const double sa = std::sin(angle_rad);
    const double cp = CosPitch(r);
    ZPartials d;
    d.d_range = r(2, 0) * ca + r(2, 1) * sa;
    d.d_roll = range_m * r(2, 2) * sa;  // l cp cr sa
    // dz/dp = -l (cp ca + sp sr sa), with sp sr = -r20 * r21 / cp.
    d.d_pitch = -range_m * (cp * ca - r(2, 0) * r(2, 1) / cp * sa);
    return d;
}

double DeltaZMax(const SensorState& state, double angle_rad, double range_m, double delta_l_m) {
    const Eigen::Matrix3d& r = state.world_R_sensor;
    const ZPartials d = BeamZPartials(r, angle_rad, range_m);
    const BeamMotion& m = state.motion;
    // Displacement term: the paper's -dy tan(theta) is the slide of the beam up a vertical
    // face when the sensor moves dy horizontally with its x axis at pitch theta; a vertical
    // move shifts z one to one. tan(pitch) = |r20| / cp.
    const double horizontal = std::hypot(m.displacement_m.x(), m.displacement_m.y());
    const double tan_pitch = std::abs(r(2, 0)) / CosPitch(r);
    // Sum of magnitudes: a bound on the change, whatever the signs (paper_reading.md item 3).
    return std::abs(d.d_range) * delta_l_m + std::abs(d.d_roll * m.d_roll_rad) +
           std::abs(d.d_pitch * m.d_pitch_rad) + std::abs(m.displacement_m.z()) +
           horizontal * tan_pitch;
}

BeamMotion MotionBetween(const core::Pose& before, const core::Pose& after) {
    const Eigen::Matrix3d r0 = before.rotation.toRotationMatrix();
    const Eigen::Matrix3d r1 = after.rotation.toRotationMatrix();
    BeamMotion m;
    m.displacement_m = after.translation - before.translation;
    // roll = atan2(r21, r22): the angle from (r22, r21)_before to (r22, r21)_after.
    m.d_roll_rad = std::atan2(r0(2, 2) * r1(2, 1) - r0(2, 1) * r1(2, 2),
                              r0(2, 2) * r1(2, 2) + r0(2, 1) * r1(2, 1));
    // pitch = atan2(-r20, cp): the same angle difference in the (cp, sp) plane.
    const double c0 = CosPitch(r0);
    const double c1 = CosPitch(r1);
    const double s0 = -r0(2, 0);
    const double s1 = -r1(2, 0);
    m.d_pitch_rad = std::atan2(c0 * s1 - s0 * c1, c0 * c1 + s0 * s1);
    return m;
}

TerrainMapper::TerrainMapper(const TerrainMapperConfig& config) : config_(config) {
    config_.Validate();
    elevation_ = core::MapF(config_.grid.rows, config_.grid.cols, 0.0F);
    certainty_ = core::MapF(config_.grid.rows, config_.grid.cols, 0.0F);
}

bool TerrainMapper::AddPoint(const Eigen::Vector3d& p_world, double dz_max_m) {
    const std::optional<core::Cell> cell = config_.grid.CellOf(p_world.x(), p_world.y());
    if (!cell) {
        return false;
    }
    float& h = elevation_.at(cell->row, cell->col);
    float& c = certainty_.at(cell->row, cell->col);
    const double z = p_world.z();
    // Eq. 5, against h^t before Eq. 6 updates it; every first hit (c == 0) gets a.
    if (c == 0.0F || std::abs(z - static_cast<double>(h)) <= std::abs(dz_max_m)) {
        c += static_cast<float>(config_.a);
    }
    // Eq. 6: keep the height of largest magnitude.
    if (std::abs(z) > std::abs(static_cast<double>(h))) {
        h = static_cast<float>(z);
    }
    return true;
}

void TerrainMapper::AddBeam(const SensorState& state, double angle_rad, double range_m) {
    const Eigen::Vector3d p_sensor(range_m * std::cos(angle_rad), range_m * std::sin(angle_rad),
                                   0.0);
    const Eigen::Vector3d p_world = state.world_R_sensor * p_sensor + state.origin_m;
    if (AddPoint(p_world, DeltaZMax(state, angle_rad, range_m, config_.delta_l_m))) {
        ++stats_.beams_mapped;
    } else {
        ++stats_.beams_outside;
    }
}

void TerrainMapper::AddScan(const core::Scan& scan, const core::Trajectory& world_T_sensor) {
    if (world_T_sensor.empty()) {
        stats_.beams_seen += scan.beams.size();
        stats_.beams_no_pose += scan.beams.size();
        return;
    }
    PoseCursor now(world_T_sensor);
    PoseCursor before(world_T_sensor);
    const double start_s = world_T_sensor.StartTime();
    for (std::size_t i = 0; i < scan.beams.size(); ++i) {
        ++stats_.beams_seen;
        const core::Beam& beam = scan.beams[i];
        if (beam.status != core::BeamStatus::kOk) {
            ++stats_.beams_not_ok;
            continue;
        }
        const double t = scan.BeamTime(i);
        const std::optional<core::Pose> pose = now.At(t);
        if (!pose) {
            ++stats_.beams_no_pose;
            continue;
        }
        // The previous measurement was one scan period earlier; before the trajectory
        // starts, the motion since its start stands in (zero at the very first pose).
        const std::optional<core::Pose> prev =
            before.At(std::max(t - config_.scan_period_s, start_s));
        SensorState state;
        state.world_R_sensor = pose->rotation.toRotationMatrix();
        state.origin_m = pose->translation;
        state.motion = MotionBetween(*prev, *pose);
        AddBeam(state, scan.BeamAngle(i), static_cast<double>(beam.range_m));
    }
}

}  // namespace casmap::mapper
