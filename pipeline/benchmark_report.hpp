#pragma once

// What `casmap bench` and `casmap sweep` report: scores per run and filter, bench.json, the
// Fig. 8-style chart, the Table II-style table, the Fig. 7-style sheets, the terminal PI table
// and the sweep heat map. Formatting in benchmark_report.cpp, drawing in benchmark_charts.cpp; no
// simulation here.

#include <cstdint>
#include <filesystem>
#include <map>
#include <string>
#include <vector>

#include "casmap/core/grid.hpp"
#include "casmap/mapper/metrics.hpp"

namespace casmap::pipeline {

/// The paper's five filter names in the paper's order, as bench.json spells them (the PI
/// table, Fig. 8 chart and Fig. 7 sheets show these; other pipelines are in
/// PipelinesMarkdown).
[[nodiscard]] const std::vector<std::string>& BenchFilterNames();

/// The scores of one named pipeline (bench_pipelines.hpp) on one run. Eq. 11's denominator is
/// always the run's plain raw map (pipeline "raw"), so PIs of pipelines compare directly.
struct FilterScore {
    double pi = 0.0;            // Eq. 11 over the paper's 200 x 80 region (scored cells)
    double rmse_m = 0.0;        // filtered vs truth over the scored cells ("all")
    std::int64_t spikes = 0;    // surviving spikes (mapper::CountSpikes)
    double fill_error_m = 0.0;  // RMSE vs truth over the cells CAS filled (NaN: none)
    // Scored cells: region cells known in this map, the raw map and the truth (all of them
    // with 0-for-unknown maps); coverage = scored / raw-known cells.
    std::int64_t cells = 0;
    double coverage = 1.0;
    double edge_rmse_m = 0.0;  // on scored truth-edge cells (docs/paper-notes.md "Edge cells")
    double open_rmse_m = 0.0;  // on the other scored cells
};

/// One course x test of the benchmark.
struct BenchRun {
    int course = 0;
    std::string test;  // T, TR, TP, TRP
    std::uint64_t seed = 0;
    std::map<std::string, FilterScore> filters;  // keyed by BenchFilterNames()
    mapper::ClassReport cas_classes;
    double raw_rmse_m = 0.0;
    std::int64_t raw_spikes = 0;
    std::int64_t scans = 0;
    std::string scene;             // scene file of a --scenes run; empty on the paper's courses
    std::string unknown = "zero";  // the run's unknown-cell convention: zero | nan
    /// Poles of the course (scene objects named pole1..pole9) and, per map ("raw" and each
    /// filter), those it kept: the map reaches half the pole's height within one cell of it.
    std::vector<std::string> poles;
    std::map<std::string, std::vector<std::string>> poles_kept;
};

/// The maps of one run for a Fig. 7-style sheet (all the same size).
struct SheetMaps {
    core::MapF raw;
    core::MapF certainty;
    core::MapF truth;
    std::map<std::string, core::MapF> filtered;  // keyed by pipeline name (every pipeline scored)
    core::Raster<std::uint8_t> cas_classes;      // mapper::PixelClass per cell
};

/// "CAS", "Wiener", "Averaging", "Median", "CWM" for the names above; any other pipeline's
/// name unchanged.
[[nodiscard]] std::string FilterDisplayName(const std::string& name);

/// JSON number (shortest round-trip form) or null for NaN/inf.
[[nodiscard]] std::string JsonNumber(double value);
/// JSON string literal with escapes.
[[nodiscard]] std::string JsonString(const std::string& text);

/// bench.json in the shape issue 5 fixes ({"runs": [...], "elapsed_s": .., "threads": ..}).
[[nodiscard]] std::string BenchJson(const std::vector<BenchRun>& runs,
                                    double elapsed_s,
                                    int threads);

/// The PI table for the terminal: one line per run, one column per paper filter present,
/// best of those marked '*'.
[[nodiscard]] std::string PiTable(const std::vector<BenchRun>& runs);

/// Table II-style Markdown: per test, CAS's removed/filled/untouched shares per course, with
/// the paper's test-T figures beside ours.
[[nodiscard]] std::string TableTwoMarkdown(const std::vector<BenchRun>& runs);

/// Markdown: per pole (pole1 = 24 mm ... pole9 = 2.5 mm), in how many runs each filter kept it
/// out of the runs whose raw map showed it.
[[nodiscard]] std::string PolesMarkdown(const std::vector<BenchRun>& runs);

/// Per-pipeline summary (Markdown): per test (or scene run), one row per pipeline present:
/// mean PI, runs where it has the lowest PI of the pipelines present, mean RMSE on edge /
/// open / all scored cells (mm), mean spikes, poles kept / poles, mean coverage.
[[nodiscard]] std::string PipelinesMarkdown(const std::vector<BenchRun>& runs);

/// A run's display name: "course04_T" or "<SceneRunStem>_<motion>".
[[nodiscard]] std::string BenchRunName(const BenchRun& run);
/// The file stem of a scene ("outdoor"), or "<folder>_scene" for a `casmap dataset` sample's
/// NNNNNN/scene.yaml.
[[nodiscard]] std::string SceneRunStem(const std::string& scene_path);

/// Fig. 8-style chart: PI per course per filter, one panel per test present in `runs`.
void WritePiChart(const std::filesystem::path& path, const std::vector<BenchRun>& runs);

/// Fig. 7-style sheet: raw map, ground truth and the five filtered maps side by side on one
/// colour scale, with a legend.
void WriteSheet(const std::filesystem::path& path, const SheetMaps& maps, const std::string& title);

/// Heat map of `values` (rows = y parameter values, cols = x parameter values), NaN drawn
/// grey, each cell labelled with its value.
struct HeatMap {
    std::string title;
    std::string x_name;
    std::string y_name;
    std::vector<double> x_values;
    std::vector<double> y_values;
    std::vector<double> values;  // y-major: values[iy * x_values.size() + ix]
    std::vector<bool> marked;    // empty or as `values`: cells drawn with a thick frame
    std::string marked_legend;   // what a frame means (shown under the map)
    int starred = -1;            // index into `values` of a cell marked with "*", or -1
};
void WriteHeatMap(const std::filesystem::path& path, const HeatMap& map);

}  // namespace casmap::pipeline
