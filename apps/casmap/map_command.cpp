// casmap map RUN.h5 [--out DIR] [--grid X0,Y0,CELL_M,ROWS,COLS]
// Builds the elevation and certainty maps (Eq. 1-6) of a run file, simulated or recorded (the
// truth labels are never read), and writes them as float TIFF + colour PNG into DIR and as
// /maps/elevation_m and /maps/certainty into the run file.
#include <cstdio>
#include <filesystem>
#include <optional>
#include <string>

#include "apps/casmap/commands.hpp"
#include "casmap/core/input_error.hpp"
#include "casmap/io/atomic_file.hpp"
#include "casmap/io/run_file.hpp"
#include "casmap/pipeline/map_run.hpp"

namespace casmap::app {
namespace {
namespace fs = std::filesystem;

struct MapOptions {
    std::string run;
    std::string out;
    std::string grid;
};

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

std::string MapYaml(const MapOptions& opt,
                    const io::RunData& run,
                    const pipeline::MappedRun& mapped) {
    const mapper::MapperStats& s = mapped.stats;
    std::string y = "# casmap map: the settings that produced the maps in this directory\n";
    y += "run: " + fs::absolute(opt.run).string() + "\n";
    y += "seed: " + (run.seed ? std::to_string(*run.seed) : std::string("null")) + "\n";
    y += "grid: " + pipeline::GridYaml(mapped.config.grid) + "\n";
    y += "mapper: {a: " + std::to_string(mapped.config.a) +
         ", delta_l_m: " + pipeline::FormatNumber(mapped.config.delta_l_m) +
         ", scan_period_s: " + pipeline::FormatNumber(mapped.config.scan_period_s) + "}\n";
    y += "stats: {beams_seen: " + std::to_string(s.beams_seen) +
         ", beams_not_ok: " + std::to_string(s.beams_not_ok) +
         ", beams_no_pose: " + std::to_string(s.beams_no_pose) +
         ", beams_outside: " + std::to_string(s.beams_outside) +
         ", beams_mapped: " + std::to_string(s.beams_mapped) + "}\n";
    return y;
}

void RunMap(const MapOptions& opt) {
    const io::RunData run = io::ReadRunFile(opt.run);
    const core::GridGeometry grid = ChooseGrid(opt, run);
    const fs::path run_path(opt.run);
    const fs::path dir = opt.out.empty()
                             ? run_path.parent_path() / (run_path.stem().string() + "_maps")
                             : fs::path(opt.out);
    io::EnsureDirectory(dir);

    const pipeline::MappedRun mapped = pipeline::MapScans(run.scans, run.poses, grid);
    const core::Raster<std::uint8_t> unknown = pipeline::UnknownMask(mapped.certainty);
    pipeline::WriteMapFiles(dir, "elevation", mapped.elevation, "elevation (Eq. 6)", "m", &unknown);
    pipeline::WriteMapFiles(dir, "certainty", mapped.certainty, "certainty (Eq. 5)", "counts",
                            &unknown);
    if (run.maps.truth_m && run.maps.grid && *run.maps.grid == grid) {
        pipeline::WriteMapFiles(dir, "truth", *run.maps.truth_m, "ground truth", "m", nullptr);
    }
    io::WriteTextAtomically(dir / "map.yaml", MapYaml(opt, run, mapped));
    if (!run.config_yaml.empty()) {
        io::WriteTextAtomically(dir / "run_config.yaml", run.config_yaml);
    }

    io::RunMaps maps;
    maps.grid = grid;
    maps.elevation_m = mapped.elevation;
    maps.certainty = mapped.certainty;
    io::AddRunMaps(opt.run, maps);
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
    AddThreadsOption(sub, common);
    sub->callback([opt] { RunMap(*opt); });
}

}  // namespace casmap::app
