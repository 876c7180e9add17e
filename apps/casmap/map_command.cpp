// casmap map RUN.h5 [--out DIR] [--grid X0,Y0,CELL_M,ROWS,COLS] [--mapper paper|kalman]
//                  [--unknown zero|nan] [--prefilter none|shadow|range_jump]
//                  [--set shadow.<f>=V | range_jump.<f>=V | kalman.<f>=V ...]
// Builds the elevation and certainty maps (Eq. 1-6, or the Kalman mapper) of a run file,
// simulated or recorded (the truth labels are never read), and writes them as float TIFF +
// colour PNG into DIR and as /maps/elevation_m and /maps/certainty into the run file.
#include <cstdio>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "apps/casmap/commands.hpp"
#include "apps/casmap/flag_names.hpp"
#include "casmap/core/input_error.hpp"
#include "casmap/io/atomic_file.hpp"
#include "casmap/io/image.hpp"
#include "casmap/io/output_set.hpp"
#include "casmap/io/run_file.hpp"
#include "casmap/mapper/unknown.hpp"
#include "casmap/pipeline/map_run.hpp"

namespace casmap::app {
namespace {
namespace fs = std::filesystem;

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
        pipeline::ApplyStageSettings(settings, opt.set, "--set");  // validates
    });
    return settings;
}

/// The grid: --grid, else the run's own (written with its ground truth), else the beams' extent.
core::GridGeometry ChooseGrid(const MapOptions& opt, const io::RunData& run) {
    if (!opt.grid.empty()) {
        const core::GridGeometry grid = pipeline::ParseGrid(opt.grid, "--grid");
        if (run.maps.grid && !(*run.maps.grid == grid)) {
            throw MakeInputError(opt.run, "--grid", opt.grid,
                                 "differs from the grid stored in the run file " +
                                     pipeline::GridYaml(*run.maps.grid) +
                                     "; its maps share one grid");
        }
        return grid;
    }
    if (run.maps.grid) {
        return *run.maps.grid;
    }
    return pipeline::GridCoveringBeams(run.scans, run.poses, 0.025, opt.run);
}

// The TIFF and PNG of one layer, written to the temporaries of `outputs`.
struct LayerFiles {
    fs::path tiff;
    fs::path png;
};

LayerFiles AddLayer(io::OutputSet& outputs, const fs::path& dir, const std::string& stem) {
    return {outputs.AddFile(dir / (stem + ".tiff"), "--out", true),
            outputs.AddFile(dir / (stem + ".png"), "--out", true)};
}

void WriteLayer(const LayerFiles& files,
                const core::MapF& map,
                const std::string& title,
                const std::string& unit,
                const core::Raster<std::uint8_t>* unknown) {
    io::WriteMapTiff(files.tiff, map);
    io::PngStyle style;
    style.title = title;
    style.unit = unit;
    style.unknown = unknown;
    io::WriteMapPng(files.png, map, style);
}

void RunMap(const MapOptions& opt) {
    const pipeline::MapSettings settings = ParseMapSettings(opt);  // bad flags exit 2 first
    const io::RunData run = io::ReadRunFile(opt.run);
    if (run.scans.empty()) {
        throw MakeInputError(opt.run, "/scans", "0 scans", "a run needs scans to be mapped");
    }
    if (run.poses.empty()) {
        throw MakeInputError(opt.run, "/poses", "0 poses",
                             "mapping needs the sensor poses (record --poses)");
    }
    const core::GridGeometry grid = ChooseGrid(opt, run);
    const fs::path run_path(opt.run);
    const fs::path dir = opt.out.empty()
                             ? run_path.parent_path() / (run_path.stem().string() + "_maps")
                             : fs::path(opt.out);
    // Every output, the run file included, is checked before mapping and published at the
    // end (the run file last): a read-only run folder fails here, not after writing --out.
    const bool with_truth = run.maps.truth_m && run.maps.grid && *run.maps.grid == grid;
    io::OutputSet outputs;
    const LayerFiles elevation_files = AddLayer(outputs, dir, "elevation");
    const LayerFiles certainty_files = AddLayer(outputs, dir, "certainty");
    const LayerFiles truth_files = with_truth ? AddLayer(outputs, dir, "truth") : LayerFiles{};
    const fs::path yaml_tmp = outputs.AddFile(dir / "map.yaml", "--out", true);
    const fs::path config_tmp = run.config_yaml.empty()
                                    ? fs::path()
                                    : outputs.AddFile(dir / "run_config.yaml", "--out", true);
    const fs::path run_tmp = outputs.AddFile(run_path, "run (its maps are stored in it)");

    const pipeline::MappedRun mapped = pipeline::MapScans(run.scans, run.poses, grid, settings);
    const core::Raster<std::uint8_t> unknown = pipeline::UnknownMask(mapped.certainty);
    const bool kalman = settings.mode == pipeline::MapperMode::kKalman;
    WriteLayer(elevation_files, mapped.elevation,
               kalman ? "elevation (Kalman mapper)" : "elevation (Eq. 6)", "m", &unknown);
    WriteLayer(certainty_files, mapped.certainty,
               kalman ? "certainty (a per fused scan)" : "certainty (Eq. 5)", "counts", &unknown);
    if (with_truth) {
        WriteLayer(truth_files, *run.maps.truth_m, "ground truth", "m", nullptr);
    }
    io::WriteTextAtomically(
        yaml_tmp, pipeline::MapConfigYaml(fs::absolute(opt.run).string(), run.seed, mapped));
    if (!run.config_yaml.empty()) {
        io::WriteTextAtomically(config_tmp, run.config_yaml);
    }
    io::RunData updated = run;  // the stored grid equals `grid` (ChooseGrid)
    updated.maps.grid = grid;
    updated.maps.elevation_m = mapped.elevation;
    updated.maps.certainty = mapped.certainty;
    io::WriteRunFile(run_tmp, updated);
    outputs.Publish();
    std::printf("mapped %llu of %llu beams onto %d x %d cells -> %s and %s\n",
                static_cast<unsigned long long>(mapped.stats.beams_mapped),
                static_cast<unsigned long long>(mapped.stats.beams_seen), grid.rows, grid.cols,
                dir.string().c_str(), opt.run.c_str());
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
                    "paper (Eq. 1-6) | kalman (Kalman fusion of each scan's lowest point)")
        ->capture_default_str();
    sub->add_option("--unknown", opt->unknown,
                    "never-observed cells: zero (the paper) | nan (grid_map convention)")
        ->capture_default_str();
    sub->add_option("--prefilter", opt->prefilter,
                    "scan pre-filter before mapping: none | shadow | range_jump")
        ->capture_default_str();
    sub->add_option("--set", opt->set,
                    "NAME=VALUE of the pre-filter run (shadow.<field>, range_jump.<field>) or of "
                    "the Kalman mapper (kalman.<field>); repeatable (docs/commands/map.md)");
    AddThreadsOption(sub, common);
    sub->callback([opt] { RunMap(*opt); });
}

}  // namespace casmap::app
