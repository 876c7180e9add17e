// casmap map RUN.h5 [--out DIR] [--grid X0,Y0,CELL_M,ROWS,COLS] [--mapper paper|kalman|consensus]
//                  [--unknown zero|nan] [--prefilter none|shadow|range_jump|sweep_jump]
//                  [--set shadow.<f>=V | range_jump.<f>=V | sweep_jump.<f>=V | kalman.<f>=V |
//                   consensus.<f>=V ...]
// Builds the elevation and certainty maps (Eq. 1-6, or the Kalman mapper) of a run file,
// simulated or recorded (the truth labels are never read), and writes them as float TIFF +
// colour PNG into DIR and as /maps/elevation_m and /maps/certainty into the run file: flags ->
// pipeline::MapRunFileOptions -> pipeline::MapRunFile (pipeline/map_file.hpp) -> one line.
#include <cstdio>
#include <string>
#include <vector>

#include "apps/casmap/commands.hpp"
#include "apps/casmap/flag_names.hpp"
#include "casmap/mapper/unknown.hpp"
#include "casmap/pipeline/map_file.hpp"

namespace casmap::app {
namespace {

struct MapOptions {
    std::string run;
    std::string out;
    std::string grid;
    std::string mapper = "paper";
    std::string unknown = "zero";
    std::string prefilter = "none";
    std::vector<std::string> set;  // mapping-stage parameters (pre-filter, Kalman mapper)
};

pipeline::MapSettings ParseMapSettings(const MapOptions& opt) {
    pipeline::MapSettings settings;
    settings.mode = pipeline::ParseMapperMode(opt.mapper, "--mapper");
    settings.unknown = mapper::ParseUnknown(opt.unknown, "command line", "--unknown");
    settings.prefilter = pipeline::ParsePrefilter(opt.prefilter, "--prefilter");
    WithSetFlag([&] {  // FilterParams names its settings list "filter parameters"
        WithSetFlag(
            [&] { pipeline::ApplyStageSettings(settings, opt.set, "--set"); });  // validates
    });
    return settings;
}

void RunMap(const MapOptions& opt) {
    pipeline::MapRunFileOptions o;
    o.run = opt.run;
    o.out = opt.out;
    o.settings = ParseMapSettings(opt);  // bad flags exit 2 first
    if (!opt.grid.empty()) {
        o.grid = pipeline::ParseGrid(opt.grid, "--grid");
    }
    pipeline::MapRunFileResult r;
    WithCommandLineFlags({{"grid", "--grid"}, {"out", "--out"}},
                         [&] { r = pipeline::MapRunFile(o); },
                         {{"grid", opt.run}, {"out", opt.out}});
    std::printf("mapped %llu of %llu beams onto %d x %d cells -> %s and %s\n",
                static_cast<unsigned long long>(r.mapped.stats.beams_mapped),
                static_cast<unsigned long long>(r.mapped.stats.beams_seen), r.grid.rows,
                r.grid.cols, r.out_dir.string().c_str(), opt.run.c_str());
}

}  // namespace

void AddMapCommand(CLI::App& app, CommonOptions& common) {
    auto opt = std::make_shared<MapOptions>();
    CLI::App* sub = app.add_subcommand(
        "map", "Elevation and certainty maps of a run file (TIFF + PNG, and into the run file)");
    sub->add_option("run", opt->run, "run file (HDF5)")->required();
    sub->add_option("--out", opt->out, "output directory (default: <run>_maps beside the run)");
    sub->add_option("--grid", opt->grid,
                    "X0,Y0,CELL_M,ROWS,COLS (default: the run's grid, else the beams' extent)");
    sub->add_option("--mapper", opt->mapper,
                    "paper (Eq. 1-6) | kalman (Kalman fusion of each scan's lowest point) | "
                    "consensus (Eq. 1-5, the mean of a cell whose heights agree)")
        ->capture_default_str();
    sub->add_option("--unknown", opt->unknown,
                    "never-observed cells: zero (the paper) | nan (grid_map convention)")
        ->capture_default_str();
    sub->add_option("--prefilter", opt->prefilter,
                    "scan pre-filter before mapping: none | shadow | range_jump | sweep_jump")
        ->capture_default_str();
    sub->add_option("--set", opt->set,
                    "NAME=VALUE of the pre-filter run (shadow.<field>, range_jump.<field>, "
                    "sweep_jump.<field>) or of the mapper mode run (kalman.<field>, "
                    "consensus.<field>); repeatable (docs/commands/map.md)");
    AddThreadsOption(sub, common);
    sub->callback([opt] { RunMap(*opt); });
}

}  // namespace casmap::app
