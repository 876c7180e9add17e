// What `RunSweep` reports: sweep.json, the terminal table, the heat map and the per-run
// configurations (sweep.hpp).
#include <chrono>
#include <cmath>
#include <cstdio>
#include <nlohmann/json.hpp>

#include "casmap/io/atomic_file.hpp"
#include "casmap/pipeline/bench_runner.hpp"
#include "casmap/pipeline/map_run.hpp"
#include "casmap/pipeline/sweep.hpp"

namespace casmap::pipeline {
namespace {
namespace fs = std::filesystem;
using Json = nlohmann::ordered_json;

Json PointJson(const SweepOptions& opt, const SweepPoint& pt) {
    Json params = Json::object();
    for (std::size_t i = 0; i < opt.axes.size(); ++i) {
        params[opt.axes[i].name] = pt.values[i];
    }
    return Json{{"params", params},
                {"pi_mean", pt.pi.mean},
                {"pi_std", pt.pi.std},
                {"pi_min", pt.pi.min},
                {"pi_max", pt.pi.max},
                {"runs", pt.pi.runs},
                {"cas_classes_pct_mean", Json{{"mixed", pt.mixed_pct},
                                              {"missing", pt.missing_pct},
                                              {"untouched", pt.untouched_pct}}},
                {"spikes_mean", pt.spikes_mean},
                {"runs_all_poles_kept", pt.runs_all_poles_kept}};
}

/// sweep.json: a header line, one point per line, the summary (NaN written as null).
std::string SweepJsonWithElapsed(const SweepResult& result, double elapsed_s) {
    const SweepOptions& opt = result.options;
    Json names = Json::array();
    for (const SweepAxis& axis : opt.axes) {
        names.push_back(axis.name);
    }
    const Json head{{"parameters", names},
                    {"fixed", opt.fixed},
                    {"courses", opt.courses},
                    {"tests", SortedTests(opt.tests)},
                    {"seed", opt.seed}};
    std::string j = head.dump();
    j.pop_back();  // the closing brace: the points follow
    j += ",\n \"points\": [";
    for (std::size_t p = 0; p < result.points.size(); ++p) {
        j += (p ? ",\n  " : "\n  ") + PointJson(opt, result.points[p]).dump();
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
