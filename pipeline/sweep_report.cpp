// What `RunSweep` reports: sweep.json, the terminal table, the heat map and the per-run
// configurations (sweep.hpp).
#include <chrono>
#include <cmath>
#include <cstdio>

#include "casmap/io/atomic_file.hpp"
#include "casmap/pipeline/bench_runner.hpp"
#include "casmap/pipeline/map_run.hpp"
#include "casmap/pipeline/sweep.hpp"

namespace casmap::pipeline {
namespace {
namespace fs = std::filesystem;

std::string SweepJsonWithElapsed(const SweepResult& result, double elapsed_s) {
    const SweepOptions& opt = result.options;
    std::string j = "{\"parameters\": [";
    for (std::size_t i = 0; i < opt.axes.size(); ++i) {
        j += (i ? ", " : "") + JsonString(opt.axes[i].name);
    }
    j += "], \"fixed\": [";
    for (std::size_t i = 0; i < opt.fixed.size(); ++i) {
        j += (i ? ", " : "") + JsonString(opt.fixed[i]);
    }
    j += "], \"courses\": [";
    for (std::size_t i = 0; i < opt.courses.size(); ++i) {
        j += (i ? ", " : "") + std::to_string(opt.courses[i]);
    }
    j += "], \"tests\": [";
    const std::vector<std::string> tests = SortedTests(opt.tests);
    for (std::size_t i = 0; i < tests.size(); ++i) {
        j += (i ? ", " : "") + JsonString(tests[i]);
    }
    j += "], \"seed\": " + std::to_string(opt.seed) + ",\n \"points\": [";
    for (std::size_t p = 0; p < result.points.size(); ++p) {
        const SweepPoint& pt = result.points[p];
        j += p ? ",\n  " : "\n  ";
        j += "{\"params\": {";
        for (std::size_t i = 0; i < opt.axes.size(); ++i) {
            j += (i ? ", " : "") + JsonString(opt.axes[i].name) + ": " + JsonNumber(pt.values[i]);
        }
        j += "}, \"pi_mean\": " + JsonNumber(pt.pi.mean) +
             ", \"pi_std\": " + JsonNumber(pt.pi.std) + ", \"pi_min\": " + JsonNumber(pt.pi.min) +
             ", \"pi_max\": " + JsonNumber(pt.pi.max) +
             ", \"runs\": " + std::to_string(pt.pi.runs) +
             ", \"cas_classes_pct_mean\": {\"mixed\": " + JsonNumber(pt.mixed_pct) +
             ", \"missing\": " + JsonNumber(pt.missing_pct) +
             ", \"untouched\": " + JsonNumber(pt.untouched_pct) + "}}";
    }
    j += "\n], \"best_point\": " + std::to_string(result.best) +
         ", \"elapsed_s\": " + JsonNumber(elapsed_s) +
         ", \"threads\": " + std::to_string(result.threads) + "}\n";
    return j;
}

}  // namespace

std::string SweepJson(const SweepResult& result) {
    return SweepJsonWithElapsed(result, result.elapsed_s);
}

std::string SweepTable(const SweepResult& result) {
    std::string t;
    char buf[128];
    for (const SweepAxis& a : result.options.axes) {
        std::snprintf(buf, sizeof(buf), "%12s", a.name.c_str());
        t += buf;
    }
    t += "     pi_mean   pi_std   pi_min   pi_max  runs\n";
    for (std::size_t p = 0; p < result.points.size(); ++p) {
        const SweepPoint& pt = result.points[p];
        for (const double v : pt.values) {
            std::snprintf(buf, sizeof(buf), "%12s", FormatNumber(v).c_str());
            t += buf;
        }
        std::snprintf(buf, sizeof(buf), "    %8.4f %8.4f %8.4f %8.4f %5zu%s\n", pt.pi.mean,
                      pt.pi.std, pt.pi.min, pt.pi.max, pt.pi.runs,
                      p == result.best ? "  <- best" : "");
        t += buf;
    }
    return t;
}

std::string WriteSweepOutputs(const fs::path& dir, const SweepResult& result) {
    const auto start = std::chrono::steady_clock::now();
    io::EnsureDirectory(dir);
    io::EnsureDirectory(dir / "runs");
    for (std::size_t r = 0; r < result.run_names.size(); ++r) {
        io::WriteTextAtomically(dir / "runs" / (result.run_names[r] + ".yaml"),
                                result.run_configs[r]);
    }
    const double elapsed =
        result.elapsed_s +
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    std::string json = SweepJsonWithElapsed(result, elapsed);
    io::WriteTextAtomically(dir / "sweep.json", json);
    const SweepOptions& opt = result.options;
    if (opt.axes.size() == 2) {
        HeatMap h;
        h.title = "CAS mean PI (Eq. 11) over " + std::to_string(opt.courses.size()) +
                  " course(s) x " + std::to_string(opt.tests.size()) + " test(s); lower is better";
        h.x_name = opt.axes[0].name;
        h.y_name = opt.axes[1].name;
        h.x_values = opt.axes[0].values;
        h.y_values = opt.axes[1].values;
        const std::size_t nx = h.x_values.size();
        const std::size_t ny = h.y_values.size();
        h.values.assign(nx * ny, std::nan(""));
        for (std::size_t ix = 0; ix < nx; ++ix) {
            for (std::size_t iy = 0; iy < ny; ++iy) {
                h.values[iy * nx + ix] = result.points[ix * ny + iy].pi.mean;
            }
        }
        WriteHeatMap(dir / "heatmap.png", h);
    }
    return json;
}

}  // namespace casmap::pipeline
