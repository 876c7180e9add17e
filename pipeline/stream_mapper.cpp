#include "casmap/pipeline/stream_mapper.hpp"

#include <optional>
#include <utility>
#include <variant>
#include <vector>

#include "casmap/core/input_error.hpp"
#include "casmap/mapper/kalman_mapper.hpp"
#include "casmap/mapper/sweep_jump_stream.hpp"

namespace casmap::pipeline {

struct StreamMapper::Impl {
    std::variant<mapper::TerrainMapper, mapper::KalmanMapper> mapper;
    std::optional<mapper::SweepJumpStream> sweep;

    void Map(const core::Scan& scan,
             const core::Trajectory& world_T_sensor,
             const std::vector<std::uint8_t>& keep) {
        std::visit([&](auto& m) { m.AddScan(scan, world_T_sensor, keep); }, mapper);
    }
    void Drain() {
        while (std::optional<mapper::SweepJumpStream::Labelled> l = sweep->Pop()) {
            Map(l->scan, l->poses, l->keep);
        }
    }
};

namespace {

// The mapper MapScans builds for `settings` (map_run.cpp), with the scan period given.
std::variant<mapper::TerrainMapper, mapper::KalmanMapper> MakeMapper(const core::GridGeometry& grid,
                                                                     const MapSettings& settings,
                                                                     double scan_period_s) {
    if (settings.mode == MapperMode::kKalman) {
        mapper::KalmanMapperConfig kalman;
        static_cast<mapper::KalmanNoiseConfig&>(kalman) = settings.kalman;
        kalman.grid = grid;
        kalman.a = settings.a;
        kalman.scan_period_s = scan_period_s;
        kalman.unknown = settings.unknown;
        return mapper::KalmanMapper(kalman);
    }
    mapper::TerrainMapperConfig config;
    config.grid = grid;
    config.a = settings.a;
    config.delta_l_m = settings.delta_l_m;
    config.scan_period_s = scan_period_s;
    config.unknown = settings.unknown;
    if (settings.mode == MapperMode::kConsensus) {
        config.consensus = settings.consensus;
    }
    return mapper::TerrainMapper(config);
}

}  // namespace

StreamMapper::StreamMapper(const core::GridGeometry& grid,
                           const MapSettings& settings,
                           double scan_period_s)
    : settings_(settings), grid_(grid) {
    settings_.Validate();
    impl_ = std::make_unique<Impl>(Impl{MakeMapper(grid, settings_, scan_period_s), {}});
    if (settings_.prefilter == Prefilter::kSweepJump) {
        impl_->sweep.emplace(settings_.sweep_jump);
    }
}

StreamMapper::~StreamMapper() = default;
StreamMapper::StreamMapper(StreamMapper&&) noexcept = default;
StreamMapper& StreamMapper::operator=(StreamMapper&&) noexcept = default;

void StreamMapper::AddScan(core::Scan scan, core::Trajectory world_T_sensor) {
    if (finished_) {
        throw MakeInputError("stream mapper", "AddScan", "after Finish()",
                             "the stream has ended; map further scans with a new mapper");
    }
    if (impl_->sweep) {
        impl_->sweep->Push(std::move(scan), std::move(world_T_sensor));
        impl_->Drain();
        return;
    }
    impl_->Map(scan, world_T_sensor, PrefilterLabels(scan, settings_));
}

void StreamMapper::Finish() {
    if (finished_) {
        return;
    }
    finished_ = true;
    if (impl_->sweep) {
        impl_->sweep->Finish();
        impl_->Drain();
    }
}

const core::MapF& StreamMapper::elevation() const {
    return std::visit([](const auto& m) -> const core::MapF& { return m.elevation(); },
                      impl_->mapper);
}

const core::MapF& StreamMapper::certainty() const {
    return std::visit([](const auto& m) -> const core::MapF& { return m.certainty(); },
                      impl_->mapper);
}

const mapper::MapperStats& StreamMapper::stats() const {
    return std::visit([](const auto& m) -> const mapper::MapperStats& { return m.stats(); },
                      impl_->mapper);
}

std::size_t StreamMapper::waiting() const { return impl_->sweep ? impl_->sweep->waiting() : 0; }

}  // namespace casmap::pipeline
