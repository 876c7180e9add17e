// casmap filter --method METHOD (cas|wiener|average|median|cwm|cas_terrain|cas_trail|
//               cas_median|cas_edge|cas_hybrid) --elevation H.tiff [--certainty C.tiff]
//               [--preset NAME] [--set NAME=VALUE]... --out OUT.tiff [--threads N]
// Filters an elevation map (32-bit float TIFF, metres) with one of the paper's five filters and
// writes OUT.tiff (32-bit float), OUT.png (colour, legend) and, for cas, OUT_classes.tiff
// (PixelClass codes as floats: 0 untouched, 1 removed, 2 filled, 3 unprocessed border) and
// OUT_classes.png. Everything is computed before the first file is written; each file is
// written atomically. The filters are single-threaded; --threads changes nothing.
#include <cstdio>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "apps/casmap/commands.hpp"
#include "apps/casmap/flag_names.hpp"
#include "casmap/core/input_error.hpp"
#include "casmap/io/image.hpp"
#include "casmap/mapper/filter_inputs.hpp"
#include "casmap/mapper/filters.hpp"
#include "casmap/mapper/metrics.hpp"
#include "casmap/pipeline/preset.hpp"

namespace casmap::app {
namespace {
namespace fs = std::filesystem;

struct FilterOptions {
    std::string method;
    std::string elevation;
    std::string certainty;
    std::string out;
    std::string preset;
    std::vector<std::string> sets;
};

fs::path Beside(const fs::path& out, const std::string& suffix, const std::string& ext) {
    return out.parent_path() / (out.stem().string() + suffix + ext);
}

const std::vector<io::ClassLegendEntry>& ClassLegend() {
    static const std::vector<io::ClassLegendEntry> legend = {
        {"untouched", 200, 200, 200},
        {"removed", 40, 40, 220},
        {"filled", 220, 120, 30},
        {"border", 90, 90, 90},
    };
    return legend;
}

void RunFilterCommand(const FilterOptions& opt) {
    const mapper::FilterMethod method = mapper::ParseFilterMethod(opt.method, "--method");
    mapper::FilterParams params;
    if (!opt.preset.empty()) {  // a preset first, --set overrides it
        const pipeline::Preset preset = pipeline::LoadPreset(opt.preset, "--preset");
        for (const std::string& s : preset.settings) {
            params.SetAssignment(s);
        }
        // Then the preset's section for the pipeline of the same name (cas_edge, cas_hybrid,
        // ...), as casmap bench applies it to that pipeline.
        const auto section = preset.pipeline_settings.find(std::string(mapper::ToString(method)));
        if (section != preset.pipeline_settings.end()) {
            for (const std::string& s : section->second) {
                params.SetAssignment(s);
            }
        }
    }
    WithSetFlag([&] {
        for (const std::string& s : opt.sets) {
            params.SetAssignment(s);
        }
        params.Validate();
    });
    const fs::path out(opt.out);
    const std::string ext = out.extension().string();
    if (ext != ".tiff" && ext != ".tif") {
        throw MakeInputError("", "--out", opt.out, "must end in .tiff or .tif");
    }
    const fs::path dir = out.has_parent_path() ? out.parent_path() : fs::path(".");
    if (!fs::is_directory(dir)) {
        throw MakeInputError("", "--out", opt.out, "directory " + dir.string() + " does not exist");
    }
    const bool cas = mapper::NeedsCertainty(method);
    if (cas && opt.certainty.empty()) {  // before reading any map
        mapper::CheckFilterInputs(method, {}, {}, params);
    }
    const core::MapF elevation = io::ReadMapTiff(opt.elevation);
    const core::MapF certainty =
        opt.certainty.empty() ? core::MapF() : io::ReadMapTiff(opt.certainty);
    mapper::CheckFilterInputs(method, elevation, certainty, params, {opt.elevation, opt.certainty});

    const mapper::FilterResult result = mapper::RunFilter(method, elevation, certainty, params);
    core::Raster<std::uint8_t> unknown;
    if (!certainty.data.empty()) {
        unknown = core::Raster<std::uint8_t>(certainty.rows, certainty.cols, 0);
        for (std::size_t i = 0; i < certainty.data.size(); ++i) {
            unknown.data[i] = certainty.data[i] == 0.0F && result.elevation.data[i] == 0.0F;
        }
    }
    io::PngStyle style;
    style.title = "casmap filter --method " + opt.method;
    style.unknown = unknown.data.empty() ? nullptr : &unknown;

    io::WriteMapTiff(out, result.elevation);
    io::WriteMapPng(Beside(out, "", ".png"), result.elevation, style);
    if (cas) {
        core::MapF codes(result.classes.rows, result.classes.cols);
        for (std::size_t i = 0; i < codes.data.size(); ++i) {
            codes.data[i] = static_cast<float>(result.classes.data[i]);
        }
        io::WriteMapTiff(Beside(out, "_classes", ".tiff"), codes);
        io::WriteClassesPng(Beside(out, "_classes", ".png"), result.classes, ClassLegend(),
                            "CAS classes (Eq. 7)");
        const mapper::ClassReport r = mapper::ClassPercentages(result.classes, certainty);
        std::printf(
            "cas: A = %g, G = %g; of %lld processed cells: removed %.1f %%, filled %.1f %%, "
            "untouched %.1f %% (without never-observed: %.1f / %.1f / %.1f %%)\n",
            params.cas.EffectiveA(), params.cas.EffectiveG(), static_cast<long long>(r.all.cells),
            r.all.removed_pct, r.all.filled_pct, r.all.untouched_pct, r.observed.removed_pct,
            r.observed.filled_pct, r.observed.untouched_pct);
    }
    std::printf("wrote %s\n", out.string().c_str());
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
    sub->add_option("--out", opt->out, "output OUT.tiff (also OUT.png; OUT_classes.* for cas)")
        ->required();
    AddThreadsOption(sub, common);
    sub->callback([opt] {
        WithFlagNames({{"certainty", "--certainty"}}, [&] { RunFilterCommand(*opt); });
    });
}

}  // namespace casmap::app
