#include "casmap/pipeline/map_run.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>

#include "casmap/core/check.hpp"
#include "casmap/core/input_error.hpp"
#include "casmap/core/lms200.hpp"
#include "casmap/core/text.hpp"
#include "casmap/io/image.hpp"
#include "casmap/io/yaml_emit.hpp"
#include "casmap/mapper/kalman_mapper.hpp"
#include "casmap/mapper/stage_params.hpp"
#include "casmap/pipeline/stage_yaml.hpp"

namespace casmap::pipeline {

double ScanPeriod(const std::vector<core::Scan>& scans) {
    if (scans.size() < 2) {
        return core::Lms200Timing::kTurnPeriodS;
    }
    std::vector<double> gaps;
    gaps.reserve(scans.size() - 1);
    for (std::size_t i = 1; i < scans.size(); ++i) {
        const double gap = scans[i].stamp_s - scans[i - 1].stamp_s;
        if (gap > 0.0) {
            gaps.push_back(gap);
        }
    }
    if (gaps.empty()) {
        return core::Lms200Timing::kTurnPeriodS;
    }
    const auto mid = gaps.begin() + static_cast<std::ptrdiff_t>(gaps.size() / 2);
    std::nth_element(gaps.begin(), mid, gaps.end());
    return *mid;
}

MapperMode ParseMapperMode(std::string_view text, const std::string& field) {
    if (text == "paper") {
        return MapperMode::kPaper;
    }
    if (text == "kalman") {
        return MapperMode::kKalman;
    }
    if (text == "consensus") {
        return MapperMode::kConsensus;
    }
    throw MakeInputError("", field, std::string(text),
                         "allowed: paper (Eq. 1-6) | kalman (Kalman fusion of the lowest point) "
                         "| consensus (Eq. 1-5, the mean of a cell whose heights agree)");
}

std::string_view ToString(MapperMode mode) {
    switch (mode) {
        case MapperMode::kKalman:
            return "kalman";
        case MapperMode::kConsensus:
            return "consensus";
        case MapperMode::kPaper:
            break;
    }
    return "paper";
}

Prefilter ParsePrefilter(std::string_view text, const std::string& field) {
    if (text == "none") {
        return Prefilter::kNone;
    }
    if (text == "shadow") {
        return Prefilter::kShadow;
    }
    if (text == "range_jump") {
        return Prefilter::kRangeJump;
    }
    if (text == "sweep_jump") {
        return Prefilter::kSweepJump;
    }
    throw MakeInputError("", field, std::string(text),
                         "allowed: none | shadow | range_jump | sweep_jump");
}

std::string_view ToString(Prefilter prefilter) {
    switch (prefilter) {
        case Prefilter::kShadow:
            return "shadow";
        case Prefilter::kRangeJump:
            return "range_jump";
        case Prefilter::kSweepJump:
            return "sweep_jump";
        case Prefilter::kNone:
            break;
    }
    return "none";
}

void MapSettings::Validate() const {
    const core::Check check;
    check.That(a >= 1, "a", a, "allowed: integer >= 1");
    check.NonNegative("delta_l_m", delta_l_m, "allowed: finite number >= 0");
    shadow.Validate();
    range_jump.Validate();
    sweep_jump.Validate();
    kalman.Validate();
    consensus.Validate();
}

namespace {

/// The mapping-stage parameters of `settings` in a FilterParams (the rest at defaults).
mapper::FilterParams StageParamsOf(const MapSettings& settings) {
    mapper::FilterParams params;
    params.shadow = settings.shadow;
    params.range_jump = settings.range_jump;
    params.sweep_jump = settings.sweep_jump;
    params.kalman = settings.kalman;
    params.consensus = settings.consensus;
    return params;
}

}  // namespace

void SetStageParams(MapSettings& settings, const mapper::FilterParams& params) {
    settings.shadow = params.shadow;
    settings.range_jump = params.range_jump;
    settings.sweep_jump = params.sweep_jump;
    settings.kalman = params.kalman;
    settings.consensus = params.consensus;
}

bool IsStageParameter(std::string_view name) {
    return name.starts_with("shadow.") || name.starts_with("range_jump.") ||
           name.starts_with("sweep_jump.") || name.starts_with("kalman.") ||
           name.starts_with("consensus.");
}

bool RunsStage(MapperMode mode, Prefilter prefilter, std::string_view stage) {
    if (stage == "kalman") {
        return mode == MapperMode::kKalman;
    }
    if (stage == "consensus") {
        return mode == MapperMode::kConsensus;
    }
    return prefilter != Prefilter::kNone && stage == ToString(prefilter);
}

void ApplyStageSettings(MapSettings& settings,
                        const std::vector<std::string>& assignments,
                        const std::string& field) {
    mapper::FilterParams params = StageParamsOf(settings);
    for (const std::string& a : assignments) {
        const std::size_t eq = a.find('=');
        if (eq == std::string::npos || eq == 0) {
            throw MakeInputError("", field, a, "expected NAME=VALUE");
        }
        const std::string name = a.substr(0, eq);
        if (!IsStageParameter(name)) {
            throw MakeInputError("", field, a,
                                 "not a mapping-stage parameter; allowed: shadow.<field>, "
                                 "range_jump.<field>, sweep_jump.<field>, kalman.<field>, "
                                 "consensus.<field> (map filters' parameters belong to casmap "
                                 "filter / bench)");
        }
        if (!RunsStage(settings.mode, settings.prefilter, name.substr(0, name.find('.')))) {
            const bool kalman = name.starts_with("kalman.");
            const bool mode = kalman || name.starts_with("consensus.");
            throw MakeInputError("", field, a,
                                 mode ? std::string(kalman ? "the Kalman" : "the consensus") +
                                            " mapper's parameter, but the mapper mode is " +
                                            std::string(ToString(settings.mode))
                                      : "a pre-filter's parameter, but the pre-filter is " +
                                            std::string(ToString(settings.prefilter)));
        }
        params.Set(name, a.substr(eq + 1));
    }
    SetStageParams(settings, params);
    settings.Validate();
}

std::vector<std::uint8_t> PrefilterLabels(const core::Scan& scan, const MapSettings& settings) {
    switch (settings.prefilter) {
        case Prefilter::kShadow:
            return mapper::ShadowFilterLabels(scan, settings.shadow);
        case Prefilter::kRangeJump:
            return mapper::RangeJumpLabels(scan, settings.range_jump);
        case Prefilter::kSweepJump:
            throw MakeInputError("", "prefilter", "sweep_jump",
                                 "compares each scan with its neighbours; label whole runs "
                                 "(PrefilterRunLabels)");
        case Prefilter::kNone:
            break;
    }
    return {};
}

std::vector<std::vector<std::uint8_t>> PrefilterRunLabels(const std::vector<core::Scan>& scans,
                                                          const core::Trajectory& world_T_sensor,
                                                          const MapSettings& settings) {
    if (settings.prefilter == Prefilter::kSweepJump) {
        return mapper::SweepJumpLabels(scans, world_T_sensor, settings.sweep_jump);
    }
    std::vector<std::vector<std::uint8_t>> labels(scans.size());
    if (settings.prefilter != Prefilter::kNone) {
        for (std::size_t k = 0; k < scans.size(); ++k) {
            labels[k] = PrefilterLabels(scans[k], settings);
        }
    }
    return labels;
}

namespace {

// Every scan into `mapper` with its pre-filter labels (empty for kNone: keep all).
template <typename Mapper>
void AddScans(Mapper& mapper,
              const std::vector<core::Scan>& scans,
              const core::Trajectory& world_T_sensor,
              const MapSettings& settings) {
    const std::vector<std::vector<std::uint8_t>> keep =
        PrefilterRunLabels(scans, world_T_sensor, settings);
    for (std::size_t k = 0; k < scans.size(); ++k) {
        mapper.AddScan(scans[k], world_T_sensor, keep[k]);
    }
}

}  // namespace

MappedRun MapScans(const std::vector<core::Scan>& scans,
                   const core::Trajectory& world_T_sensor,
                   const core::GridGeometry& grid,
                   const MapSettings& settings) {
    settings.Validate();
    mapper::TerrainMapperConfig config;
    config.grid = grid;
    config.a = settings.a;
    config.delta_l_m = settings.delta_l_m;
    config.scan_period_s = ScanPeriod(scans);
    config.unknown = settings.unknown;
    if (settings.mode == MapperMode::kKalman) {
        mapper::KalmanMapperConfig kalman;
        static_cast<mapper::KalmanNoiseConfig&>(kalman) = settings.kalman;
        kalman.grid = grid;
        kalman.a = settings.a;
        kalman.scan_period_s = config.scan_period_s;
        kalman.unknown = settings.unknown;
        mapper::KalmanMapper mapper(kalman);
        AddScans(mapper, scans, world_T_sensor, settings);
        return MappedRun{mapper.elevation(), mapper.certainty(), mapper.stats(), config, settings};
    }
    if (settings.mode == MapperMode::kConsensus) {
        config.consensus = settings.consensus;
    }
    mapper::TerrainMapper mapper(config);
    AddScans(mapper, scans, world_T_sensor, settings);
    return MappedRun{mapper.elevation(), mapper.certainty(), mapper.stats(), config, settings};
}

core::GridGeometry GridCoveringBeams(const std::vector<core::Scan>& scans,
                                     const core::Trajectory& world_T_sensor,
                                     double cell_m,
                                     const std::string& where) {
    if (!(cell_m > 0.0) || !std::isfinite(cell_m)) {  // else "x0_m/y0_m must be finite" later
        throw MakeInputError(where, "cell_m", FormatNumber(cell_m), "must be a finite number > 0");
    }
    double x_lo = std::numeric_limits<double>::infinity();
    double y_lo = x_lo;
    double x_hi = -x_lo;
    double y_hi = -x_lo;
    for (const core::Scan& scan : scans) {
        for (std::size_t i = 0; i < scan.beams.size(); ++i) {
            if (scan.beams[i].status != core::BeamStatus::kOk) {
                continue;
            }
            const std::optional<core::Pose> pose = world_T_sensor.PoseAt(scan.BeamTime(i));
            if (!pose) {
                continue;
            }
            const Eigen::Vector3d p =
                mapper::BeamToWorld(*pose, scan.BeamAngle(i), scan.beams[i].range_m);
            x_lo = std::min(x_lo, p.x());
            x_hi = std::max(x_hi, p.x());
            y_lo = std::min(y_lo, p.y());
            y_hi = std::max(y_hi, p.y());
        }
    }
    if (!(x_lo <= x_hi)) {
        throw MakeInputError(where, "scans", "",
                             "no valid beam has a pose, so there is nothing to map");
    }
    core::GridGeometry grid;
    grid.cell_m = cell_m;
    grid.x0_m = std::floor(x_lo / cell_m) * cell_m;
    grid.y0_m = std::floor(y_lo / cell_m) * cell_m;
    const double rows = std::floor((x_hi - grid.x0_m) / cell_m) + 1.0;
    const double cols = std::floor((y_hi - grid.y0_m) / cell_m) + 1.0;
    constexpr double kMaxCells = 4000.0;
    if (rows > kMaxCells || cols > kMaxCells) {
        throw MakeInputError(
            where, "scans", FormatNumber(rows) + " x " + FormatNumber(cols) + " cells",
            "the beams span more than 4000 x 4000 cells; give the grid explicitly");
    }
    grid.rows = static_cast<int>(rows);
    grid.cols = static_cast<int>(cols);
    return grid;
}

core::GridGeometry ParseGrid(const std::string& text, const std::string& field) {
    const std::string rule = "expected X0,Y0,CELL_M,ROWS,COLS with CELL_M > 0, ROWS, COLS > 0";
    const std::optional<std::vector<double>> parsed = core::ParseNumberList(text, 5);
    if (!parsed) {
        throw MakeInputError("", field, text, rule);
    }
    const std::vector<double>& v = *parsed;
    if (!(v[2] > 0.0) || v[3] < 1.0 || v[4] < 1.0 || v[3] != std::floor(v[3]) ||
        v[4] != std::floor(v[4]) || v[3] > 1e5 || v[4] > 1e5) {
        throw MakeInputError("", field, text, rule);
    }
    return core::GridGeometry{v[0], v[1], v[2], static_cast<int>(v[3]), static_cast<int>(v[4])};
}

core::Raster<std::uint8_t> UnknownMask(const core::MapF& certainty) {
    core::Raster<std::uint8_t> mask(certainty.rows, certainty.cols, 0);
    for (std::size_t i = 0; i < certainty.data.size(); ++i) {
        mask.data[i] = certainty.data[i] == 0.0F ? 1 : 0;
    }
    return mask;
}

void WriteMapFiles(const std::filesystem::path& dir,
                   const std::string& stem,
                   const core::MapF& map,
                   const std::string& title,
                   const std::string& unit,
                   const core::Raster<std::uint8_t>* unknown) {
    io::WriteMapTiff(dir / (stem + ".tiff"), map);
    io::PngStyle style;
    style.title = title;
    style.unit = unit;
    style.unknown = unknown;
    io::WriteMapPng(dir / (stem + ".png"), map, style);
}

std::string GridYaml(const core::GridGeometry& grid) {
    YAML::Emitter out;
    io::EmitGrid(out, grid);
    return out.c_str();
}

std::string MapConfigYaml(const std::string& run_path,
                          std::optional<std::uint64_t> seed,
                          const MappedRun& mapped) {
    const mapper::MapperStats& s = mapped.stats;
    YAML::Emitter out;
    out << YAML::Comment("casmap map: the settings that produced the maps in this directory");
    out << YAML::BeginMap;
    out << YAML::Key << "run" << YAML::Value << run_path;
    out << YAML::Key << "seed" << YAML::Value;
    if (seed) {
        out << *seed;
    } else {
        io::EmitNull(out);
    }
    out << YAML::Key << "grid" << YAML::Value;
    io::EmitGrid(out, mapped.config.grid);
    out << YAML::Key << "mapper" << YAML::Value << YAML::Flow << YAML::BeginMap;
    out << YAML::Key << "mode" << YAML::Value << std::string(ToString(mapped.settings.mode));
    out << YAML::Key << "unknown" << YAML::Value
        << std::string(mapper::ToString(mapped.settings.unknown));
    out << YAML::Key << "prefilter" << YAML::Value
        << std::string(ToString(mapped.settings.prefilter));
    out << YAML::Key << "a" << YAML::Value << mapped.config.a;
    io::EmitNumber(out, "delta_l_m", mapped.config.delta_l_m);
    io::EmitNumber(out, "scan_period_s", mapped.config.scan_period_s);
    const MapSettings& st = mapped.settings;
    for (const mapper::StageSection& section : mapper::StageSections(StageParamsOf(st))) {
        if (RunsStage(st.mode, st.prefilter, section.stage)) {
            detail::EmitStageSection(out, section);
        }
    }
    out << YAML::EndMap;
    out << YAML::Key << "stats" << YAML::Value << YAML::Flow << YAML::BeginMap;
    out << YAML::Key << "beams_seen" << YAML::Value << s.beams_seen;
    out << YAML::Key << "beams_not_ok" << YAML::Value << s.beams_not_ok;
    out << YAML::Key << "beams_no_pose" << YAML::Value << s.beams_no_pose;
    out << YAML::Key << "beams_outside" << YAML::Value << s.beams_outside;
    out << YAML::Key << "beams_rejected" << YAML::Value << s.beams_rejected;
    out << YAML::Key << "beams_mapped" << YAML::Value << s.beams_mapped;
    out << YAML::EndMap << YAML::EndMap;
    return io::EmittedText(out);
}

}  // namespace casmap::pipeline
