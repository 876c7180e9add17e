#include "casmap/mapper/terrain_mapper.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <string>

#include "casmap/core/check.hpp"
#include "casmap/core/input_error.hpp"
#include "casmap/core/text.hpp"
#include "casmap/mapper/beam_geometry.hpp"
#include "casmap/mapper/consensus_cells.hpp"

namespace casmap::mapper {
using detail::AngleChanges;
using detail::CosPitch;
using detail::DeltaZMaxCs;
using detail::ZRow;

void TerrainMapperConfig::Validate() const {
    grid.Validate();
    const core::Check check("mapper");
    check.NonNegative("delta_l_m", delta_l_m, "must be finite and >= 0");
    check.That(a >= 1, "a", a, "must be a positive integer");
    check.Positive("scan_period_s", scan_period_s, "must be finite and > 0");
    if (consensus) {
        consensus->Validate();
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
    return DeltaZMaxCs(state, std::cos(angle_rad), std::sin(angle_rad), range_m, delta_l_m);
}

BeamMotion MotionBetween(const core::Pose& before, const core::Pose& after) {
    // roll = atan2(r21, r22): the angle from (r22, r21)_before to (r22, r21)_after; pitch =
    // atan2(-r20, cp): the same angle difference in the (cp, sp) plane.
    BeamMotion m;
    m.displacement_m = after.translation - before.translation;
    AngleChanges(ZRow(before.rotation.normalized()), ZRow(after.rotation.normalized()), m);
    return m;
}

void BeamDirections::Update(const core::Scan& scan) {
    const std::size_t n = scan.beams.size();
    if (n == cos.size() && scan.start_angle_rad == start_rad && scan.angle_step_rad == step_rad) {
        return;
    }
    cos.resize(n);
    sin.resize(n);
    for (std::size_t i = 0; i < n; ++i) {
        cos[i] = std::cos(scan.BeamAngle(i));
        sin[i] = std::sin(scan.BeamAngle(i));
    }
    start_rad = scan.start_angle_rad;
    step_rad = scan.angle_step_rad;
}

TerrainMapper::TerrainMapper(const TerrainMapperConfig& config) : config_(config) {
    config_.Validate();
    const float unknown =
        config_.unknown == Unknown::kNaN ? std::numeric_limits<float>::quiet_NaN() : 0.0F;
    elevation_ = core::MapF(config_.grid.rows, config_.grid.cols, unknown);
    certainty_ = core::MapF(config_.grid.rows, config_.grid.cols, 0.0F);
    if (config_.consensus) {
        eq6_ = elevation_;
        const std::size_t cells = elevation_.data.size();
        sum_m_.assign(cells, 0.0);
        hits_.assign(cells, 0);
        low_m_.assign(cells, std::numeric_limits<float>::infinity());
        high_m_.assign(cells, -std::numeric_limits<float>::infinity());
    }
}

void TerrainMapper::Update(std::size_t idx, double z, double dz_max_m) {
    const bool nan = config_.unknown == Unknown::kNaN;
    if (!config_.consensus) {
        detail::UpdateCell(elevation_.data[idx], certainty_.data[idx], z, dz_max_m, config_.a, nan);
        return;
    }
    detail::UpdateConsensusCell(elevation_.data[idx], certainty_.data[idx], eq6_.data[idx],
                                sum_m_[idx], hits_[idx], low_m_[idx], high_m_[idx], z, dz_max_m,
                                config_.a, nan, *config_.consensus);
}

bool TerrainMapper::AddPoint(const Eigen::Vector3d& p_world, double dz_max_m) {
    const std::optional<core::Cell> cell = config_.grid.CellOf(p_world.x(), p_world.y());
    if (!cell) {
        return false;
    }
    Update(static_cast<std::size_t>(cell->row) * static_cast<std::size_t>(config_.grid.cols) +
               static_cast<std::size_t>(cell->col),
           p_world.z(), dz_max_m);
    return true;
}

void TerrainMapper::AddBeam(const SensorState& state, double angle_rad, double range_m) {
    AddBeamCs(state, std::cos(angle_rad), std::sin(angle_rad), range_m);
}

void TerrainMapper::AddBeamCs(const SensorState& state, double ca, double sa, double range_m) {
    const Eigen::Matrix3d& r = state.world_R_sensor;
    const Eigen::Vector3d p_world =
        r.col(0) * (range_m * ca) + r.col(1) * (range_m * sa) + state.origin_m;
    if (AddPoint(p_world, DeltaZMaxCs(state, ca, sa, range_m, config_.delta_l_m))) {
        ++stats_.beams_mapped;
    } else {
        ++stats_.beams_outside;
    }
}

void TerrainMapper::AddScan(const core::Scan& scan,
                            const core::Trajectory& world_T_sensor,
                            std::span<const std::uint8_t> keep) {
    if (!keep.empty() && keep.size() != scan.beams.size()) {
        throw MakeInputError(
            "mapper", "keep labels", std::to_string(keep.size()),
            "must have one entry per beam (" + std::to_string(scan.beams.size()) + ")");
    }
    dirs_.Update(scan);
    const std::size_t n = scan.beams.size();
    stats_.beams_seen += n;
    if (world_T_sensor.empty()) {
        stats_.beams_no_pose += n;
        return;
    }
    // The batch of detail::ForEachBeamPoint (the live window's path: the same points), plus
    // the grid cells computed four at a time.
    thread_local detail::BeamBatch batch;  // per-thread scratch, reused from scan to scan
    const detail::FillCounts counts =
        detail::FillBatch(scan, world_T_sensor, dirs_, config_.scan_period_s, keep, batch);
    stats_.beams_not_ok += counts.not_ok;
    stats_.beams_rejected += counts.rejected;
    stats_.beams_no_pose += counts.no_pose;
    const core::GridGeometry& g = config_.grid;
    detail::ComputeBatch(config_.delta_l_m, batch, &g);
    const bool nan = config_.unknown == Unknown::kNaN;
    const bool consensus = config_.consensus.has_value();
    for (std::size_t j = 0; j < batch.size; ++j) {
        const double r = batch.row[j];
        const double c = batch.col[j];
        if (!(r >= 0.0 && c >= 0.0 && r < g.rows && c < g.cols)) {
            ++stats_.beams_outside;  // also NaN
            continue;
        }
        const std::size_t idx = static_cast<std::size_t>(r) * static_cast<std::size_t>(g.cols) +
                                static_cast<std::size_t>(c);
        if (consensus) {
            Update(idx, batch.z[j], batch.dz_max[j]);
        } else {
            detail::UpdateCell(elevation_.data[idx], certainty_.data[idx], batch.z[j],
                               batch.dz_max[j], config_.a, nan);
        }
        ++stats_.beams_mapped;
    }
}

}  // namespace casmap::mapper
