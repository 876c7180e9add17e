// Scoring of benchmark runs: the named pipelines (bench_pipelines.hpp) and CAS alone (sweeps)
// against the exact ground truth over the paper's region.
#include <algorithm>
#include <cmath>
#include <map>
#include <memory>
#include <stdexcept>
#include <utility>
#include <variant>

#include "casmap/core/input_error.hpp"
#include "casmap/mapper/filters.hpp"
#include "casmap/mapper/metrics.hpp"
#include "casmap/mapper/stage_params.hpp"
#include "casmap/pipeline/bench_pipelines.hpp"
#include "casmap/pipeline/bench_runner.hpp"

namespace casmap::pipeline {
namespace {

/// RMSE against truth over the cells CAS filled inside `region` (NaN if none; NaN cells of
/// `map` are left out).
double FillError(const core::MapF& map,
                 const core::MapF& truth,
                 const mapper::ClassMap& cas_classes,
                 const mapper::Region& region) {
    double sum = 0.0;
    std::int64_t n = 0;
    for (int r = region.row0; r < region.row0 + region.rows; ++r) {
        for (int c = region.col0; c < region.col0 + region.cols; ++c) {
            if (cas_classes.at(r, c) == static_cast<std::uint8_t>(mapper::PixelClass::kFilled)) {
                const double d = static_cast<double>(map.at(r, c)) - truth.at(r, c);
                if (std::isnan(d)) {
                    continue;
                }
                sum += d * d;
                ++n;
            }
        }
    }
    return n > 0 ? std::sqrt(sum / static_cast<double>(n)) : std::nan("");
}

/// Poles of the scene (objects named pole<N>) with the cell holding their axis.
struct Pole {
    std::string name;
    int row = 0;
    int col = 0;
    double height_m = 0.0;
};

std::vector<Pole> Poles(const core::Scene& scene, const core::GridGeometry& grid) {
    std::vector<Pole> poles;
    for (const core::SceneObject& o : scene.objects) {
        const auto* cyl = std::get_if<core::CylinderShape>(&o.shape);
        if (cyl == nullptr || o.name.rfind("pole", 0) != 0) {
            continue;
        }
        const Eigen::Vector3d& p = o.world_T_object.translation;
        if (const std::optional<core::Cell> cell = grid.CellOf(p.x(), p.y())) {
            poles.push_back({o.name, cell->row, cell->col, p.z() + 0.5 * cyl->height_m});
        }
    }
    std::sort(poles.begin(), poles.end(),
              [](const Pole& a, const Pole& b) { return a.name < b.name; });
    return poles;
}

/// A map keeps a pole when it reaches half the pole's height within one cell of it.
bool Keeps(const core::MapF& map, const Pole& pole) {
    for (int r = std::max(0, pole.row - 1); r <= std::min(map.rows - 1, pole.row + 1); ++r) {
        for (int c = std::max(0, pole.col - 1); c <= std::min(map.cols - 1, pole.col + 1); ++c) {
            if (map.at(r, c) >= 0.5 * pole.height_m) {
                return true;
            }
        }
    }
    return false;
}

std::vector<std::string> KeptPoles(const core::MapF& map, const std::vector<Pole>& poles) {
    std::vector<std::string> kept;
    for (const Pole& p : poles) {
        if (Keeps(map, p)) {
            kept.push_back(p.name);
        }
    }
    return kept;
}

/// The mapping-stage parameters a pipeline's map depends on: the sections of the stages it
/// runs (mapper/stage_params.hpp; "" for the paper mapper without pre-filter). Two pipelines
/// with equal keys share one map; FormatNumber's texts are equal exactly when the numbers are.
std::string StageKey(const PipelineSpec& spec, const mapper::FilterParams& p) {
    std::string key;
    for (const mapper::StageSection& section : mapper::StageSections(p)) {
        if (!RunsStage(spec.mode, spec.prefilter, section.stage)) {
            continue;
        }
        key += section.stage;
        for (const mapper::StageParam& param : section.params) {
            key += " " + param.key + "=" + param.value;
        }
        key += ";";
    }
    return key;
}

}  // namespace

std::shared_ptr<const MappedRun> StageMaps::Find(const std::string& key) const {
    for (const auto& [k, map] : maps_) {
        if (k == key) {
            return map;
        }
    }
    return nullptr;
}

void StageMaps::Add(const std::string& key, std::shared_ptr<const MappedRun> map) {
    if (maps_.size() >= capacity_) {
        maps_.erase(maps_.begin());
    }
    maps_.emplace_back(key, std::move(map));
    ++made_;
}

BenchRun ScorePipelines(const MappedBenchRun& run,
                        const SimulatedRun* sim,
                        const Course& course,
                        const mapper::FilterParams& params,
                        const std::vector<std::string>& pipelines,
                        SheetMaps* sheet,
                        const std::map<std::string, mapper::FilterParams>& own,
                        StageMaps* stage_maps) {
    CheckPipelines(pipelines);
    const core::MapF& raw = run.mapped.elevation;
    const core::MapF& c = run.mapped.certainty;
    const mapper::Region region = mapper::PaperRegion(raw.rows, raw.cols);
    BenchRun out;
    out.course = run.course;
    out.test = run.test;
    out.seed = run.setup.seed;
    out.scans = static_cast<std::int64_t>(run.scans);
    out.unknown = std::string(mapper::ToString(run.mapped.settings.unknown));
    // The paper's CAS on the plain map: Table II classes and the cells whose fill error every
    // pipeline reports.
    const mapper::FilterResult cas = mapper::RunFilter(mapper::FilterMethod::kCas, raw, c, params);
    out.cas_classes = mapper::ClassPercentages(cas.classes, c);
    const std::vector<Pole> poles = Poles(course.scene, run.setup.grid);
    for (const Pole& p : poles) {
        out.poles.push_back(p.name);
    }
    out.poles_kept["raw"] = KeptPoles(raw, poles);
    const mapper::FilterMetrics raw_metrics =
        mapper::EvaluateFilter({raw, {}}, raw, course.truth, region);
    out.raw_rmse_m = raw_metrics.raw_rmse_m;
    out.raw_spikes = raw_metrics.raw_spikes;
    // Maps of the other mapper modes / pre-filters, each made once per stage parameters from
    // the same scans (a preset section may give one pipeline its own pre-filter settings).
    std::map<std::string, std::shared_ptr<const MappedRun>> maps;  // this call's, by key
    const auto params_of = [&](const std::string& name) -> const mapper::FilterParams& {
        const auto it = own.find(name);
        return it == own.end() ? params : it->second;
    };
    const auto key_of = [&](const PipelineSpec& spec) {
        std::string key = std::string(ToString(spec.mode)) + "/" +
                          std::string(ToString(spec.prefilter)) + "/" +
                          std::string(mapper::ToString(run.mapped.settings.unknown)) + "/";
        const double base[] = {static_cast<double>(run.mapped.config.a),
                               run.mapped.config.delta_l_m};
        key.append(reinterpret_cast<const char*>(base), sizeof base);
        return key + StageKey(spec, params_of(spec.name));
    };
    const auto is_plain = [&](const PipelineSpec& spec) {
        return spec.mode == run.mapped.settings.mode &&
               spec.prefilter == run.mapped.settings.prefilter && spec.mode == MapperMode::kPaper &&
               spec.prefilter == Prefilter::kNone;
    };
    for (const std::string& name : pipelines) {
        const PipelineSpec& spec = FindPipeline(name, "pipelines");
        const std::string key = key_of(spec);
        if (is_plain(spec) || maps.count(key) != 0) {
            continue;
        }
        if (stage_maps != nullptr) {
            if (std::shared_ptr<const MappedRun> kept = stage_maps->Find(key)) {
                maps.emplace(key, std::move(kept));
                continue;
            }
        }
        if (sim == nullptr) {
            throw MakeInputError("", "pipelines", name,
                                 "needs the run's scans (a mapper mode or scan pre-filter "
                                 "other than the run's map)");
        }
        MapSettings settings = run.mapped.settings;
        settings.a = run.mapped.config.a;
        settings.delta_l_m = run.mapped.config.delta_l_m;
        settings.mode = spec.mode;
        settings.prefilter = spec.prefilter;
        SetStageParams(settings, params_of(name));
        auto made = std::make_shared<const MappedRun>(
            MapScans(sim->run.scans, sim->run.poses, run.setup.grid, settings));
        if (stage_maps != nullptr) {
            stage_maps->Add(key, made);
        }
        maps.emplace(key, std::move(made));
    }
    for (const std::string& name : pipelines) {
        const PipelineSpec& spec = FindPipeline(name, "pipelines");
        const MappedRun& map = is_plain(spec) ? run.mapped : *maps.at(key_of(spec));
        const auto own_params = own.find(name);
        const bool shared = own_params == own.end();
        mapper::FilterResult result;
        if (!spec.filter) {
            result.elevation = map.elevation;
        } else if (&map == &run.mapped && *spec.filter == mapper::FilterMethod::kCas && shared) {
            result = cas;
        } else {
            result = mapper::RunFilter(*spec.filter, map.elevation, map.certainty,
                                       shared ? params : own_params->second);
        }
        const mapper::FilterMetrics m = mapper::EvaluateFilter(result, raw, course.truth, region);
        FilterScore& score = out.filters[name];
        score.pi = m.pi;
        score.rmse_m = m.rmse_m;
        score.spikes = m.spikes;
        score.fill_error_m = FillError(result.elevation, course.truth, cas.classes, region);
        score.cells = m.cells;
        score.coverage = m.coverage;
        score.edge_rmse_m = m.edge_rmse_m;
        score.open_rmse_m = m.open_rmse_m;
        out.poles_kept[name] = KeptPoles(result.elevation, poles);
        if (sheet != nullptr) {  // the Fig. 7 sheet draws the paper's five; --maps writes all
            sheet->filtered[name] = std::move(result.elevation);
        }
    }
    if (sheet != nullptr) {
        sheet->raw = raw;
        sheet->certainty = c;
        sheet->truth = course.truth;
        sheet->cas_classes = cas.classes;
    }
    return out;
}

BenchRun ScoreRun(const MappedBenchRun& run,
                  const Course& course,
                  const mapper::FilterParams& params,
                  SheetMaps* sheet) {
    return ScorePipelines(run, nullptr, course, params, PaperPipelineNames(), sheet);
}

CasScore ScoreCas(const MappedBenchRun& run,
                  const Course& course,
                  const mapper::FilterParams& params,
                  mapper::FilterMethod method) {
    const core::MapF& raw = run.mapped.elevation;
    const mapper::FilterResult cas = mapper::RunFilter(method, raw, run.mapped.certainty, params);
    const mapper::Region region = mapper::PaperRegion(raw.rows, raw.cols);
    const std::vector<Pole> poles = Poles(course.scene, run.setup.grid);
    CasScore score;
    score.pi = mapper::PerformanceIndex(cas.elevation, raw, course.truth, region);
    score.classes = mapper::ClassPercentages(cas.classes, run.mapped.certainty);
    score.spikes = mapper::CountSpikes(cas.elevation, course.truth, region);
    score.poles = poles.size();
    score.poles_kept = KeptPoles(cas.elevation, poles).size();
    return score;
}

}  // namespace casmap::pipeline
