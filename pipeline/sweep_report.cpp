// What `RunSweep` reports: sweep.json, the terminal table, the heat map and the per-run
// configurations (sweep.hpp).
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <map>
#include <nlohmann/json.hpp>

#include "casmap/io/atomic_file.hpp"
#include "casmap/io/output_set.hpp"
#include "casmap/pipeline/bench_runner.hpp"
#include "casmap/pipeline/distributed.hpp"
#include "casmap/pipeline/map_run.hpp"
#include "casmap/pipeline/sweep.hpp"

namespace casmap::pipeline {
namespace {
namespace fs = std::filesystem;
using Json = nlohmann::ordered_json;

Json Num(double v) { return std::isfinite(v) ? Json(v) : Json(nullptr); }

Json ParamsJson(const SweepOptions& opt, const std::vector<double>& values) {
    Json params = Json::object();
    for (std::size_t i = 0; i < opt.axes.size(); ++i) {
        params[opt.axes[i].name] = values[i];
    }
    return params;
}

Json PointJson(const SweepOptions& opt, const SweepPoint& pt) {
    return Json{{"params", ParamsJson(opt, pt.values)},
                {"pi_mean", Num(pt.pi.mean)},
                {"pi_std", Num(pt.pi.std)},
                {"pi_min", Num(pt.pi.min)},
                {"pi_max", Num(pt.pi.max)},
                {"runs", pt.pi.runs},
                {"cas_classes_pct_mean", Json{{"mixed", Num(pt.mixed_pct)},
                                              {"missing", Num(pt.missing_pct)},
                                              {"untouched", Num(pt.untouched_pct)}}},
                {"spikes_mean", Num(pt.spikes_mean)},
                {"spikes_total", pt.spikes_total},
                {"runs_all_poles_kept", pt.runs_all_poles_kept},
                {"poles", pt.poles},
                {"poles_kept", pt.poles_kept},
                {"keeps_every_pole", pt.KeepsEveryPole()}};
}

/// Held-out figures of one filter over some runs.
struct HeldSummary {
    std::vector<double> pi;
    std::size_t runs_all_poles_kept = 0;
    std::size_t poles = 0;
    std::size_t poles_kept = 0;
    std::int64_t spikes = 0;
    void Add(const HeldOutScore& s) {
        pi.push_back(s.pi);
        runs_all_poles_kept += s.poles_kept == s.poles ? 1 : 0;
        poles += s.poles;
        poles_kept += s.poles_kept;
        spikes += s.spikes;
    }
    [[nodiscard]] Json ToJson() const {
        const SweepStats st = Summarise(pi);
        return Json{{"pi_mean", Num(st.mean)},
                    {"pi_std", Num(st.std)},
                    {"runs", pi.size()},
                    {"runs_all_poles_kept", runs_all_poles_kept},
                    {"poles", poles},
                    {"poles_kept", poles_kept},
                    {"spikes_mean", Num(pi.empty() ? std::nan("")
                                                   : static_cast<double>(spikes) /
                                                         static_cast<double>(pi.size()))}};
    }
};

struct HeldGroup {
    HeldSummary chosen;
    HeldSummary paper;
    std::size_t chosen_lower_pi = 0;  // runs where the chosen point's PI < the paper's
    std::size_t runs = 0;
};

/// Per test (T, TR, TP, TRP order of the options) and "all".
std::vector<std::pair<std::string, HeldGroup>> HeldGroups(const SweepResult& result) {
    std::vector<std::pair<std::string, HeldGroup>> groups;
    for (const std::string& t : SortedTests(result.options.tests)) {
        groups.emplace_back(t, HeldGroup{});
    }
    groups.emplace_back("all", HeldGroup{});
    for (const HeldOutRun& run : result.held_out) {
        for (auto& [name, g] : groups) {
            if (name == run.test || name == "all") {
                g.chosen.Add(run.chosen);
                g.paper.Add(run.paper);
                g.chosen_lower_pi += run.chosen.pi < run.paper.pi ? 1 : 0;
                g.runs += 1;
            }
        }
    }
    return groups;
}

Json HeldOutJson(const SweepResult& result) {
    const SweepOptions& opt = result.options;
    Json by_test = Json::object();
    for (const auto& [name, g] : HeldGroups(result)) {
        by_test[name] = Json{{"chosen", g.chosen.ToJson()},
                             {"paper", g.paper.ToJson()},
                             {"runs_chosen_lower_pi", g.chosen_lower_pi}};
    }
    Json runs = Json::array();
    for (const HeldOutRun& r : result.held_out) {
        const auto score = [](const HeldOutScore& s) {
            return Json{{"pi", Num(s.pi)},
                        {"spikes", s.spikes},
                        {"poles", s.poles},
                        {"poles_kept", s.poles_kept}};
        };
        runs.push_back(Json{{"name", r.name},
                            {"seed", r.seed},
                            {"course", r.course},
                            {"test", r.test},
                            {"chosen", score(r.chosen)},
                            {"paper", score(r.paper)}});
    }
    return Json{{"seeds", opt.test_seeds.empty() ? opt.TrainSeeds() : opt.test_seeds},
                {"courses", opt.test_courses.empty() ? opt.courses : opt.test_courses},
                {"chosen_params", ParamsJson(opt, result.points[result.best].values)},
                {"paper", "cas at the paper's defaults (no --set/--fix), same runs"},
                {"by_test", by_test},
                {"runs", runs}};
}

/// sweep.json: a header line, one point per line, the summary (NaN written as null).
std::string SweepJsonWithElapsed(const SweepResult& result, double elapsed_s) {
    const SweepOptions& opt = result.options;
    Json names = Json::array();
    for (const SweepAxis& axis : opt.axes) {
        names.push_back(axis.name);
    }
    const Json head{{"parameters", names},
                    {"filter", opt.filter},
                    {"fixed", opt.fixed},
                    {"courses", opt.courses},
                    {"tests", SortedTests(opt.tests)},
                    {"seed", opt.TrainSeeds().front()},
                    {"seeds", opt.TrainSeeds()},
                    {"grow", opt.grow},
                    {"search", opt.search}};
    std::string j = head.dump();
    j.pop_back();  // the closing brace: the points follow
    j += ",\n \"points\": [";
    for (std::size_t p = 0; p < result.points.size(); ++p) {
        j += (p ? ",\n  " : "\n  ") + PointJson(opt, result.points[p]).dump();
    }
    Json growth = Json::array();
    for (const SweepGrowth& g : result.growth) {
        growth.push_back(Json{{"round", g.round},
                              {"axis", g.axis},
                              {"added", g.added},
                              {"best_before", ParamsJson(opt, g.best_before)}});
    }
    Json path = Json::array();
    for (const SweepStep& st : result.path) {
        path.push_back(Json{{"pass", st.pass},
                            {"axis", st.axis},
                            {"best", ParamsJson(opt, st.best)},
                            {"scored", st.scored}});
    }
    Json tail{{"best_point", result.best},
              {"best_params", ParamsJson(opt, result.points[result.best].values)},
              {"best_keeps_every_pole", result.best_keeps_every_pole},
              {"best_rule", result.best_rule},
              {"pareto_front", result.pareto},
              {"growth", growth},
              {"path", path}};
    if (!result.held_out.empty()) {
        tail["held_out"] = HeldOutJson(result);
    }
    std::string t = tail.dump();
    t.pop_back();
    j += "\n], " + t.substr(1) + ", \"elapsed_s\": " + JsonNumber(elapsed_s) +
         ", \"threads\": " + std::to_string(result.threads) + "}\n";
    return j;
}

}  // namespace

std::string SweepJson(const SweepResult& result) {
    return SweepJsonWithElapsed(result, result.elapsed_s);
}

std::string SweepTable(const SweepResult& result) {
    const SweepOptions& opt = result.options;
    std::string t = "filter " + opt.filter +
                    "; training runs: " + std::to_string(result.run_names.size()) + "\n";
    char buf[160];
    for (const SweepAxis& a : opt.axes) {
        std::snprintf(buf, sizeof(buf), "%12s", a.name.c_str());
        t += buf;
    }
    t += "     pi_mean   pi_std   pi_min   pi_max  runs  spikes  poles kept\n";
    for (std::size_t p = 0; p < result.points.size(); ++p) {
        const SweepPoint& pt = result.points[p];
        for (const double v : pt.values) {
            std::snprintf(buf, sizeof(buf), "%12s", FormatNumber(v).c_str());
            t += buf;
        }
        std::snprintf(buf, sizeof(buf), "    %8.4f %8.4f %8.4f %8.4f %5zu %7.1f %5zu/%-5zu%s%s\n",
                      pt.pi.mean, pt.pi.std, pt.pi.min, pt.pi.max, pt.pi.runs, pt.spikes_mean,
                      pt.poles_kept, pt.poles, pt.KeepsEveryPole() ? " all" : "    ",
                      p == result.best ? "  <- best" : "");
        t += buf;
    }
    t += "best: " + result.best_rule + "\n";
    for (const SweepGrowth& g : result.growth) {
        t += "grew (round " + std::to_string(g.round) + "): " + g.axis +
             " += " + FormatNumber(g.added.front()) + "\n";
    }
    for (const SweepStep& st : result.path) {
        t += "descent pass " + std::to_string(st.pass) + ", " + st.axis + ": best";
        for (std::size_t i = 0; i < st.best.size(); ++i) {
            t += " " + opt.axes[i].name + "=" + FormatNumber(st.best[i]);
        }
        t += " (" + std::to_string(st.scored) + " points scored)\n";
    }
    if (!result.held_out.empty()) {
        t += "held-out runs (" + std::to_string(result.held_out.size()) +
             "): chosen point vs paper CAS\n";
        t += "  test   pi chosen  pi paper  runs all poles kept (chosen, paper)  spikes (chosen, "
             "paper)  runs chosen PI lower\n";
        for (const auto& [name, g] : HeldGroups(result)) {
            const SweepStats c = Summarise(g.chosen.pi);
            const SweepStats p = Summarise(g.paper.pi);
            const double n = std::max(1.0, static_cast<double>(g.runs));
            std::snprintf(buf, sizeof(buf),
                          "  %-5s %9.4f %9.4f  %5zu, %5zu of %-5zu %14.1f, %-8.1f %8zu of %zu\n",
                          name.c_str(), c.mean, p.mean, g.chosen.runs_all_poles_kept,
                          g.paper.runs_all_poles_kept, g.runs,
                          static_cast<double>(g.chosen.spikes) / n,
                          static_cast<double>(g.paper.spikes) / n, g.chosen_lower_pi, g.runs);
            t += buf;
        }
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
        h.title = opt.filter + " mean PI (Eq. 11) over " + std::to_string(result.run_names.size()) +
                  " training run(s); lower is better";
        h.x_name = opt.axes[0].name;
        h.y_name = opt.axes[1].name;
        h.x_values = opt.axes[0].values;
        h.y_values = opt.axes[1].values;
        const std::size_t nx = h.x_values.size();
        const std::size_t ny = h.y_values.size();
        h.values.assign(nx * ny, std::nan(""));
        h.marked.assign(nx * ny, false);
        for (std::size_t p = 0; p < result.points.size(); ++p) {  // descent: a subset
            const SweepPoint& pt = result.points[p];
            const auto ix = static_cast<std::size_t>(
                std::find(h.x_values.begin(), h.x_values.end(), pt.values[0]) - h.x_values.begin());
            const auto iy = static_cast<std::size_t>(
                std::find(h.y_values.begin(), h.y_values.end(), pt.values[1]) - h.y_values.begin());
            h.values[iy * nx + ix] = pt.pi.mean;
            h.marked[iy * nx + ix] = pt.KeepsEveryPole();
            if (p == result.best) {
                h.starred = static_cast<int>(iy * nx + ix);
            }
        }
        h.marked_legend = "red frame: every pole kept in every training run; * chosen point";
        WriteHeatMap(dir / "heatmap.png", h);
    }
    return json;
}

std::optional<SweepResult> RunSweepToFolder(SweepOptions options,
                                            const std::filesystem::path& out_dir,
                                            const std::string& json_copy,
                                            const core::ProgressFn& progress) {
    options.Validate();  // bad input fails before any work
    if (!json_copy.empty()) {
        io::CheckOutputPath(json_copy, "json");
    }
    const DistributedSession session;
    options.session = &session;
    if (session.rank() == 0) {
        io::EnsureDirectory(out_dir);
    }
    SweepResult result = RunSweep(options, progress);
    result.options.session = nullptr;  // the session ends here
    if (session.rank() != 0) {
        return std::nullopt;  // rank 0 writes every output
    }
    const std::string json = WriteSweepOutputs(out_dir, result);
    if (!json_copy.empty()) {
        io::WriteTextAtomically(json_copy, json);
    }
    return result;
}

}  // namespace casmap::pipeline
