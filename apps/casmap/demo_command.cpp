// casmap demo [--seed N] [--set NAME=VALUE]... [--out DIR] [--threads N]
// Builds the synthetic elevation/certainty pair with exact truth (mapper/synthetic_map.hpp: a
// floor with three of the paper's parallelepipeds, its cylinder, nine thin poles, holes,
// mixed-pixel streaks and spikes), runs all five filters and prints the PI table (Eq. 11 over
// the paper's 200 x 80 region) with RMSE, surviving spikes, filled-cell and edge errors and
// CAS's Table II shares. With --out, writes every map as 32-bit float TIFF + colour PNG.
#include <cstdio>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "apps/casmap/commands.hpp"
#include "apps/casmap/flag_names.hpp"
#include "casmap/core/parallel.hpp"
#include "casmap/io/atomic_file.hpp"
#include "casmap/io/image.hpp"
#include "casmap/mapper/filters.hpp"
#include "casmap/mapper/metrics.hpp"
#include "casmap/mapper/synthetic_map.hpp"
#include "casmap/pipeline/map_run.hpp"

namespace casmap::app {
namespace {
namespace fs = std::filesystem;

struct DemoOptions {
    unsigned long long seed = 1;
    std::vector<std::string> sets;
    std::string out;
};

void RunDemo(const DemoOptions& opt, const CommonOptions& common) {
    mapper::FilterParams params;
    WithSetFlag([&] {
        for (const std::string& s : opt.sets) {
            params.SetAssignment(s);
        }
        params.Validate();
    });
    mapper::SyntheticMapConfig cfg;
    cfg.seed = opt.seed;
    cfg.a = params.cas.a;
    const mapper::SyntheticMap map = mapper::BuildSyntheticMap(cfg);
    const std::vector<mapper::FilterMethod>& methods = mapper::AllFilterMethods();
    std::vector<mapper::FilterResult> results(methods.size());
    // One filter per item; each writes only its own slot, so threads change nothing.
    core::ParallelFor(methods.size(), common.threads, [&](std::size_t m) {
        results[m] = mapper::RunFilter(methods[m], map.elevation, map.certainty, params);
    });
    const mapper::Region region = mapper::PaperRegion(map.truth.rows, map.truth.cols);
    std::printf(
        "casmap demo: synthetic %d x %d map, seed %llu, PI region rows %d..%d, cols %d..%d\n",
        map.truth.rows, map.truth.cols, opt.seed, region.row0, region.row0 + region.rows - 1,
        region.col0, region.col0 + region.cols - 1);
    std::printf("%-8s %8s %10s %7s %13s %12s\n", "filter", "PI", "RMSE_m", "spikes",
                "filled_RMSE_m", "edge_RMSE_m");
    for (std::size_t m = 0; m < methods.size(); ++m) {
        const mapper::FilterMetrics x =
            mapper::EvaluateFilter(results[m], map.elevation, map.truth, region);
        std::printf("%-8s %8.4f %10.5f %7lld %13.5f %12.5f\n",
                    std::string(mapper::ToString(methods[m])).c_str(), x.pi, x.rmse_m,
                    static_cast<long long>(x.spikes), x.filled_rmse_m, x.edge_rmse_m);
        if (m == 0) {
            std::printf("%-8s %8.4f %10.5f %7lld\n", "(raw)", 1.0, x.raw_rmse_m,
                        static_cast<long long>(x.raw_spikes));
        }
    }
    const mapper::ClassReport r = mapper::ClassPercentages(results[0].classes, map.certainty);
    std::printf(
        "cas classes over %lld processed cells: removed %.1f %%, filled %.1f %%, "
        "untouched %.1f %%\n",
        static_cast<long long>(r.all.cells), r.all.removed_pct, r.all.filled_pct,
        r.all.untouched_pct);
    std::printf(
        "  without never-observed cells (%lld): removed %.1f %%, filled %.1f %%, "
        "untouched %.1f %%\n",
        static_cast<long long>(r.observed.cells), r.observed.removed_pct, r.observed.filled_pct,
        r.observed.untouched_pct);
    if (opt.out.empty()) {
        return;
    }
    const fs::path dir(opt.out);
    io::EnsureDirectory(dir);
    core::Raster<std::uint8_t> unknown(map.certainty.rows, map.certainty.cols, 0);
    for (std::size_t i = 0; i < unknown.data.size(); ++i) {
        unknown.data[i] = map.certainty.data[i] == 0.0F ? 1 : 0;
    }
    pipeline::WriteMapFiles(dir, "elevation", map.elevation, "raw elevation H", "m", &unknown);
    pipeline::WriteMapFiles(dir, "certainty", map.certainty, "certainty C", "counts", &unknown);
    pipeline::WriteMapFiles(dir, "truth", map.truth, "ground truth", "m", nullptr);
    for (std::size_t m = 0; m < methods.size(); ++m) {
        const std::string name(mapper::ToString(methods[m]));
        pipeline::WriteMapFiles(dir, "filtered_" + name, results[m].elevation, "filtered: " + name,
                                "m", nullptr);
    }
    io::WriteClassesPng(dir / "cas_classes.png", results[0].classes,
                        {{"untouched", 200, 200, 200},
                         {"removed", 40, 40, 220},
                         {"filled", 220, 120, 30},
                         {"border", 90, 90, 90}},
                        "CAS classes (Eq. 7)");
    std::printf("wrote maps to %s\n", dir.string().c_str());
}

}  // namespace

void AddDemoCommand(CLI::App& app, CommonOptions& common) {
    auto opt = std::make_shared<DemoOptions>();
    CLI::App* sub = app.add_subcommand(
        "demo", "All five filters on a synthetic map pair with exact truth: the PI table");
    sub->add_option("--seed", opt->seed, "seed of the synthetic map");
    sub->add_option("--set", opt->sets, "filter parameter NAME=VALUE (repeatable)");
    sub->add_option("--out", opt->out, "directory for TIFF + PNG maps");
    AddThreadsOption(sub, common);
    sub->callback([opt, &common] { RunDemo(*opt, common); });
}

}  // namespace casmap::app
