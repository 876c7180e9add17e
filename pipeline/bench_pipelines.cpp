#include "casmap/pipeline/bench_pipelines.hpp"

#include <algorithm>
#include <set>

#include "casmap/core/input_error.hpp"
#include "casmap/core/text.hpp"

namespace casmap::pipeline {
namespace {

using mapper::FilterMethod;

std::string NameList() {
    std::string list;
    for (const PipelineSpec& p : AllPipelines()) {
        list += (list.empty() ? "" : ", ") + p.name;
    }
    return list;
}

std::size_t OrderOf(const std::string& name) {
    const std::vector<PipelineSpec>& all = AllPipelines();
    for (std::size_t i = 0; i < all.size(); ++i) {
        if (all[i].name == name) {
            return i;
        }
    }
    return all.size();
}

}  // namespace

const std::vector<PipelineSpec>& AllPipelines() {
    constexpr MapperMode kPaper = MapperMode::kPaper;
    constexpr MapperMode kKalman = MapperMode::kKalman;
    constexpr MapperMode kConsensus = MapperMode::kConsensus;
    constexpr Prefilter kNone = Prefilter::kNone;
    constexpr Prefilter kShadow = Prefilter::kShadow;
    constexpr Prefilter kJump = Prefilter::kRangeJump;
    constexpr Prefilter kSweep = Prefilter::kSweepJump;
    static const std::vector<PipelineSpec> all = {
        {"cas", kPaper, kNone, FilterMethod::kCas, "Eq. 1-6 map, CAS filter (Eq. 7-10)"},
        {"wiener", kPaper, kNone, FilterMethod::kWiener, "Eq. 1-6 map, 5 x 5 Wiener filter"},
        {"average", kPaper, kNone, FilterMethod::kAverage, "Eq. 1-6 map, 5 x 5 mean"},
        {"median", kPaper, kNone, FilterMethod::kMedian, "Eq. 1-6 map, 5 x 5 median"},
        {"cwm", kPaper, kNone, FilterMethod::kCwm, "Eq. 1-6 map, centre-weighted median"},
        {"raw", kPaper, kNone, std::nullopt, "Eq. 1-6 map, no filter"},
        {"cas_terrain", kPaper, kNone, FilterMethod::kCasTerrain,
         "Eq. 1-6 map, CAS on heights relative to a local ground estimate"},
        {"cas_trail", kPaper, kNone, FilterMethod::kCasTrail,
         "Eq. 1-6 map, CAS that also removes low-certainty cells without same-height support"},
        {"cas_median", kPaper, kNone, FilterMethod::kCasMedian,
         "Eq. 1-6 map, cas_trail's objects at their height, 5 x 5 median elsewhere"},
        {"cas_edge", kPaper, kNone, FilterMethod::kCasEdge,
         "Eq. 1-6 map, median of cas_trail's map; objects and box edges at their height"},
        {"cas_hybrid", kPaper, kNone, FilterMethod::kCasHybrid,
         "cas_edge, plus cas_median's surface median for the cells cas_edge leaves at the median"},
        {"kalman", kKalman, kNone, std::nullopt,
         "Kalman fusion of each scan's lowest point per cell (Fankhauser et al.), no filter"},
        {"kalman_median", kKalman, kNone, FilterMethod::kMedian, "Kalman map, 5 x 5 median"},
        {"shadow", kPaper, kShadow, std::nullopt, "shadow-point scan filter, Eq. 1-6 map"},
        {"shadow_cas", kPaper, kShadow, FilterMethod::kCas,
         "shadow-point scan filter, Eq. 1-6 map, CAS"},
        {"range_jump", kPaper, kJump, std::nullopt, "range-jump scan filter, Eq. 1-6 map"},
        {"range_jump_cas", kPaper, kJump, FilterMethod::kCas,
         "range-jump scan filter, Eq. 1-6 map, CAS"},
        {"range_jump_cas_terrain", kPaper, kJump, FilterMethod::kCasTerrain,
         "range-jump scan filter, Eq. 1-6 map, cas_terrain"},
        {"range_jump_median", kPaper, kJump, FilterMethod::kMedian,
         "range-jump scan filter, Eq. 1-6 map, 5 x 5 median"},
        {"sweep_jump", kPaper, kSweep, std::nullopt,
         "sweep-jump scan filter (mixed pixels across consecutive scans), Eq. 1-6 map"},
        {"sweep_jump_cas", kPaper, kSweep, FilterMethod::kCas,
         "sweep-jump scan filter, Eq. 1-6 map, CAS"},
        {"sweep_jump_median", kPaper, kSweep, FilterMethod::kMedian,
         "sweep-jump scan filter, Eq. 1-6 map, 5 x 5 median"},
        {"sweep_jump_hybrid", kPaper, kSweep, FilterMethod::kCasHybrid,
         "sweep-jump scan filter, Eq. 1-6 map, cas_hybrid"},
        {"consensus", kConsensus, kNone, std::nullopt,
         "Eq. 1-5 map with the consensus cell height (mean where a cell's heights agree)"},
        {"consensus_median", kConsensus, kNone, FilterMethod::kMedian,
         "consensus map, 5 x 5 median"},
        {"consensus_hybrid", kConsensus, kNone, FilterMethod::kCasHybrid,
         "consensus map, cas_hybrid"},
        {"sweep_jump_consensus_hybrid", kConsensus, kSweep, FilterMethod::kCasHybrid,
         "sweep-jump scan filter, consensus map, cas_hybrid"},
    };
    return all;
}

std::vector<std::string> PaperPipelineNames() {
    return {"cas", "wiener", "average", "median", "cwm"};
}

std::vector<std::string> AllPipelineNames() {
    std::vector<std::string> names;
    for (const PipelineSpec& p : AllPipelines()) {
        names.push_back(p.name);
    }
    return names;
}

const PipelineSpec& FindPipeline(std::string_view name, const std::string& field) {
    for (const PipelineSpec& p : AllPipelines()) {
        if (p.name == name) {
            return p;
        }
    }
    throw MakeInputError("", field, std::string(name), "allowed: all or a list of " + NameList());
}

std::vector<std::string> ParsePipelines(const std::string& text, const std::string& field) {
    if (text == "all") {
        return AllPipelineNames();
    }
    std::set<std::string> given;
    for (const std::string& part : core::SplitList(text)) {
        given.insert(FindPipeline(part, field).name);
    }
    if (given.empty()) {
        throw MakeInputError("", field, text, "allowed: all or a list of " + NameList());
    }
    return InPipelineOrder({given.begin(), given.end()});
}

void CheckPipelines(const std::vector<std::string>& names) {
    std::set<std::string> seen;
    for (const std::string& n : names) {
        (void)FindPipeline(n, "pipelines");
        if (!seen.insert(n).second) {
            throw MakeInputError("", "pipelines", n, "each pipeline at most once");
        }
    }
    if (names.empty()) {
        throw MakeInputError("", "pipelines", "", "at least one pipeline");
    }
}

std::vector<std::string> InPipelineOrder(std::vector<std::string> names) {
    std::stable_sort(names.begin(), names.end(), [](const std::string& a, const std::string& b) {
        const std::size_t oa = OrderOf(a);
        const std::size_t ob = OrderOf(b);
        return oa != ob ? oa < ob : a < b;
    });
    return names;
}

}  // namespace casmap::pipeline
