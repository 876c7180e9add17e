#include "casmap/pipeline/map_file.hpp"

#include <cstdint>

#include "casmap/core/input_error.hpp"
#include "casmap/core/text.hpp"
#include "casmap/io/atomic_file.hpp"
#include "casmap/io/image.hpp"
#include "casmap/io/output_set.hpp"
#include "casmap/io/run_file.hpp"

namespace casmap::pipeline {
namespace {
namespace fs = std::filesystem;

/// The grid: the one given, else the run's own (written with its truth), else the beams'.
core::GridGeometry ChooseGrid(const MapRunFileOptions& o, const io::RunData& run) {
    if (o.grid) {
        if (run.maps.grid && !(*run.maps.grid == *o.grid)) {
            const core::GridGeometry& g = *o.grid;  // as ParseGrid reads it: X0,Y0,CELL_M,ROWS,COLS
            const std::string text = core::FormatNumber(g.x0_m) + "," + core::FormatNumber(g.y0_m) +
                                     "," + core::FormatNumber(g.cell_m) + "," +
                                     std::to_string(g.rows) + "," + std::to_string(g.cols);
            throw MakeInputError(o.run, "grid", text,
                                 "differs from the grid stored in the run file " +
                                     GridYaml(*run.maps.grid) + "; its maps share one grid");
        }
        return *o.grid;
    }
    if (run.maps.grid) {
        return *run.maps.grid;
    }
    return GridCoveringBeams(run.scans, run.poses, 0.025, o.run);
}

/// The TIFF and PNG of one layer, written to the temporaries of `outputs`.
struct LayerFiles {
    fs::path tiff;
    fs::path png;
};

LayerFiles AddLayer(io::OutputSet& outputs, const fs::path& dir, const std::string& stem) {
    return {outputs.AddFile(dir / (stem + ".tiff"), "out", true),
            outputs.AddFile(dir / (stem + ".png"), "out", true)};
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

}  // namespace

MapRunFileResult MapRunFile(const MapRunFileOptions& o) {
    o.settings.Validate();  // bad settings fail before the run is read
    const io::RunData run = io::ReadRunFile(o.run);
    if (run.scans.empty()) {
        throw MakeInputError(o.run, "/scans", "0 scans", "a run needs scans to be mapped");
    }
    if (run.poses.empty()) {
        throw MakeInputError(o.run, "/poses", "0 poses",
                             "mapping needs the sensor poses (record --poses)");
    }
    MapRunFileResult result;
    result.grid = ChooseGrid(o, run);
    const fs::path run_path(o.run);
    result.out_dir = o.out.empty() ? run_path.parent_path() / (run_path.stem().string() + "_maps")
                                   : fs::path(o.out);
    const fs::path& dir = result.out_dir;
    // Every output, the run file included, is checked before mapping and published at the
    // end (the run file last): a read-only run folder fails here, not after writing `out`.
    const bool with_truth = run.maps.truth_m && run.maps.grid && *run.maps.grid == result.grid;
    io::OutputSet outputs;
    const LayerFiles elevation_files = AddLayer(outputs, dir, "elevation");
    const LayerFiles certainty_files = AddLayer(outputs, dir, "certainty");
    const LayerFiles truth_files = with_truth ? AddLayer(outputs, dir, "truth") : LayerFiles{};
    const fs::path yaml_tmp = outputs.AddFile(dir / "map.yaml", "out", true);
    const fs::path config_tmp = run.config_yaml.empty()
                                    ? fs::path()
                                    : outputs.AddFile(dir / "run_config.yaml", "out", true);
    const fs::path run_tmp = outputs.AddFile(run_path, "run (its maps are stored in it)");

    result.mapped = MapScans(run.scans, run.poses, result.grid, o.settings);
    const MappedRun& mapped = result.mapped;
    const core::Raster<std::uint8_t> unknown = UnknownMask(mapped.certainty);
    const bool kalman = o.settings.mode == MapperMode::kKalman;
    const bool consensus = o.settings.mode == MapperMode::kConsensus;
    WriteLayer(elevation_files, mapped.elevation,
               kalman      ? "elevation (Kalman mapper)"
               : consensus ? "elevation (consensus cell height)"
                           : "elevation (Eq. 6)",
               "m", &unknown);
    WriteLayer(certainty_files, mapped.certainty,
               kalman ? "certainty (a per fused scan)" : "certainty (Eq. 5)", "counts", &unknown);
    if (with_truth) {
        WriteLayer(truth_files, *run.maps.truth_m, "ground truth", "m", nullptr);
    }
    io::WriteTextAtomically(yaml_tmp,
                            MapConfigYaml(fs::absolute(o.run).string(), run.seed, mapped));
    if (!run.config_yaml.empty()) {
        io::WriteTextAtomically(config_tmp, run.config_yaml);
    }
    io::RunData updated = run;  // the stored grid equals result.grid (ChooseGrid)
    updated.maps.grid = result.grid;
    updated.maps.elevation_m = mapped.elevation;
    updated.maps.certainty = mapped.certainty;
    io::WriteRunFile(run_tmp, updated);
    outputs.Publish();
    return result;
}

}  // namespace casmap::pipeline
