#include "casmap/pipeline/benchmark_report.hpp"

#include <algorithm>
#include <array>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <nlohmann/json.hpp>
#include <set>

#include "casmap/pipeline/bench_pipelines.hpp"

namespace casmap::pipeline {
namespace {

// Key order as written (nlohmann's ordered_json): bench.json keeps its documented order.
using Json = nlohmann::ordered_json;

// Table II of the paper (benchmark test T), courses 1-16: mixed, missing, untouched (%).
constexpr std::array<double, 16> kPaperMixed = {17.8, 16.7, 17.6, 15.0, 15.9, 16.7, 16.2, 17.5,
                                                17.5, 16.8, 16.0, 13.4, 16.1, 12.1, 11.4, 13.4};
constexpr std::array<double, 16> kPaperMissing = {5.6, 6.0, 7.6, 6.4, 6.4, 6.5, 6.2, 6.4,
                                                  6.5, 6.2, 6.5, 4.9, 4.4, 4.5, 4.5, 4.2};
constexpr std::array<double, 16> kPaperUntouched = {76.6, 77.3, 74.8, 78.6, 77.7, 76.8, 77.6, 76.1,
                                                    76.0, 77.0, 77.5, 81.7, 79.5, 83.4, 84.1, 82.4};

std::string Fixed(double v, int decimals) {
    if (!std::isfinite(v)) {
        return "-";
    }
    char buf[64];
    std::snprintf(buf, sizeof(buf), "%.*f", decimals, v);
    return buf;
}

/// OpenCV's viridis colour map at u in [0, 1] (a 256-entry table built once).
}  // namespace

std::string FilterDisplayName(const std::string& name) {
    if (name == "cas") return "CAS";
    if (name == "wiener") return "Wiener";
    if (name == "average") return "Averaging";
    if (name == "median") return "Median";
    if (name == "cwm") return "CWM";
    return name;  // other pipelines go by their registry name
}

const std::vector<std::string>& BenchFilterNames() {
    static const std::vector<std::string> names = {"cas", "wiener", "average", "median", "cwm"};
    return names;
}

std::string JsonNumber(double value) {
    return Json(std::isfinite(value) ? Json(value) : Json(nullptr)).dump();
}

std::string JsonString(const std::string& text) { return Json(text).dump(); }

namespace {
/// A double, or null for NaN/inf (nlohmann writes non-finite numbers as null too; explicit
/// here so the intent is visible).
Json Num(double v) { return std::isfinite(v) ? Json(v) : Json(nullptr); }

Json ScoreJson(const FilterScore& f, const BenchRun& r, const std::string& name) {
    const auto kept = r.poles_kept.find(name);
    const std::size_t poles_kept = kept == r.poles_kept.end() ? 0 : kept->second.size();
    return Json{{"pi", f.pi},
                {"rmse_m", f.rmse_m},
                {"spikes", f.spikes},
                {"fill_error_m", f.fill_error_m},
                {"coverage", Num(f.coverage)},
                {"cells", f.cells},
                {"rmse_edge_m", Num(f.edge_rmse_m)},
                {"rmse_open_m", Num(f.open_rmse_m)},
                {"poles_kept", poles_kept},
                {"poles", r.poles.size()}};
}

Json SharesJson(const mapper::ClassShares& s) {
    return Json{
        {"mixed", s.removed_pct}, {"missing", s.filled_pct}, {"untouched", s.untouched_pct}};
}

/// One run of bench.json (issue 5's shape; NaN is written as null).
Json RunJson(const BenchRun& r) {
    Json filters = Json::object();
    std::vector<std::string> pipelines;
    for (const auto& [name, score] : r.filters) {
        pipelines.push_back(name);
    }
    for (const std::string& name : InPipelineOrder(pipelines)) {
        filters[name] = ScoreJson(r.filters.at(name), r, name);
    }
    Json observed = SharesJson(r.cas_classes.observed);
    observed["cells"] = r.cas_classes.observed.cells;
    Json kept = Json::object();
    for (const auto& [map, names] : r.poles_kept) {
        kept[map] = names;
    }
    Json run{{"course", r.course}, {"test", r.test}};
    if (!r.scene.empty()) {
        run["scene"] = r.scene;
    }
    run.update(Json{{"seed", r.seed},
                    {"scans", r.scans},
                    {"unknown", r.unknown},
                    {"filters", filters},
                    {"cas_classes_pct", SharesJson(r.cas_classes.all)},
                    {"cas_processed_cells", r.cas_classes.all.cells},
                    {"cas_classes_observed_pct", observed},
                    {"raw", Json{{"rmse_m", r.raw_rmse_m}, {"spikes", r.raw_spikes}}},
                    {"poles", r.poles},
                    {"poles_kept", kept}});
    return run;
}
}  // namespace

std::string BenchJson(const std::vector<BenchRun>& runs, double elapsed_s, int threads) {
    // One run per line: readable, diff-friendly, and the runs part is independent of the
    // timing fields that follow it.
    std::string j = "{\"runs\": [";
    for (std::size_t i = 0; i < runs.size(); ++i) {
        j += (i == 0 ? "\n  " : ",\n  ") + RunJson(runs[i]).dump();
    }
    j += "\n], \"elapsed_s\": " + JsonNumber(elapsed_s) +
         ", \"threads\": " + std::to_string(threads) + "}\n";
    return j;
}

std::string PiTable(const std::vector<BenchRun>& runs) {
    std::vector<std::string> shown;  // the paper's filters some run has
    for (const std::string& name : BenchFilterNames()) {
        for (const BenchRun& r : runs) {
            if (r.filters.count(name) != 0) {
                shown.push_back(name);
                break;
            }
        }
    }
    std::string t = "course test ";
    for (const std::string& name : shown) {
        char buf[32];
        std::snprintf(buf, sizeof(buf), "%9s", name.c_str());
        t += buf;
    }
    t += "   (PI, Eq. 11; lower is better; * = best)\n";
    for (const BenchRun& r : runs) {
        if (!r.scene.empty()) {
            continue;  // scene runs: PipelinesMarkdown
        }
        char head[32];
        std::snprintf(head, sizeof(head), "%6d %-4s ", r.course, r.test.c_str());
        t += head;
        double best = std::numeric_limits<double>::infinity();
        for (const std::string& name : shown) {
            const auto it = r.filters.find(name);
            if (it != r.filters.end() && std::isfinite(it->second.pi)) {
                best = std::min(best, it->second.pi);
            }
        }
        for (const std::string& name : shown) {
            const auto it = r.filters.find(name);
            const double pi = it != r.filters.end() ? it->second.pi : std::nan("");
            char buf[32];
            std::snprintf(buf, sizeof(buf), "%8s%c", Fixed(pi, 3).c_str(), pi == best ? '*' : ' ');
            t += buf;
        }
        t += "\n";
    }
    return t;
}

std::string TableTwoMarkdown(const std::vector<BenchRun>& runs) {
    std::set<std::string> tests;
    for (const BenchRun& r : runs) {
        tests.insert(r.test);
    }
    std::string md =
        "# Table II: pixels the CAS filter classified (percent of the processed interior)\n\n"
        "\"all\" counts every processed cell; \"observed\" leaves out never-observed cells "
        "(certainty 0) that were not filled. Paper: benchmark test T, 196 x 196 processed "
        "pixels of a 200 x 200 map.\n";
    for (const char* name : {"T", "TR", "TP", "TRP"}) {
        const std::string test = name;
        if (tests.count(test) == 0) {
            continue;
        }
        md += "\n## Test " + test +
              "\n\n| course | mixed (all) | missing (all) | untouched (all)"
              " | mixed (observed) | missing (observed) | untouched (observed) |";
        md += test == "T" ? " paper mixed | paper missing | paper untouched |\n" : "\n";
        md += "|---|---|---|---|---|---|---|";
        md += test == "T" ? "---|---|---|\n" : "\n";
        for (const BenchRun& r : runs) {
            if (r.test != test || !r.scene.empty()) {
                continue;
            }
            const mapper::ClassShares& a = r.cas_classes.all;
            const mapper::ClassShares& o = r.cas_classes.observed;
            md += "| " + std::to_string(r.course) + " | " + Fixed(a.removed_pct, 1) + " | " +
                  Fixed(a.filled_pct, 1) + " | " + Fixed(a.untouched_pct, 1) + " | " +
                  Fixed(o.removed_pct, 1) + " | " + Fixed(o.filled_pct, 1) + " | " +
                  Fixed(o.untouched_pct, 1) + " |";
            if (test == "T") {
                const bool known = r.course >= 1 && r.course <= 16;
                const std::size_t c = static_cast<std::size_t>(known ? r.course - 1 : 0);
                md += known ? " " + Fixed(kPaperMixed[c], 1) + " | " + Fixed(kPaperMissing[c], 1) +
                                  " | " + Fixed(kPaperUntouched[c], 1) + " |"
                            : " - | - | - |";
            }
            md += "\n";
        }
    }
    return md;
}

namespace {
/// The pipelines some run has, in AllPipelines() order.
std::vector<std::string> PresentPipelines(const std::vector<BenchRun>& runs) {
    std::set<std::string> names;
    for (const BenchRun& r : runs) {
        for (const auto& [name, score] : r.filters) {
            names.insert(name);
        }
    }
    return InPipelineOrder({names.begin(), names.end()});
}

std::string DisplayName(const std::string& name) {
    for (const std::string& paper : BenchFilterNames()) {
        if (paper == name) {
            return FilterDisplayName(name);
        }
    }
    return name;
}
}  // namespace

std::string PolesMarkdown(const std::vector<BenchRun>& runs) {
    const std::vector<std::string> shown = PresentPipelines(runs);
    static const char* const kDiameters[] = {"24", "21", "19", "15", "11", "9", "6", "4.5", "2.5"};
    std::string md =
        "# Poles kept per filter\n\nA map keeps a pole when it reaches half the pole's height "
        "(0.457 m) within one cell of the pole's cell. Counts are runs that kept the pole / runs "
        "whose raw map showed it (runs where the raw map missed it cannot count).\n\n"
        "| pole | diameter (mm) | runs | raw |";
    for (const std::string& f : shown) {
        md += " " + DisplayName(f) + " |";
    }
    md += "\n|---|---|---|---|";
    for (std::size_t i = 0; i < shown.size(); ++i) {
        md += "---|";
    }
    md += "\n";
    for (int k = 1; k <= 9; ++k) {
        const std::string pole = "pole" + std::to_string(k);
        const auto kept = [&](const BenchRun& r, const std::string& map) {
            const auto it = r.poles_kept.find(map);
            return it != r.poles_kept.end() &&
                   std::find(it->second.begin(), it->second.end(), pole) != it->second.end();
        };
        int present = 0;
        int seen = 0;
        std::map<std::string, int> count;
        for (const BenchRun& r : runs) {
            if (std::find(r.poles.begin(), r.poles.end(), pole) == r.poles.end()) {
                continue;
            }
            ++present;
            if (!kept(r, "raw")) {
                continue;
            }
            ++seen;
            for (const std::string& f : shown) {
                count[f] += kept(r, f) ? 1 : 0;
            }
        }
        if (present == 0) {
            continue;
        }
        md += "| " + pole + " | " + kDiameters[k - 1] + " | " + std::to_string(present) + " | " +
              std::to_string(seen) + " |";
        for (const std::string& f : shown) {
            md += " " + std::to_string(count[f]) + "/" + std::to_string(seen) + " |";
        }
        md += "\n";
    }
    return md;
}

std::string BenchRunName(const BenchRun& run) {
    if (run.scene.empty()) {
        char name[48];
        std::snprintf(name, sizeof(name), "course%02d_%s", run.course, run.test.c_str());
        return name;
    }
    return SceneRunStem(run.scene) + "_" + run.test;
}

std::string SceneRunStem(const std::string& scene_path) {
    const std::filesystem::path p(scene_path);
    std::string stem = p.stem().string();
    if (stem == "scene" && p.has_parent_path()) {  // casmap dataset samples: NNNNNN/scene.yaml
        stem = p.parent_path().filename().string() + "_" + stem;
    }
    return stem;
}

std::string PipelinesMarkdown(const std::vector<BenchRun>& runs) {
    const std::vector<std::string> shown = PresentPipelines(runs);
    // Groups: each test of the paper's courses, then each scene run on its own.
    std::vector<std::pair<std::string, std::vector<const BenchRun*>>> groups;
    for (const char* test : {"T", "TR", "TP", "TRP"}) {
        std::vector<const BenchRun*> members;
        for (const BenchRun& r : runs) {
            if (r.scene.empty() && r.test == test) {
                members.push_back(&r);
            }
        }
        if (!members.empty()) {
            groups.emplace_back(
                std::string("Test ") + test + " (" + std::to_string(members.size()) + " courses)",
                members);
        }
    }
    for (const BenchRun& r : runs) {
        if (!r.scene.empty()) {
            groups.emplace_back("Scene " + BenchRunName(r) + " (" + r.scene + ")",
                                std::vector<const BenchRun*>{&r});
        }
    }
    std::string md =
        "# Pipelines side by side\n\nPer pipeline (docs/paper-notes.md \"Named pipelines\"): "
        "mean PI (Eq. 11 against the plain raw map), runs where it has the lowest PI of the "
        "pipelines listed, mean RMSE on truth-edge / open / all scored cells (mm), mean "
        "surviving spikes, poles kept / poles over the runs, mean coverage (scored cells / "
        "cells the raw map knows). Unknown cells: each run's convention (0 on the paper's "
        "courses, NaN on terrain scenes: RMSEs then cover observed cells only).\n";
    for (const auto& [title, members] : groups) {
        md += "\n## " + title +
              "\n\n| pipeline | PI | lowest PI | RMSE edges | RMSE open |"
              " RMSE all | spikes | poles kept | coverage |\n"
              "|---|---|---|---|---|---|---|---|---|\n";
        std::map<std::string, int> wins;
        for (const BenchRun* r : members) {
            double best = std::numeric_limits<double>::infinity();
            for (const std::string& name : shown) {
                const auto it = r->filters.find(name);
                if (it != r->filters.end() && std::isfinite(it->second.pi)) {
                    best = std::min(best, it->second.pi);
                }
            }
            for (const std::string& name : shown) {
                const auto it = r->filters.find(name);
                wins[name] += it != r->filters.end() && it->second.pi == best ? 1 : 0;
            }
        }
        for (const std::string& name : shown) {
            std::array<double, 6> sum{};  // pi, edge, open, all, spikes, coverage
            std::array<int, 6> n{};
            std::size_t kept = 0;
            std::size_t poles = 0;
            const auto add = [&](std::size_t i, double v) {
                if (std::isfinite(v)) {
                    sum[i] += v;
                    ++n[i];
                }
            };
            for (const BenchRun* r : members) {
                const auto it = r->filters.find(name);
                if (it == r->filters.end()) {
                    continue;
                }
                const FilterScore& f = it->second;
                add(0, f.pi);
                add(1, 1000.0 * f.edge_rmse_m);
                add(2, 1000.0 * f.open_rmse_m);
                add(3, 1000.0 * f.rmse_m);
                add(4, static_cast<double>(f.spikes));
                add(5, f.coverage);
                const auto k = r->poles_kept.find(name);
                kept += k == r->poles_kept.end() ? 0 : k->second.size();
                poles += r->poles.size();
            }
            const auto mean = [&](std::size_t i, int decimals) {
                return n[i] > 0 ? Fixed(sum[i] / n[i], decimals) : std::string("-");
            };
            md += "| " + name + " | " + mean(0, 3) + " | " + std::to_string(wins[name]) + "/" +
                  std::to_string(members.size()) + " | " + mean(1, 1) + " | " + mean(2, 1) + " | " +
                  mean(3, 1) + " | " + mean(4, 1) + " | " + std::to_string(kept) + "/" +
                  std::to_string(poles) + " | " + mean(5, 3) + " |\n";
        }
    }
    return md;
}

}  // namespace casmap::pipeline
