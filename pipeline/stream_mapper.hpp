#pragma once

// MapScans (pipeline/map_run.hpp) fed one scan at a time, e.g. from a scanner or a Python
// loop: the same mapper modes (paper, consensus, kalman), unknown-cell conventions and scan
// pre-filters. The shadow and range_jump pre-filters label each scan on arrival; sweep_jump
// compares a scan with the next `reach` ones, so a scan is mapped once they have arrived
// (mapper::SweepJumpStream) and Finish() maps the last ones. After Finish() the maps equal
// MapScans' on the same scans bit for bit when the scan period given is the run's (ScanPeriod)
// and the scans are evenly spaced (the stream's median gap is then the run's).

#include <cstddef>
#include <memory>

#include "casmap/core/grid.hpp"
#include "casmap/core/scan.hpp"
#include "casmap/core/trajectory.hpp"
#include "casmap/mapper/terrain_mapper.hpp"
#include "casmap/pipeline/map_run.hpp"

namespace casmap::pipeline {

class StreamMapper {
public:
    /// Validates `settings` (InputError naming the field) and the grid.
    StreamMapper(const core::GridGeometry& grid, const MapSettings& settings, double scan_period_s);
    ~StreamMapper();
    StreamMapper(StreamMapper&&) noexcept;
    StreamMapper& operator=(StreamMapper&&) noexcept;
    StreamMapper(const StreamMapper&) = delete;
    StreamMapper& operator=(const StreamMapper&) = delete;

    /// The next scan (time order) with poses covering its beams' times. InputError after
    /// Finish().
    void AddScan(core::Scan scan, core::Trajectory world_T_sensor);
    /// No more scans: maps the ones a pre-filter still holds back. Idempotent.
    void Finish();

    [[nodiscard]] const core::MapF& elevation() const;
    [[nodiscard]] const core::MapF& certainty() const;
    /// beams_rejected counts the pre-filter's rejections among the scans mapped so far.
    [[nodiscard]] const mapper::MapperStats& stats() const;
    [[nodiscard]] const MapSettings& settings() const { return settings_; }
    [[nodiscard]] const core::GridGeometry& grid() const { return grid_; }
    /// Scans added but not yet mapped (sweep_jump: up to `reach`; 0 after Finish()).
    [[nodiscard]] std::size_t waiting() const;
    [[nodiscard]] bool finished() const { return finished_; }

private:
    struct Impl;
    MapSettings settings_;
    core::GridGeometry grid_;
    bool finished_ = false;
    std::unique_ptr<Impl> impl_;
};

}  // namespace casmap::pipeline
