// casmap filter --method METHOD (cas|wiener|average|median|cwm|cas_terrain|cas_trail|
//               cas_median|cas_edge|cas_hybrid) --elevation H.tiff [--certainty C.tiff]
//               [--preset NAME] [--set NAME=VALUE]... --out OUT.tiff [--threads N]
// Filters an elevation map (32-bit float TIFF, metres) with one of the paper's five filters and
// writes OUT.tiff (32-bit float), OUT.png (colour, legend) and, for cas, OUT_classes.tiff
// (PixelClass codes as floats: 0 untouched, 1 removed, 2 filled, 3 unprocessed border) and
// OUT_classes.png. Everything is computed before the first file is written; each file is
// written atomically. The filters are single-threaded; --threads changes nothing.
#include <cstdio>
#include <memory>
#include <string>
#include <vector>

#include "apps/casmap/commands.hpp"
#include "apps/casmap/flag_names.hpp"
#include "casmap/pipeline/filter_file.hpp"
#include "casmap/pipeline/preset.hpp"

namespace casmap::app {
namespace {

struct FilterOptions {
    std::string method;
    std::string elevation;
    std::string certainty;
    std::string out;
    std::string preset;
    std::vector<std::string> sets;
};

void RunFilterCommand(const FilterOptions& opt) {
    pipeline::FilterFileOptions options{opt.method, opt.elevation, opt.certainty, opt.out, {}};
    if (!opt.preset.empty()) {  // a preset first, --set overrides it
        const pipeline::Preset preset = pipeline::LoadPreset(opt.preset, "--preset");
        for (const std::string& s : preset.settings) {
            options.params.SetAssignment(s);
        }
        // Then the preset's section for the pipeline of the same name (cas_edge, cas_hybrid,
        // ...), as casmap bench applies it to that pipeline.
        const auto section = preset.pipeline_settings.find(opt.method);
        if (section != preset.pipeline_settings.end()) {
            for (const std::string& s : section->second) {
                options.params.SetAssignment(s);
            }
        }
    }
    WithSetFlag([&] {
        for (const std::string& s : opt.sets) {
            options.params.SetAssignment(s);
        }
        options.params.Validate();
    });
    pipeline::FilterFileResult r;
    WithFlagNames({{"method", "--method"}, {"out", "--out"}, {"certainty", "--certainty"}},
                  [&] { r = pipeline::FilterMapFiles(options); });
    if (r.classes) {
        // Labelled with the method: the variants print their own A, G and classes (the
        // median-based ones cas_trail's, which they keep as their classes).
        const bool trail_classes =
            opt.method == "cas_median" || opt.method == "cas_edge" || opt.method == "cas_hybrid";
        const std::string label = opt.method + (trail_classes ? " (cas_trail's classes)" : "");
        const mapper::ClassReport& c = *r.classes;
        std::printf(
            "%s: A = %g, G = %g; of %lld processed cells: removed %.1f %%, filled %.1f %%, "
            "untouched %.1f %% (without never-observed: %.1f / %.1f / %.1f %%)\n",
            label.c_str(), options.params.cas.EffectiveA(), options.params.cas.EffectiveG(),
            static_cast<long long>(c.all.cells), c.all.removed_pct, c.all.filled_pct,
            c.all.untouched_pct, c.observed.removed_pct, c.observed.filled_pct,
            c.observed.untouched_pct);
    }
    std::printf("wrote %s\n", opt.out.c_str());
}

}  // namespace

void AddFilterCommand(CLI::App& app, CommonOptions& common) {
    auto opt = std::make_shared<FilterOptions>();
    CLI::App* sub =
        app.add_subcommand("filter", "Filter an elevation map: CAS (Eq. 7-10) or a 5x5 baseline");
    sub->add_option(
           "--method", opt->method,
           "cas|wiener|average|median|cwm|cas_terrain|cas_trail|cas_median|cas_edge|cas_hybrid")
        ->required();
    sub->add_option("--elevation", opt->elevation, "elevation map H, 32-bit float TIFF (m)")
        ->required();
    sub->add_option("--certainty", opt->certainty,
                    "certainty map C, 32-bit float TIFF (counts); required for cas");
    sub->add_option("--preset", opt->preset,
                    "filter-parameter preset: config/presets/NAME.yaml (paper, tuned) or a file");
    sub->add_option("--set", opt->sets,
                    "filter parameter NAME=VALUE (repeatable; overrides --preset)");
    sub->add_option("--out", opt->out,
                    "output OUT.tiff (also OUT.png; OUT_classes.* for the cas methods)")
        ->required();
    AddThreadsOption(sub, common);
    sub->callback([opt] { RunFilterCommand(*opt); });
}

}  // namespace casmap::app
