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

namespace {

using namespace casmap;

struct Setting {
    std::string name;
    bool shadow = false;
    mapper::ShadowFilterConfig shadow_config;
    mapper::RangeJumpConfig jump_config;
};

std::vector<Setting> Settings() {
    std::vector<Setting> out;
    for (const double deg : {5.0, 10.0, 15.0}) {
        Setting s{"shadow min_angle_deg=" + std::to_string(static_cast<int>(deg)), true, {}, {}};
        s.shadow_config.min_angle_deg = deg;
        s.shadow_config.max_angle_deg = 180.0 - deg;
        out.push_back(s);
    }
    for (const double jump : {0.05, 0.1, 0.2, 0.4}) {
        Setting s{"range_jump jump_min_m=" + std::to_string(jump).substr(0, 4), false, {}, {}};
        s.jump_config.jump_min_m = jump;
        s.jump_config.margin_m = std::min(0.03, 0.4 * jump);
        out.push_back(s);
    }
    for (const double chord : {0.02, 0.1}) {
        Setting s{"range_jump chord_tol_m=" + std::to_string(chord).substr(0, 4), false, {}, {}};
        s.jump_config.chord_tol_m = chord;
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
                for (std::size_t k = 0; k < run.scans.size(); ++k) {
                    const std::vector<std::uint8_t> keep =
                        s.shadow ? mapper::ShadowFilterLabels(run.scans[k], s.shadow_config)
                                 : mapper::RangeJumpLabels(run.scans[k], s.jump_config);
                    score.Add(run.scans[k], keep, run.truth[k].labels);
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
