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

/// Filter names in the paper's order, as bench.json spells them.
[[nodiscard]] const std::vector<std::string>& BenchFilterNames();

struct FilterScore {
    double pi = 0.0;            // Eq. 11 over the paper's 200 x 80 region
    double rmse_m = 0.0;        // filtered vs truth over the region
    std::int64_t spikes = 0;    // surviving spikes (mapper::CountSpikes)
    double fill_error_m = 0.0;  // RMSE vs truth over the cells CAS filled (NaN: none)
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
    std::map<std::string, core::MapF> filtered;  // keyed by BenchFilterNames()
    core::Raster<std::uint8_t> cas_classes;      // mapper::PixelClass per cell
};

/// "CAS", "Wiener", "Averaging", "Median", "CWM" for the names above.
[[nodiscard]] std::string FilterDisplayName(const std::string& name);

/// JSON number (shortest round-trip form) or null for NaN/inf.
[[nodiscard]] std::string JsonNumber(double value);
/// JSON string literal with escapes.
[[nodiscard]] std::string JsonString(const std::string& text);

/// bench.json in the shape issue 5 fixes ({"runs": [...], "elapsed_s": .., "threads": ..}).
[[nodiscard]] std::string BenchJson(const std::vector<BenchRun>& runs,
                                    double elapsed_s,
                                    int threads);

/// The PI table for the terminal: one line per run, one column per filter, best marked '*'.
[[nodiscard]] std::string PiTable(const std::vector<BenchRun>& runs);

/// Table II-style Markdown: per test, CAS's removed/filled/untouched shares per course, with
/// the paper's test-T figures beside ours.
[[nodiscard]] std::string TableTwoMarkdown(const std::vector<BenchRun>& runs);

/// Markdown: per pole (pole1 = 24 mm ... pole9 = 2.5 mm), in how many runs each filter kept it
/// out of the runs whose raw map showed it.
[[nodiscard]] std::string PolesMarkdown(const std::vector<BenchRun>& runs);

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
