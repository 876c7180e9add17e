#pragma once

// A second mapper mode, the established baseline of the elevation-mapping literature
// (Fankhauser et al., "Robot-Centric Elevation Mapping with Uncertainty Estimates", CLAWAR
// 2014; "Probabilistic Terrain Mapping for Mobile Robots with Uncertain Pose Estimates", ICRA
// 2018): each scan's lowest point per cell, with a height variance from the sensor's noise
// model, fused into the cell's estimate by a 1-D Kalman filter; a measurement outside the
// Mahalanobis gate does not fuse but inflates the cell's variance (so a changed surface takes
// over after a few scans). Same inputs, grid and pose handling as TerrainMapper (Eq. 1-3).

#include <cstdint>
#include <span>
#include <vector>

#include "casmap/core/grid.hpp"
#include "casmap/core/scan.hpp"
#include "casmap/core/trajectory.hpp"
#include "casmap/mapper/beam_batch.hpp"
#include "casmap/mapper/kalman_noise.hpp"
#include "casmap/mapper/terrain_mapper.hpp"
#include "casmap/mapper/unknown.hpp"

namespace casmap::mapper {

/// Kalman elevation mapper settings: the noise model and gate (KalmanNoiseConfig, settable as
/// the filter parameters kalman.<field>) and what the run decides (grid, scan period, a, unknown).
struct KalmanMapperConfig : KalmanNoiseConfig {
    core::GridGeometry grid;
    double scan_period_s = 1.0 / 75.0;  // pose one scan earlier (shared Eq. 1-4 batch)
    int a = 3;                          // certainty increment per fused scan (as Eq. 5's a)
    Unknown unknown = Unknown::kZero;   // never-observed elevation: 0 (paper) or NaN
    void Validate() const;              // throws InputError naming the field ("kalman.<field>")
};

/// Elevation (fused height), certainty (a per fused scan) and variance (m^2; NaN where
/// unknown) maps. Deterministic: cells are fused in beam order at the end of each scan.
class KalmanMapper {
public:
    explicit KalmanMapper(const KalmanMapperConfig& config);  // validates config

    /// As TerrainMapper::AddScan (keep labels from scan pre-filters, same statistics).
    void AddScan(const core::Scan& scan,
                 const core::Trajectory& world_T_sensor,
                 std::span<const std::uint8_t> keep = {});

    /// One height measurement of a cell (row-major index) with its variance (m^2).
    void Fuse(std::size_t cell, double z_m, double variance_m2);

    /// Height variance (m^2) of a point at range `range_m` whose beam has world z component
    /// `beam_z` (the config's noise model).
    [[nodiscard]] double PointVariance(double range_m, double beam_z) const;

    [[nodiscard]] const core::MapF& elevation() const { return elevation_; }
    [[nodiscard]] const core::MapF& certainty() const { return certainty_; }
    [[nodiscard]] const core::MapF& variance() const { return variance_; }
    [[nodiscard]] const KalmanMapperConfig& config() const { return config_; }
    [[nodiscard]] const MapperStats& stats() const { return stats_; }

private:
    KalmanMapperConfig config_;
    core::MapF elevation_;
    core::MapF certainty_;
    core::MapF variance_;
    MapperStats stats_;
    detail::BeamBatch batch_;
    BeamDirections dirs_;
    // Per-scan lowest point: scan index that last touched a cell, its z and variance.
    std::vector<std::uint64_t> touched_scan_;
    std::vector<double> scan_z_, scan_var_;
    std::vector<std::size_t> touched_;
    std::uint64_t scan_index_ = 0;
};

}  // namespace casmap::mapper
