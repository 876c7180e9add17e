#include "casmap/mapper/filter_params.hpp"

#include <charconv>
#include <cmath>
#include <functional>
#include <map>

#include "casmap/core/check.hpp"
#include "casmap/core/input_error.hpp"
#include "casmap/core/text.hpp"

namespace casmap::mapper {
namespace {

// Set and Validate name the parameter; a CLI shows them as --set, Python as keywords.
const char* const kWhere = "filter parameters";

[[noreturn]] void Reject(std::string_view name, std::string_view value, const std::string& rule) {
    throw MakeInputError(kWhere, std::string(name), std::string(value), rule);
}

double ParseNumber(std::string_view name, std::string_view value) {
    double v = 0.0;
    const auto [end, ec] = std::from_chars(value.data(), value.data() + value.size(), v);
    if (ec != std::errc() || end != value.data() + value.size() || !std::isfinite(v)) {
        Reject(name, value, "must be a finite number");
    }
    return v;
}

double ParseRange(
    std::string_view name, std::string_view value, double lo, double hi, bool lo_open) {
    const double v = ParseNumber(name, value);
    if ((lo_open ? !(v > lo) : !(v >= lo)) || v > hi) {
        std::string rule = "allowed: ";
        rule += lo_open ? "> " : ">= ";
        rule += core::FormatNumber(lo);
        if (std::isfinite(hi)) {
            rule += " and <= " + core::FormatNumber(hi);
        }
        Reject(name, value, rule);
    }
    return v;
}

/// A number strictly between lo and hi.
double ParseBetween(std::string_view name, std::string_view value, double lo, double hi) {
    const double v = ParseNumber(name, value);
    if (!(v > lo && v < hi)) {
        Reject(name, value,
               "allowed: > " + core::FormatNumber(lo) + " and < " + core::FormatNumber(hi));
    }
    return v;
}

int ParseInt(std::string_view name, std::string_view value, int lo, int hi) {
    int v = 0;
    const auto [end, ec] = std::from_chars(value.data(), value.data() + value.size(), v);
    if (ec != std::errc() || end != value.data() + value.size() || v < lo || v > hi) {
        Reject(name, value, "allowed: integer " + std::to_string(lo) + ".." + std::to_string(hi));
    }
    return v;
}

template <typename Enum>
Enum ParseChoice(std::string_view name,
                 std::string_view value,
                 const std::vector<std::pair<std::string_view, Enum>>& choices) {
    std::string allowed;
    for (const auto& [text, e] : choices) {
        if (value == text) {
            return e;
        }
        allowed += allowed.empty() ? "" : "|";
        allowed += text;
    }
    Reject(name, value, "allowed: " + allowed);
}

constexpr double kInf = HUGE_VAL;

using Setter = std::function<void(FilterParams&, std::string_view, std::string_view)>;

const std::map<std::string, Setter, std::less<>>& Setters() {
    static const std::map<std::string, Setter, std::less<>> setters = {
        {"k", [](FilterParams& p, auto n, auto v) { p.cas.k = ParseInt(n, v, 1, 7); }},
        {"a", [](FilterParams& p, auto n, auto v) { p.cas.a = ParseInt(n, v, 1, 1000); }},
        {"cell_m",
         [](FilterParams& p, auto n, auto v) { p.cas.cell_m = ParseRange(n, v, 0, kInf, true); }},
        {"speed_m_s", [](FilterParams& p, auto n,
                         auto v) { p.cas.speed_m_s = ParseRange(n, v, 0, kInf, true); }},
        {"scan_period_s", [](FilterParams& p, auto n,
                             auto v) { p.cas.scan_period_s = ParseRange(n, v, 0, kInf, true); }},
        {"A", [](FilterParams& p, auto n, auto v) { p.cas.A = ParseRange(n, v, 0, kInf, false); }},
        {"G", [](FilterParams& p, auto n, auto v) { p.cas.G = ParseRange(n, v, 0, kInf, false); }},
        {"gs_mode",
         [](FilterParams& p, auto n, auto v) {
             p.cas.gs_mode = ParseChoice<GsMode>(
                 n, v, {{"sum", GsMode::kSum}, {"variance", GsMode::kVariance}});
         }},
        {"h_sum_min", [](FilterParams& p, auto n,
                         auto v) { p.cas.h_sum_min = ParseRange(n, v, 0, kInf, false); }},
        {"B", [](FilterParams& p, auto n, auto v) { p.cas.B = ParseRange(n, v, 0, kInf, false); }},
        {"normalise",
         [](FilterParams& p, auto n, auto v) {
             p.cas.normalise = ParseChoice<Normalise>(
                 n, v, {{"window", Normalise::kWindow}, {"global", Normalise::kGlobal}});
         }},
        {"e_term",
         [](FilterParams& p, auto n, auto v) {
             p.cas.e_term = ParseChoice<bool>(n, v, {{"off", false}, {"on", true}});
         }},
        {"E", [](FilterParams& p, auto n, auto v) { p.cas.E = ParseRange(n, v, 0, kInf, false); }},
        {"wm_empty",
         [](FilterParams& p, auto n, auto v) {
             p.cas.wm_empty = ParseChoice<WmEmpty>(
                 n, v, {{"include", WmEmpty::kInclude}, {"skip", WmEmpty::kSkip}});
         }},
        {"unknown",
         [](FilterParams& p, auto n, auto v) {
             p.cas.unknown =
                 ParseChoice<Unknown>(n, v, {{"zero", Unknown::kZero}, {"nan", Unknown::kNaN}});
             p.baseline.unknown = p.cas.unknown;
         }},
        {"ground",
         [](FilterParams& p, auto n, auto v) {
             p.cas.ground =
                 ParseChoice<Ground>(n, v, {{"zero", Ground::kZero}, {"local", Ground::kLocal}});
         }},
        {"ground_k",
         [](FilterParams& p, auto n, auto v) { p.cas.ground_k = ParseInt(n, v, 1, 15); }},
        {"ground_quantile", [](FilterParams& p, auto n,
                               auto v) { p.cas.ground_quantile = ParseRange(n, v, 0, 1, false); }},
        {"support",
         [](FilterParams& p, auto n, auto v) {
             p.cas.support =
                 ParseChoice<Support>(n, v, {{"off", Support::kOff}, {"height", Support::kHeight}});
         }},
        {"support_tol_m", [](FilterParams& p, auto n,
                             auto v) { p.cas.support_tol_m = ParseRange(n, v, 0, kInf, true); }},
        {"support_min",
         [](FilterParams& p, auto n, auto v) { p.cas.support_min = ParseInt(n, v, 1, 48); }},
        {"edge_tol_m", [](FilterParams& p, auto n,
                          auto v) { p.cas.edge_tol_m = ParseRange(n, v, 0, kInf, true); }},
        {"edge_min",
         [](FilterParams& p, auto n, auto v) { p.cas.edge_min = ParseInt(n, v, 1, 225); }},
        {"surface_tol_m", [](FilterParams& p, auto n,
                             auto v) { p.cas.surface_tol_m = ParseRange(n, v, 0, kInf, true); }},
        {"surface_min",
         [](FilterParams& p, auto n, auto v) { p.cas.surface_min = ParseInt(n, v, 1, 225); }},
        {"surface_prior", [](FilterParams& p, auto n,
                             auto v) { p.cas.surface_prior = ParseRange(n, v, 0, 1e6, false); }},
        {"median_mix",
         [](FilterParams& p, auto n, auto v) { p.cas.median_mix = ParseRange(n, v, 0, 1, false); }},
        {"nan_median_mix",
         [](FilterParams& p, auto n, auto v) {
             const double x = ParseRange(n, v, -1, 1, false);
             if (x < 0.0 && x != -1.0) {
                 Reject(n, v, "allowed: -1 (as median_mix) or 0..1");
             }
             p.cas.nan_median_mix = x;
         }},
        {"edge_fill",
         [](FilterParams& p, auto n, auto v) { p.cas.edge_fill = ParseRange(n, v, 0, 1, false); }},
        {"edge_fill_run",
         [](FilterParams& p, auto n, auto v) { p.cas.edge_fill_run = ParseInt(n, v, 0, 2); }},
        {"edge_spill_c", [](FilterParams& p, auto n,
                            auto v) { p.cas.edge_spill_c = ParseRange(n, v, 0, 1e6, false); }},
        {"edge_spill_drop_m", [](FilterParams& p, auto n, auto v) {
             p.cas.edge_spill_drop_m = ParseRange(n, v, 0, 1, false);
         }},
        {"edge_spill",
         [](FilterParams& p, auto n, auto v) { p.cas.edge_spill = ParseRange(n, v, 0, 1, false); }},
        {"window",
         [](FilterParams& p, auto n, auto v) {
             const int w = ParseInt(n, v, 3, 15);
             if (w % 2 == 0) {
                 Reject(n, v, "allowed: odd integer 3..15");
             }
             p.baseline.window = w;
         }},
        {"noise", [](FilterParams& p, auto n,
                     auto v) { p.baseline.noise = ParseRange(n, v, 0, kInf, false); }},
        // --- scan pre-filters (scan_filters.hpp) and the Kalman mapper mode (kalman_noise.hpp)
        {"shadow.min_angle_deg",
         [](FilterParams& p, auto n, auto v) {
             p.shadow.min_angle_deg = ParseBetween(n, v, 0, 90);
         }},
        {"shadow.max_angle_deg",
         [](FilterParams& p, auto n, auto v) {
             p.shadow.max_angle_deg = ParseBetween(n, v, 90, 180);
         }},
        {"shadow.window",
         [](FilterParams& p, auto n, auto v) { p.shadow.window = ParseInt(n, v, 1, 10); }},
        {"shadow.neighbors",
         [](FilterParams& p, auto n, auto v) { p.shadow.neighbors = ParseInt(n, v, 0, 20); }},
        {"shadow.remove_start_point",
         [](FilterParams& p, auto n, auto v) {
             p.shadow.remove_start_point = ParseChoice<bool>(n, v, {{"off", false}, {"on", true}});
         }},
        {"range_jump.jump_min_m",
         [](FilterParams& p, auto n, auto v) {
             p.range_jump.jump_min_m = ParseRange(n, v, 0, kInf, true);
         }},
        {"range_jump.margin_m",
         [](FilterParams& p, auto n, auto v) {
             p.range_jump.margin_m = ParseRange(n, v, 0, kInf, false);
         }},
        {"range_jump.chord_tol_m",
         [](FilterParams& p, auto n, auto v) {
             p.range_jump.chord_tol_m = ParseRange(n, v, 0, kInf, false);
         }},
        {"sweep_jump.jump_min_m",
         [](FilterParams& p, auto n, auto v) {
             p.sweep_jump.jump_min_m = ParseRange(n, v, 0, kInf, true);
         }},
        {"sweep_jump.margin_m",
         [](FilterParams& p, auto n, auto v) {
             p.sweep_jump.margin_m = ParseRange(n, v, 0, kInf, false);
         }},
        {"sweep_jump.max_angle_deg",
         [](FilterParams& p, auto n, auto v) {
             p.sweep_jump.max_angle_deg = ParseBetween(n, v, 0, 90);
         }},
        {"sweep_jump.depression_share",
         [](FilterParams& p, auto n, auto v) {
             p.sweep_jump.depression_share = ParseRange(n, v, 0, 1, false);
         }},
        {"sweep_jump.reach",
         [](FilterParams& p, auto n, auto v) { p.sweep_jump.reach = ParseInt(n, v, 1, 3); }},
        {"kalman.range_sigma_m",
         [](FilterParams& p, auto n, auto v) {
             p.kalman.range_sigma_m = ParseRange(n, v, 0, kInf, false);
         }},
        {"kalman.beam_constant_m",
         [](FilterParams& p, auto n, auto v) {
             p.kalman.beam_constant_m = ParseRange(n, v, 0, kInf, false);
         }},
        {"kalman.beam_angle_rad",
         [](FilterParams& p, auto n, auto v) {
             p.kalman.beam_angle_rad = ParseRange(n, v, 0, kInf, false);
         }},
        {"kalman.min_variance_m2",
         [](FilterParams& p, auto n, auto v) {
             p.kalman.min_variance_m2 = ParseRange(n, v, 0, kInf, true);
         }},
        {"kalman.mahalanobis_gate",
         [](FilterParams& p, auto n, auto v) {
             p.kalman.mahalanobis_gate = ParseRange(n, v, 0, kInf, true);
         }},
        {"kalman.multi_height_noise_m2",
         [](FilterParams& p, auto n, auto v) {
             p.kalman.multi_height_noise_m2 = ParseRange(n, v, 0, kInf, false);
         }},
        {"consensus.spread_m",
         [](FilterParams& p, auto n, auto v) {
             p.consensus.spread_m = ParseRange(n, v, 0, 1, false);
         }},
        {"consensus.min_hits",
         [](FilterParams& p, auto n, auto v) { p.consensus.min_hits = ParseInt(n, v, 2, 1000000); }},
        {"center_weight",
         [](FilterParams& p, auto n, auto v) {
             const int w = ParseInt(n, v, 1, 99);
             if (w % 2 == 0) {
                 Reject(n, v, "allowed: odd integer 1..99, so the sample count stays odd");
             }
             p.baseline.center_weight = w;
         }},
    };
    return setters;
}

}  // namespace

FilterMethod ParseFilterMethod(std::string_view name, const std::string& field) {
    for (const FilterMethod m : AllFilterMethods()) {
        if (name == ToString(m)) {
            return m;
        }
    }
    for (const FilterMethod m : AllFilterMethodsWithVariants()) {
        if (name == ToString(m)) {
            return m;
        }
    }
    throw MakeInputError("", field, std::string(name),
                         "allowed: cas|wiener|average|median|cwm|cas_terrain|cas_trail|cas_median|"
                         "cas_edge|cas_hybrid");
}

std::string_view ToString(FilterMethod method) {
    switch (method) {
        case FilterMethod::kCas:
            return "cas";
        case FilterMethod::kWiener:
            return "wiener";
        case FilterMethod::kAverage:
            return "average";
        case FilterMethod::kMedian:
            return "median";
        case FilterMethod::kCwm:
            return "cwm";
        case FilterMethod::kCasTerrain:
            return "cas_terrain";
        case FilterMethod::kCasTrail:
            return "cas_trail";
        case FilterMethod::kCasMedian:
            return "cas_median";
        case FilterMethod::kCasEdge:
            return "cas_edge";
        case FilterMethod::kCasHybrid:
            return "cas_hybrid";
    }
    return "?";
}

const std::vector<FilterMethod>& AllFilterMethods() {
    static const std::vector<FilterMethod> all = {FilterMethod::kCas, FilterMethod::kWiener,
                                                  FilterMethod::kAverage, FilterMethod::kMedian,
                                                  FilterMethod::kCwm};
    return all;
}

const std::vector<FilterMethod>& AllFilterMethodsWithVariants() {
    static const std::vector<FilterMethod> all = {
        FilterMethod::kCas,      FilterMethod::kWiener,    FilterMethod::kAverage,
        FilterMethod::kMedian,   FilterMethod::kCwm,       FilterMethod::kCasTerrain,
        FilterMethod::kCasTrail, FilterMethod::kCasMedian, FilterMethod::kCasEdge,
        FilterMethod::kCasHybrid};
    return all;
}

double CasParams::EffectiveA() const {
    if (A) {
        return *A;
    }
    // Eq. 8; int() is "round to the nearest integer" in the paper's words.
    return a * (std::round(cell_m / (speed_m_s * scan_period_s)) + 2.0);
}

double CasParams::EffectiveG() const { return G ? *G : 10.0 * EffectiveA(); }

void FilterParams::Set(std::string_view name, std::string_view value) {
    const auto& setters = Setters();
    const auto it = setters.find(name);
    if (it == setters.end()) {
        std::string known;
        for (const auto& [n, s] : setters) {
            known += known.empty() ? "" : ", ";
            known += n;
        }
        throw MakeInputError(kWhere, std::string(name), std::string(value),
                             "unknown filter parameter; known: " + known);
    }
    it->second(*this, name, value);
}

void FilterParams::SetAssignment(std::string_view assignment) {
    const std::size_t eq = assignment.find('=');
    if (eq == std::string_view::npos || eq == 0) {
        throw MakeInputError(kWhere, std::string(assignment), "", "expected NAME=VALUE");
    }
    Set(assignment.substr(0, eq), assignment.substr(eq + 1));
}

void FilterParams::Validate() const {
    const core::Check check(kWhere);
    check.That(cas.k >= 1 && cas.k <= 7, "k", cas.k, "allowed: integer 1..7");
    check.That(cas.a >= 1, "a", cas.a, "allowed: integer >= 1");
    check.That(cas.cell_m > 0 && std::isfinite(cas.cell_m), "cell_m", cas.cell_m, "allowed: > 0");
    check.That(cas.speed_m_s > 0 && std::isfinite(cas.speed_m_s), "speed_m_s", cas.speed_m_s,
               "allowed: > 0");
    check.That(cas.scan_period_s > 0 && std::isfinite(cas.scan_period_s), "scan_period_s",
               cas.scan_period_s, "allowed: > 0");
    check.That(std::isfinite(cas.EffectiveA()) && cas.EffectiveA() >= 0, "A", cas.EffectiveA(),
               "allowed: >= 0");
    check.That(std::isfinite(cas.EffectiveG()) && cas.EffectiveG() >= 0, "G", cas.EffectiveG(),
               "allowed: >= 0");
    check.That(cas.h_sum_min >= 0, "h_sum_min", cas.h_sum_min, "allowed: >= 0");
    check.That(cas.B >= 0, "B", cas.B, "allowed: >= 0");
    check.That(cas.E >= 0, "E", cas.E, "allowed: >= 0");
    check.That(cas.ground_k >= 1 && cas.ground_k <= 15, "ground_k", cas.ground_k,
               "allowed: integer 1..15");
    check.That(cas.ground_quantile >= 0 && cas.ground_quantile <= 1, "ground_quantile",
               cas.ground_quantile, "allowed: 0..1");
    check.That(cas.support_tol_m > 0 && std::isfinite(cas.support_tol_m), "support_tol_m",
               cas.support_tol_m, "allowed: > 0");
    check.That(cas.support_min >= 1 && cas.support_min <= 48, "support_min", cas.support_min,
               "allowed: integer 1..48");
    check.That(cas.edge_tol_m > 0 && std::isfinite(cas.edge_tol_m), "edge_tol_m", cas.edge_tol_m,
               "allowed: > 0");
    check.That(cas.edge_min >= 1 && cas.edge_min <= 225, "edge_min", cas.edge_min,
               "allowed: integer 1..225");
    check.That(cas.surface_tol_m > 0 && std::isfinite(cas.surface_tol_m), "surface_tol_m",
               cas.surface_tol_m, "allowed: > 0");
    check.That(cas.surface_min >= 1 && cas.surface_min <= 225, "surface_min", cas.surface_min,
               "allowed: integer 1..225");
    check.That(cas.surface_prior >= 0 && cas.surface_prior <= 1e6, "surface_prior",
               cas.surface_prior, "allowed: 0..1e6");
    check.That(cas.median_mix >= 0 && cas.median_mix <= 1, "median_mix", cas.median_mix,
               "allowed: 0..1");
    check.That(cas.nan_median_mix == -1.0 || (cas.nan_median_mix >= 0 && cas.nan_median_mix <= 1),
               "nan_median_mix", cas.nan_median_mix, "allowed: -1 (as median_mix) or 0..1");
    check.That(cas.edge_fill >= 0 && cas.edge_fill <= 1, "edge_fill", cas.edge_fill,
               "allowed: 0..1");
    check.That(cas.edge_fill_run >= 0 && cas.edge_fill_run <= 2, "edge_fill_run", cas.edge_fill_run,
               "allowed: integer 0..2");
    check.That(cas.edge_spill_c >= 0 && cas.edge_spill_c <= 1e6, "edge_spill_c", cas.edge_spill_c,
               "allowed: 0..1e6");
    check.That(cas.edge_spill_drop_m >= 0 && cas.edge_spill_drop_m <= 1, "edge_spill_drop_m",
               cas.edge_spill_drop_m, "allowed: 0..1");
    check.That(cas.edge_spill >= 0 && cas.edge_spill <= 1, "edge_spill", cas.edge_spill,
               "allowed: 0..1");
    check.That(baseline.window >= 3 && baseline.window <= 15 && baseline.window % 2 == 1, "window",
               baseline.window, "allowed: odd integer 3..15");
    check.That(!baseline.noise || (*baseline.noise >= 0 && std::isfinite(*baseline.noise)), "noise",
               baseline.noise.value_or(0.0), "allowed: >= 0");
    check.That(baseline.center_weight >= 1 && baseline.center_weight % 2 == 1, "center_weight",
               baseline.center_weight, "allowed: odd integer >= 1");
    // InputError naming shadow.<field>, range_jump.<field>, sweep_jump.<field>, kalman.<field>
    shadow.Validate();
    range_jump.Validate();
    sweep_jump.Validate();
    kalman.Validate();
}

const std::vector<std::string>& FilterParams::Names() {
    static const std::vector<std::string> names = [] {
        std::vector<std::string> out;
        for (const auto& [n, s] : Setters()) {
            out.push_back(n);
        }
        return out;
    }();
    return names;
}

}  // namespace casmap::mapper
