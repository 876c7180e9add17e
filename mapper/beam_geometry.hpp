#pragma once

// Per-beam math of Eq. 1-6 shared by the offline TerrainMapper and the live ActiveWindow:
// the pose of every beam (interpolated at its own time), its world point (Eq. 1), its
// Delta z_max (Eq. 4) and the cell update of Eq. 5-6. Inline so both hot loops compile to the
// same instructions, which keeps the live window's cells bit for bit equal to the offline map's.

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <span>
#include <vector>

#include "casmap/core/scan.hpp"
#include "casmap/core/trajectory.hpp"
#include "casmap/mapper/beam_batch.hpp"
#include "casmap/mapper/terrain_mapper.hpp"

namespace casmap::mapper::detail {

// cos(pitch) from R = Rz Ry Rx: the norm of (r21, r22) = (cp sr, cp cr); never below a tiny
// positive value so the pitch-90-degree singularity yields finite numbers.
inline double CosPitch(const Eigen::Matrix3d& r) {
    return std::max(std::sqrt(r(2, 1) * r(2, 1) + r(2, 2) * r(2, 2)), 1e-12);
}

// atan2(y, x) for the small angle changes between two poses (x > 0, |y| < 0.1 x) by its
// series (error < 1e-9 rad); std::atan2 otherwise.
inline double SmallAngle(double y, double x) {
    if (x > 0.0 && std::abs(y) < 0.1 * x) {
        const double r = y / x;
        const double r2 = r * r;
        return r * (1.0 - r2 * (1.0 / 3.0 - r2 * (1.0 / 5.0 - r2 * (1.0 / 7.0 - r2 / 9.0))));
    }
    return std::atan2(y, x);
}

// Roll and pitch change from the last rows of two rotation matrices (see MotionBetween).
inline void AngleChanges(const Eigen::Vector3d& row_before,
                         const Eigen::Vector3d& row_after,
                         BeamMotion& m) {
    m.d_roll_rad = SmallAngle(row_before.z() * row_after.y() - row_before.y() * row_after.z(),
                              row_before.z() * row_after.z() + row_before.y() * row_after.y());
    const double c0 = std::max(
        std::sqrt(row_before.y() * row_before.y() + row_before.z() * row_before.z()), 1e-12);
    const double c1 =
        std::max(std::sqrt(row_after.y() * row_after.y() + row_after.z() * row_after.z()), 1e-12);
    const double s0 = -row_before.x();
    const double s1 = -row_after.x();
    m.d_pitch_rad = SmallAngle(c0 * s1 - s0 * c1, c0 * c1 + s0 * s1);
}

// Last row of the rotation matrix of a unit quaternion.
inline Eigen::Vector3d ZRow(const Eigen::Quaterniond& q) {
    return {2.0 * (q.x() * q.z() - q.w() * q.y()), 2.0 * (q.y() * q.z() + q.w() * q.x()),
            1.0 - 2.0 * (q.x() * q.x() + q.y() * q.y())};
}

// Eq. 4 with the beam direction given as cos/sin of its angle.
inline double DeltaZMaxCs(
    const SensorState& state, double ca, double sa, double range_m, double delta_l_m) {
    const Eigen::Matrix3d& r = state.world_R_sensor;
    const double cp = CosPitch(r);
    const double inv_cp = 1.0 / cp;
    const double d_range = r(2, 0) * ca + r(2, 1) * sa;
    const double d_roll = range_m * r(2, 2) * sa;
    const double d_pitch = -range_m * (cp * ca - r(2, 0) * r(2, 1) * inv_cp * sa);
    const BeamMotion& m = state.motion;
    // Displacement term: the paper's -dy tan(theta) is the slide of the beam up a vertical
    // face when the sensor moves dy horizontally with its x axis at pitch theta; a vertical
    // move shifts z one to one. tan(pitch) = |r20| / cp.
    const double horizontal = std::sqrt(m.displacement_m.x() * m.displacement_m.x() +
                                        m.displacement_m.y() * m.displacement_m.y());
    // Sum of magnitudes: a bound on the change, whatever the signs (paper_reading.md item 3).
    return std::abs(d_range) * delta_l_m + std::abs(d_roll * m.d_roll_rad) +
           std::abs(d_pitch * m.d_pitch_rad) + std::abs(m.displacement_m.z()) +
           horizontal * (std::abs(r(2, 0)) * inv_cp);
}

/// Eq. 5 and Eq. 6 on one cell (h in m, c in counts) for a world height z with its
/// Delta z_max and certainty increment a. `nan_unknown`: an unknown cell holds NaN
/// (Unknown::kNaN) and its first hit sets the height.
inline void UpdateCell(
    float& h, float& c, double z, double dz_max_m, int a, bool nan_unknown = false) {
    // Eq. 5, against h^t before Eq. 6 updates it; every first hit (c == 0) gets a.
    const bool first = c == 0.0F;
    if (first || std::abs(z - static_cast<double>(h)) <= std::abs(dz_max_m)) {
        c += static_cast<float>(a);
    }
    // Eq. 6: keep the height of largest magnitude.
    if (std::abs(z) > std::abs(static_cast<double>(h)) || (first && nan_unknown)) {
        h = static_cast<float>(z);
    }
}

/// Eq. 1-4 for every valid beam of `scan` with the pose at its own time:
/// `point(p_world, dz_max_m)` is called per beam that has a pose, in beam order; `stats`
/// counts beams seen, not ok, rejected by `keep` (empty, or one label per beam, 0 = skip) and
/// without pose. `dirs` must be Update()d for the scan. The per-beam math runs as one batch per
/// scan (mapper/beam_batch.hpp: AVX2 lanes, the same bits on the scalar path), so the offline
/// TerrainMapper and the live ActiveWindow get identical points.
template <typename PointFn>
void ForEachBeamPoint(const core::Scan& scan,
                      const core::Trajectory& world_T_sensor,
                      const BeamDirections& dirs,
                      double scan_period_s,
                      double delta_l_m,
                      MapperStats& stats,
                      PointFn&& point,
                      std::span<const std::uint8_t> keep = {}) {
    const std::size_t n = scan.beams.size();
    stats.beams_seen += n;
    if (world_T_sensor.empty()) {
        stats.beams_no_pose += n;
        return;
    }
    thread_local BeamBatch batch;  // per-thread scratch, reused from scan to scan
    const FillCounts counts = FillBatch(scan, world_T_sensor, dirs, scan_period_s, keep, batch);
    stats.beams_not_ok += counts.not_ok;
    stats.beams_rejected += counts.rejected;
    stats.beams_no_pose += counts.no_pose;
    ComputeBatch(delta_l_m, batch);
    for (std::size_t j = 0; j < batch.size; ++j) {
        point(Eigen::Vector3d(batch.x[j], batch.y[j], batch.z[j]), batch.dz_max[j]);
    }
}

}  // namespace casmap::mapper::detail
