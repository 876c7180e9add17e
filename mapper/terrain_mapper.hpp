#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <optional>
#include <span>
#include <vector>

#include "casmap/core/grid.hpp"
#include "casmap/core/pose.hpp"
#include "casmap/core/scan.hpp"
#include "casmap/core/trajectory.hpp"
#include "casmap/mapper/consensus.hpp"
#include "casmap/mapper/unknown.hpp"

namespace casmap::mapper {

/// Terrain mapper settings (paper Sec. II.A).
struct TerrainMapperConfig {
    core::GridGeometry grid;            // world x along-track (rows), y across-track (cols)
    double delta_l_m = 0.032;           // Eq. 4 delta-l: LMS 200 maximum range error [10]
    int a = 3;                          // Eq. 5 certainty increment, a positive integer
    double scan_period_s = 1.0 / 75.0;  // Eq. 4: time between two consecutive measurements
    Unknown unknown = Unknown::kZero;   // never-observed elevation: 0 (paper) or NaN (grid_map)
    std::optional<ConsensusConfig> consensus;  // unset: the paper's Eq. 6 for every cell
    void Validate() const;                     // throws InputError naming the field
};

/// How the sensor moved during the scan period before a beam (the deltas of Eq. 4).
struct BeamMotion {
    Eigen::Vector3d displacement_m = Eigen::Vector3d::Zero();  // o(t) - o(t - T), world frame
    double d_roll_rad = 0.0;                                   // roll(t) - roll(t - T)
    double d_pitch_rad = 0.0;                                  // pitch(t) - pitch(t - T)
};

/// Sensor pose at one beam's time plus its motion: everything Eq. 1-4 need for that beam.
struct SensorState {
    Eigen::Matrix3d world_R_sensor = Eigen::Matrix3d::Identity();  // R = Rz Ry Rx
    Eigen::Vector3d origin_m = Eigen::Vector3d::Zero();            // sensor origin, world
    BeamMotion motion;
};

/// Partial derivatives of the beam's world z (Eq. 1) at a pose, the sensor origin held fixed.
struct ZPartials {
    double d_range = 0.0;  // dz/dl (m/m)
    double d_roll = 0.0;   // dz/droll (m/rad), roll of R = Rz(yaw) Ry(pitch) Rx(roll)
    double d_pitch = 0.0;  // dz/dpitch (m/rad)
};

/// Eq. 1: world point of a beam at `angle_rad` about sensor +z with range `range_m`.
[[nodiscard]] Eigen::Vector3d BeamToWorld(const core::Pose& world_T_sensor,
                                          double angle_rad,
                                          double range_m);

/// Analytic partials of z_world with respect to range, roll and pitch (Eq. 4's terms).
[[nodiscard]] ZPartials BeamZPartials(const Eigen::Matrix3d& world_R_sensor,
                                      double angle_rad,
                                      double range_m);

/// Eq. 4 generalised to any pose (docs/paper-notes.md): sum of magnitudes of the range,
/// roll and pitch terms plus the displacement term |dz_o| + |d_horizontal| * |tan(pitch)|.
[[nodiscard]] double DeltaZMax(const SensorState& state,
                               double angle_rad,
                               double range_m,
                               double delta_l_m);

/// Roll and pitch change from `before` to `after` (radians, wrapped to (-pi, pi]).
[[nodiscard]] BeamMotion MotionBetween(const core::Pose& before, const core::Pose& after);

/// Counts of what AddScan did with the beams it saw.
struct MapperStats {
    std::uint64_t beams_seen = 0;
    std::uint64_t beams_not_ok = 0;    // status != kOk: update nothing
    std::uint64_t beams_rejected = 0;  // a scan pre-filter's keep label was 0: skipped
    std::uint64_t beams_no_pose = 0;   // beam time outside the trajectory: skipped
    std::uint64_t beams_outside = 0;   // world point outside the grid
    std::uint64_t beams_mapped = 0;
};

/// Cosine and sine of every beam angle of a scan geometry, recomputed only when it changes.
struct BeamDirections {
    std::vector<double> cos, sin;
    double start_rad = 0.0;
    double step_rad = 0.0;
    void Update(const core::Scan& scan);  // no-op while the geometry stays the same
};

/// Elevation map H and certainty map C built by Eq. 1-6. Unknown cells hold elevation 0 (or NaN
/// with Unknown::kNaN) and certainty 0, as in the paper. Certainty is a float count (multiples
/// of a). Cost per beam is independent of the run's length (bench/mapper_bench.cpp). With
/// `config.consensus` set, H holds the consensus cell height (ConsensusConfig); Eq. 5 and the
/// certainty still compare each point with the cell's Eq. 6 height, so C is the paper's.
class TerrainMapper {
public:
    explicit TerrainMapper(const TerrainMapperConfig& config);  // validates config

    /// Maps every beam of `scan` with the pose at its own time scan.BeamTime(i); beams with
    /// status != kOk update nothing, beams whose time has no pose are skipped. `keep` (empty,
    /// or one entry per beam, e.g. from mapper/scan_filters.hpp) skips beams labelled 0;
    /// InputError if its size differs from the scan's.
    void AddScan(const core::Scan& scan,
                 const core::Trajectory& world_T_sensor,
                 std::span<const std::uint8_t> keep = {});

    /// Lower-level entry: one valid beam (sensor frame angle, range in m) at a known state.
    void AddBeam(const SensorState& state, double angle_rad, double range_m);

    /// Eq. 5 and Eq. 6 for one world point with its Delta z_max; returns false if off-grid.
    bool AddPoint(const Eigen::Vector3d& p_world, double dz_max_m);

    [[nodiscard]] const core::MapF& elevation() const { return elevation_; }
    [[nodiscard]] const core::MapF& certainty() const { return certainty_; }
    [[nodiscard]] const TerrainMapperConfig& config() const { return config_; }
    [[nodiscard]] const MapperStats& stats() const { return stats_; }

private:
    void Update(std::size_t idx, double z, double dz_max_m);  // Eq. 5-6 (+ consensus) of a cell
    void AddBeamCs(const SensorState& state, double cos_angle, double sin_angle, double range_m);

    TerrainMapperConfig config_;
    core::MapF elevation_;
    core::MapF certainty_;
    // Consensus mode only (empty otherwise): Eq. 6's height, and the sum, count, smallest and
    // largest of each cell's heights.
    core::MapF eq6_;
    std::vector<double> sum_m_;
    std::vector<std::uint32_t> hits_;
    std::vector<float> low_m_, high_m_;
    MapperStats stats_;
    BeamDirections dirs_;  // per-beam direction of the last scan geometry
};

}  // namespace casmap::mapper
