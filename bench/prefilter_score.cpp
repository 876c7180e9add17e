// Precision and recall of the scan pre-filters' mixed-pixel removal (mapper/scan_filters.hpp)
// against the simulator's per-beam truth labels, over simulated run files:
//   build/bench/prefilter_score RUN.h5...
// Prints one line per filter setting with the pooled counts of all runs given.
#include <algorithm>
#include <cstdio>
#include <exception>
#include <string>
#include <vector>

#include "casmap/io/run_file.hpp"
#include "casmap/mapper/scan_filters.hpp"
#include "casmap/mapper/sweep_jump.hpp"

namespace {

using namespace casmap;

enum class Kind { kShadow, kRangeJump, kSweepJump };

struct Setting {
    std::string name;
    Kind kind = Kind::kRangeJump;
    mapper::ShadowFilterConfig shadow_config;
    mapper::RangeJumpConfig jump_config;
    mapper::SweepJumpConfig sweep_config;
};

// Keep labels of every scan of `run` for setting `s`.
std::vector<std::vector<std::uint8_t>> RunLabels(const Setting& s, const io::RunData& run) {
    if (s.kind == Kind::kSweepJump) {
        return mapper::SweepJumpLabels(run.scans, run.poses, s.sweep_config);
    }
    std::vector<std::vector<std::uint8_t>> keep;
    for (const core::Scan& scan : run.scans) {
        keep.push_back(s.kind == Kind::kShadow ? mapper::ShadowFilterLabels(scan, s.shadow_config)
                                               : mapper::RangeJumpLabels(scan, s.jump_config));
    }
    return keep;
}

std::vector<Setting> Settings() {
    std::vector<Setting> out;
    for (const double deg : {5.0, 10.0, 15.0}) {
        Setting s{"shadow min_angle_deg=" + std::to_string(static_cast<int>(deg)), Kind::kShadow};
        s.shadow_config.min_angle_deg = deg;
        s.shadow_config.max_angle_deg = 180.0 - deg;
        out.push_back(s);
    }
    for (const double jump : {0.05, 0.1, 0.2, 0.4}) {
        Setting s{"range_jump jump_min_m=" + std::to_string(jump).substr(0, 4)};
        s.jump_config.jump_min_m = jump;
        s.jump_config.margin_m = std::min(0.03, 0.4 * jump);
        out.push_back(s);
    }
    for (const double chord : {0.02, 0.1}) {
        Setting s{"range_jump chord_tol_m=" + std::to_string(chord).substr(0, 4)};
        s.jump_config.chord_tol_m = chord;
        out.push_back(s);
    }
    for (const double deg : {5.0, 10.0, 15.0, 89.0}) {
        Setting s{"sweep_jump max_angle_deg=" + std::to_string(static_cast<int>(deg)),
                  Kind::kSweepJump};
        s.sweep_config.max_angle_deg = deg;
        out.push_back(s);
    }
    for (const double share : {0.0, 0.25, 0.5}) {
        Setting s{"sweep_jump depression_share=" + std::to_string(share).substr(0, 4),
                  Kind::kSweepJump};
        s.sweep_config.depression_share = share;
        out.push_back(s);
    }
    for (const int reach : {2, 3}) {
        Setting s{"sweep_jump reach=" + std::to_string(reach), Kind::kSweepJump};
        s.sweep_config.reach = reach;
        out.push_back(s);
    }
    for (const double margin : {0.03, 0.07}) {
        Setting s{"sweep_jump margin_m=" + std::to_string(margin).substr(0, 4), Kind::kSweepJump};
        s.sweep_config.margin_m = margin;
        s.sweep_config.jump_min_m = std::max(0.1, 2.5 * margin);
        out.push_back(s);
    }
    return out;
}

}  // namespace

int main(int argc, char** argv) {
    if (argc < 2) {
        std::fprintf(stderr, "usage: prefilter_score RUN.h5...\n");
        return 2;
    }
    try {
        std::vector<io::RunData> runs;
        for (int a = 1; a < argc; ++a) {
            runs.push_back(io::ReadRunFile(argv[a]));
            if (runs.back().truth.size() != runs.back().scans.size()) {
                std::fprintf(stderr, "%s: /scans/labels: needs a simulated run\n", argv[a]);
                return 2;
            }
        }
        std::printf("%-28s %9s %9s %9s %9s %9s\n", "filter", "tp", "fp", "fn", "precision",
                    "recall");
        for (const Setting& s : Settings()) {
            mapper::RemovalScore score;
            for (const io::RunData& run : runs) {
                const std::vector<std::vector<std::uint8_t>> keep = RunLabels(s, run);
                for (std::size_t k = 0; k < run.scans.size(); ++k) {
                    score.Add(run.scans[k], keep[k], run.truth[k].labels);
                }
            }
            std::printf("%-28s %9lld %9lld %9lld %9.3f %9.3f\n", s.name.c_str(),
                        static_cast<long long>(score.true_pos),
                        static_cast<long long>(score.false_pos),
                        static_cast<long long>(score.false_neg), score.Precision(), score.Recall());
        }
    } catch (const std::exception& e) {
        std::fprintf(stderr, "%s\n", e.what());
        return 2;
    }
    return 0;
}
