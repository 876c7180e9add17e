// casmap demo [--seed N] [--set NAME=VALUE]... [--out DIR] [--threads N]
// Builds the synthetic elevation/certainty pair with exact truth (mapper/synthetic_map.hpp: a
// floor with three of the paper's parallelepipeds, its cylinder, nine thin poles, holes,
// mixed-pixel streaks and spikes), runs all five filters and prints the PI table (Eq. 11 over
// the paper's 200 x 80 region) with RMSE, surviving spikes, filled-cell and edge errors and
// CAS's Table II shares. With --out, writes every map as 32-bit float TIFF + colour PNG.
#include <cstdio>
#include <memory>
#include <string>
#include <vector>

#include "apps/casmap/commands.hpp"
#include "apps/casmap/flag_names.hpp"
#include "casmap/pipeline/demo.hpp"

namespace casmap::app {
namespace {

struct DemoOptions {
    unsigned long long seed = 1;
    std::vector<std::string> sets;
    std::string out;
};

void PrintTable(const pipeline::DemoResult& r, unsigned long long seed) {
    const mapper::Region& region = r.region;
    std::printf(
        "casmap demo: synthetic %d x %d map, seed %llu, PI region rows %d..%d, cols %d..%d\n",
        r.map.truth.rows, r.map.truth.cols, seed, region.row0, region.row0 + region.rows - 1,
        region.col0, region.col0 + region.cols - 1);
    std::printf("%-8s %8s %10s %7s %13s %12s\n", "filter", "PI", "RMSE_m", "spikes",
                "filled_RMSE_m", "edge_RMSE_m");
    for (std::size_t m = 0; m < r.methods.size(); ++m) {
        const mapper::FilterMetrics& x = r.metrics[m];
        std::printf("%-8s %8.4f %10.5f %7lld %13.5f %12.5f\n",
                    std::string(mapper::ToString(r.methods[m])).c_str(), x.pi, x.rmse_m,
                    static_cast<long long>(x.spikes), x.filled_rmse_m, x.edge_rmse_m);
        if (m == 0) {
            std::printf("%-8s %8.4f %10.5f %7lld\n", "(raw)", 1.0, x.raw_rmse_m,
                        static_cast<long long>(x.raw_spikes));
        }
    }
    const mapper::ClassReport& c = r.cas_classes;
    std::printf(
        "cas classes over %lld processed cells: removed %.1f %%, filled %.1f %%, "
        "untouched %.1f %%\n",
        static_cast<long long>(c.all.cells), c.all.removed_pct, c.all.filled_pct,
        c.all.untouched_pct);
    std::printf(
        "  without never-observed cells (%lld): removed %.1f %%, filled %.1f %%, "
        "untouched %.1f %%\n",
        static_cast<long long>(c.observed.cells), c.observed.removed_pct, c.observed.filled_pct,
        c.observed.untouched_pct);
}

void RunDemo(const DemoOptions& opt, const CommonOptions& common) {
    pipeline::DemoOptions options;
    options.seed = opt.seed;
    WithSetFlag([&] {
        for (const std::string& s : opt.sets) {
            options.params.SetAssignment(s);
        }
        options.params.Validate();
    });
    const pipeline::DemoResult r = pipeline::RunDemo(options, common.threads);
    PrintTable(r, opt.seed);
    if (!opt.out.empty()) {
        pipeline::WriteDemoMaps(r, opt.out);
        std::printf("wrote maps to %s\n", opt.out.c_str());
    }
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
