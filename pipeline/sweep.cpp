// `casmap sweep`'s options: axes, seeds, training and held-out sets, and their validation
// (sweep.hpp). The runs are in sweep_run.cpp, the outputs in sweep_report.cpp.
#include "casmap/pipeline/sweep.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <optional>
#include <set>

#include "casmap/core/check.hpp"
#include "casmap/core/input_error.hpp"
#include "casmap/core/text.hpp"
#include "casmap/pipeline/bench_pipelines.hpp"
#include "casmap/pipeline/bench_runner.hpp"
#include "casmap/pipeline/sweep_detail.hpp"

namespace casmap::pipeline {
namespace {

constexpr std::size_t kMaxPoints = 10000;
constexpr int kMaxGrowRounds = 20;

std::string Allowed() {
    std::string list;
    for (const std::string& n : SweepableParameters()) {
        list += (list.empty() ? "" : ", ") + n;
    }
    return "unknown parameter; allowed: " + list;
}

/// Throws InputError naming "axes" when `name` is a mapping stage's parameter (pre-filter,
/// Kalman mapper) that the swept pipeline does not run: the axis would change nothing.
void CheckStageAxis(const SweepOptions& opt, const std::string& name) {
    if (!IsStageParameter(name)) {
        return;
    }
    const PipelineSpec& spec = FindPipeline(opt.filter, "filter");
    const bool shadow = name.starts_with("shadow.");
    const bool jump = name.starts_with("range_jump.");
    const bool sweep = name.starts_with("sweep_jump.");
    const bool consensus = name.starts_with("consensus.");
    const bool used = shadow      ? spec.prefilter == Prefilter::kShadow
                      : jump      ? spec.prefilter == Prefilter::kRangeJump
                      : sweep     ? spec.prefilter == Prefilter::kSweepJump
                      : consensus ? spec.mode == MapperMode::kConsensus
                                  : spec.mode == MapperMode::kKalman;
    if (!used) {
        throw MakeInputError("", "axes", name,
                             "the filter " + opt.filter + " does not run the " +
                                 (shadow      ? "shadow pre-filter"
                                  : jump      ? "range_jump pre-filter"
                                  : sweep     ? "sweep_jump pre-filter"
                                  : consensus ? "consensus mapper"
                                              : "Kalman mapper") +
                                 " (sweep a pipeline that does, e.g. " +
                                 (shadow      ? "shadow_cas"
                                  : jump      ? "range_jump_cas"
                                  : sweep     ? "sweep_jump_hybrid"
                                  : consensus ? "consensus_hybrid"
                                              : "kalman_median") +
                                 ")");
    }
}

double ParseNumber(const std::string& text,
                   const std::string& assignment,
                   const std::string& field) {
    const std::optional<double> v = core::ParseFiniteDouble(text);
    if (!v) {
        throw MakeInputError("", field, assignment, "FROM, TO and STEP must be numbers");
    }
    return *v;
}

bool IsSweepable(const std::string& name) {
    const std::vector<std::string>& names = SweepableParameters();
    return std::find(names.begin(), names.end(), name) != names.end();
}

std::uint64_t ParseSeed(const std::string& text, const std::string& all, const std::string& field) {
    const bool digits =
        !text.empty() && text.size() <= 19 &&
        std::all_of(text.begin(), text.end(), [](char c) { return c >= '0' && c <= '9'; });
    if (!digits) {
        throw MakeInputError("", field, all,
                             "expected seeds like 1-2 or 3,7 (non-negative integers)");
    }
    return std::stoull(text);
}

}  // namespace

namespace detail {

std::vector<std::vector<double>> GridPoints(const std::vector<SweepAxis>& axes) {
    std::vector<std::vector<double>> points = {{}};
    for (const SweepAxis& axis : axes) {
        std::vector<std::vector<double>> next;
        for (const auto& p : points) {
            for (const double v : axis.values) {
                next.push_back(p);
                next.back().push_back(v);
            }
        }
        points = std::move(next);
        if (points.size() > kMaxPoints) {
            throw MakeInputError("", "axes", "", "more than 10000 grid points");
        }
    }
    return points;
}

std::vector<std::string> PointOverrides(const SweepOptions& opt, const std::vector<double>& point) {
    std::vector<std::string> out = opt.fixed;
    for (std::size_t i = 0; i < opt.axes.size(); ++i) {
        if (opt.axes[i].name == "speed") {
            continue;  // a rig setting; CAS's v follows the run (RunFilterParams)
        }
        out.push_back(opt.axes[i].name + "=" + FormatNumber(point[i]));
        if (opt.axes[i].name == "E") {
            out.push_back("e_term=on");  // sweeping E means using Eq. 10's E term
        }
    }
    return out;
}

int AxisIndex(const SweepOptions& opt, const std::string& name) {
    for (std::size_t i = 0; i < opt.axes.size(); ++i) {
        if (opt.axes[i].name == name) {
            return static_cast<int>(i);
        }
    }
    return -1;
}

std::vector<double> Speeds(const SweepOptions& opt) {
    const int i = AxisIndex(opt, "speed");
    return i >= 0 ? opt.axes[static_cast<std::size_t>(i)].values : std::vector<double>{0.0};
}

std::vector<std::vector<SimSetup>> Setups(const SweepOptions& opt,
                                          const BenchSettings& settings,
                                          const std::vector<std::string>& tests) {
    const bool swept = AxisIndex(opt, "speed") >= 0;
    std::vector<std::vector<SimSetup>> setups;
    BenchSettings probe = settings;
    for (const double v : Speeds(opt)) {
        probe.speed_m_s = swept ? std::optional(v) : std::nullopt;
        setups.emplace_back();
        for (const std::string& t : tests) {
            setups.back().push_back(BenchSetup(probe, opt.courses.front(), t));
        }
    }
    return setups;
}

void CheckAxisValue(const SweepOptions& opt, const std::string& name, double v) {
    if (name == "speed" && !(v > 0.0 && v <= rig::TableLimits::kMaxSpeedMS)) {
        throw MakeInputError("", "axes", "speed=" + FormatNumber(v),
                             "allowed: > 0 and <= 1 m/s (the table's limit)");
    }
    if (name == "a" && (v != std::floor(v) || v < 1 || v > 1000)) {
        throw MakeInputError("", "axes", "a=" + FormatNumber(v), "allowed: integer 1..1000");
    }
    if (name == "speed") {
        return;
    }
    mapper::FilterParams check;
    for (const std::string& f : opt.fixed) {
        check.SetAssignment(f);
    }
    try {
        check.Set(name, FormatNumber(v));
        check.Validate();
    } catch (const InputError& e) {
        throw MakeInputError("", "axes", name + "=" + FormatNumber(v), e.what());
    }
}

double Snap(double v) { return core::ParseFiniteDouble(core::FormatNumber(v, 12)).value_or(v); }

bool AxisValueAllowed(const SweepOptions& opt, const std::string& name, double value) {
    try {
        CheckAxisValue(opt, name, value);
    } catch (const InputError&) {
        return false;
    }
    return true;
}

std::optional<mapper::FilterMethod> SweepFilter(const SweepOptions& opt) {
    const std::vector<std::string>& fast = SweepableFilters();
    if (std::find(fast.begin(), fast.end(), opt.filter) == fast.end()) {
        return std::nullopt;
    }
    return mapper::ParseFilterMethod(opt.filter, "filter");
}

}  // namespace detail

const std::vector<std::string>& SweepableParameters() {
    static const std::vector<std::string> names = {
        "A", "G", "B", "h_sum_min", "a", "E", "k", "speed", "support_tol_m", "support_min",
        "ground_k", "ground_quantile", "edge_min", "edge_tol_m", "surface_tol_m", "surface_min",
        "surface_prior", "median_mix", "nan_median_mix", "edge_fill", "edge_fill_run",
        "edge_spill_c", "edge_spill_drop_m", "edge_spill",
        // mapping stages: only with a pipeline that runs them (--filter shadow_cas, ...)
        "shadow.min_angle_deg", "shadow.max_angle_deg", "shadow.window", "shadow.neighbors",
        "range_jump.jump_min_m", "range_jump.margin_m", "range_jump.chord_tol_m",
        "sweep_jump.jump_min_m", "sweep_jump.margin_m", "sweep_jump.max_angle_deg",
        "sweep_jump.depression_share", "sweep_jump.reach", "kalman.range_sigma_m",
        "kalman.beam_constant_m", "kalman.beam_angle_rad", "kalman.min_variance_m2",
        "kalman.mahalanobis_gate", "kalman.multi_height_noise_m2", "consensus.spread_m",
        "consensus.min_hits"};
    return names;
}

const std::vector<std::string>& SweepableFilters() {
    static const std::vector<std::string> names = {"cas",        "cas_trail", "cas_terrain",
                                                   "cas_median", "cas_edge",  "cas_hybrid"};
    return names;
}

SweepAxis ParseSweepAxis(const std::string& assignment, const std::string& field) {
    const std::size_t eq = assignment.find('=');
    const std::string rule = "expected NAME=FROM:TO:STEP with FROM <= TO and STEP > 0";
    if (eq == std::string::npos) {
        throw MakeInputError("", field, assignment, rule);
    }
    SweepAxis axis;
    axis.name = assignment.substr(0, eq);
    if (!IsSweepable(axis.name)) {
        throw MakeInputError("", field, axis.name, Allowed());
    }
    const std::vector<std::string> range = core::SplitList(assignment.substr(eq + 1), ':');
    if (range.size() != 3) {
        throw MakeInputError("", field, assignment, rule);
    }
    const double from = ParseNumber(range[0], assignment, field);
    const double to = ParseNumber(range[1], assignment, field);
    const double step = ParseNumber(range[2], assignment, field);
    if (!(step > 0.0)) {
        throw MakeInputError("", field, assignment, "STEP must be > 0 (" + rule + ")");
    }
    if (from > to) {
        throw MakeInputError("", field, assignment, "inverted range: FROM > TO (" + rule + ")");
    }
    const double count = std::floor((to - from) / step * (1.0 + 1e-12) + 1e-9) + 1.0;
    if (count > static_cast<double>(kMaxPoints)) {
        throw MakeInputError("", field, assignment, "more than 10000 values");
    }
    for (int i = 0; i < static_cast<int>(count); ++i) {
        axis.values.push_back(detail::Snap(from + i * step));  // 0.09, not 0.09000000000000001
    }
    return axis;
}

std::vector<std::uint64_t> ParseSeeds(const std::string& text, const std::string& field) {
    std::set<std::uint64_t> seeds;
    const std::vector<std::string> parts = core::SplitList(text);
    if (parts.empty()) {
        (void)ParseSeed(text, text, field);  // throws: no seed given
    }
    for (const std::string& part : parts) {
        const std::size_t dash = part.find('-');
        if (dash == std::string::npos) {
            seeds.insert(ParseSeed(part, text, field));
        } else {
            const std::uint64_t lo = ParseSeed(part.substr(0, dash), text, field);
            const std::uint64_t hi = ParseSeed(part.substr(dash + 1), text, field);
            if (lo > hi || hi - lo >= 10000) {
                throw MakeInputError("", field, text,
                                     "a range FROM-TO needs FROM <= TO, at most 10000 seeds");
            }
            for (std::uint64_t s = lo; s <= hi; ++s) {
                seeds.insert(s);
            }
        }
    }
    return {seeds.begin(), seeds.end()};
}

std::vector<std::uint64_t> SweepOptions::TrainSeeds() const {
    return seeds.empty() ? std::vector<std::uint64_t>{seed} : seeds;
}

void SweepOptions::Validate() const {
    const core::Check check;
    try {
        (void)FindPipeline(filter, "filter");
    } catch (const InputError& e) {
        check.Fail("filter", filter,
                   "allowed: a bench pipeline name (cas, cas_trail, cas_terrain, "
                   "range_jump_cas, ...; casmap bench --pipelines)");
    }
    for (std::size_t i = 0; i < axes.size(); ++i) {
        const SweepAxis& axis = axes[i];
        if (!IsSweepable(axis.name)) {
            check.Fail("axes", axis.name, Allowed());
        }
        if (axis.values.empty()) {
            check.Fail("axes", axis.name, "at least one value");
        }
        CheckStageAxis(*this, axis.name);
        for (std::size_t j = 0; j < i; ++j) {
            if (axes[j].name == axis.name) {
                check.Fail("axes", axis.name, "parameter given twice");
            }
        }
        for (const double v : axis.values) {
            if (axis.name == "speed" || axis.name == "a") {
                detail::CheckAxisValue(*this, axis.name, v);
            }
        }
    }
    if (search != "grid" && search != "descent") {
        check.Fail("search", search, "allowed: grid, descent");
    }
    if (grow < 0 || grow > kMaxGrowRounds) {
        check.Fail("grow", std::to_string(grow), "allowed: 0..20 rounds");
    }
    CheckCoursesAndTests(courses, tests);
    if (!test_courses.empty()) {
        try {
            CheckCoursesAndTests(test_courses, tests);
        } catch (const InputError& e) {
            check.Fail("test_courses", "", e.what());
        }
    }
    const std::vector<std::uint64_t> train = TrainSeeds();
    if (HasHeldOut()) {
        const std::vector<std::uint64_t> held = test_seeds.empty() ? train : test_seeds;
        const std::vector<int> held_courses = test_courses.empty() ? courses : test_courses;
        for (const std::uint64_t s : held) {
            for (const int c : held_courses) {
                if (std::find(train.begin(), train.end(), s) != train.end() &&
                    std::find(courses.begin(), courses.end(), c) != courses.end()) {
                    check.Fail(
                        test_seeds.empty() ? "test_courses" : "test_seeds",
                        "seed " + std::to_string(s) + ", course " + std::to_string(c),
                        "a held-out run must not be a training run (give other seeds or courses)");
                }
            }
        }
    }
    const BenchSettings settings = ResolveBenchSettings(courses_dir, rig_path, sensor_path, seed);
    (void)detail::Setups(*this, settings, SortedTests(tests));
    for (const auto& p : detail::GridPoints(axes)) {
        mapper::FilterParams params;
        for (const std::string& o : detail::PointOverrides(*this, p)) {
            params.SetAssignment(o);
        }
        params.Validate();
    }
}

SweepStats Summarise(const std::vector<double>& values) {
    SweepStats s;
    std::vector<double> finite;
    for (const double x : values) {
        if (std::isfinite(x)) {
            finite.push_back(x);
        }
    }
    s.runs = finite.size();
    if (finite.empty()) {
        return s;
    }
    double sum = 0.0;
    for (const double x : finite) {
        sum += x;
    }
    s.mean = sum / static_cast<double>(finite.size());
    double ss = 0.0;
    for (const double x : finite) {
        ss += (x - s.mean) * (x - s.mean);
    }
    s.std = std::sqrt(ss / static_cast<double>(finite.size()));  // population spread
    s.min = *std::min_element(finite.begin(), finite.end());
    s.max = *std::max_element(finite.begin(), finite.end());
    return s;
}

}  // namespace casmap::pipeline
