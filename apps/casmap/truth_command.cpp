// casmap truth --scene FILE --grid X0,Y0,CELL_M,ROWS,COLS --out FILE.tiff [--png FILE.png]
//              [--rule highest|centre] [--keep-below-datum | --clamp-to-datum]
// The exact ground-truth elevation map of a scene (sim/ground_truth.hpp) as a single-channel
// 32-bit float TIFF in metres; rows along world x, columns along y (DESIGN.md "Map grid").
#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <string>

#include "apps/casmap/commands.hpp"
#include "casmap/core/grid.hpp"
#include "casmap/core/input_error.hpp"
#include "casmap/io/image.hpp"
#include "casmap/io/output_set.hpp"
#include "casmap/io/scene_file.hpp"
#include "casmap/pipeline/map_run.hpp"
#include "casmap/sim/ground_truth.hpp"

namespace casmap::app {
namespace {

struct TruthOptions {
    std::string scene;
    std::string grid;
    std::string out;
    std::string rule = "highest";
    bool keep_below_datum = false;
    bool clamp_to_datum = false;
    std::string png;  // optional colour PNG for people
};

void RunTruth(const TruthOptions& opt, const CommonOptions& common) {
    const std::string ext = std::filesystem::path(opt.out).extension().string();
    if (ext != ".tiff" && ext != ".tif") {
        throw MakeInputError("command line", "--out", opt.out, "must end in .tiff or .tif");
    }
    if (!opt.png.empty() && std::filesystem::path(opt.png).extension() != ".png") {
        throw MakeInputError("command line", "--png", opt.png, "must end in .png");
    }
    const core::GridGeometry grid = pipeline::ParseGrid(opt.grid, "--grid");
    io::OutputSet outputs;  // TIFF and PNG: checked first, published together
    const std::filesystem::path tiff_tmp = outputs.AddFile(opt.out, "--out");
    const std::filesystem::path png_tmp =
        opt.png.empty() ? std::filesystem::path() : outputs.AddFile(opt.png, "--png");
    sim::GroundTruthOptions options;
    options.rule =
        opt.rule == "centre" ? sim::TruthRule::kCellCentre : sim::TruthRule::kHighestInCell;
    if (opt.keep_below_datum && opt.clamp_to_datum) {
        throw MakeInputError("command line", "--clamp-to-datum", "--keep-below-datum",
                             "the two flags exclude each other");
    }
    if (opt.keep_below_datum || opt.clamp_to_datum) {
        options.clamp_to_datum = opt.clamp_to_datum;
    }  // neither: clamp unless the scene has terrain (sim::ClampsToDatum)
    const core::Scene scene = io::LoadScene(opt.scene);
    const core::MapF map = sim::GroundTruthElevation(scene, grid, options, common.threads);
    io::WriteMapTiff(tiff_tmp, map);
    if (!opt.png.empty()) {
        io::PngStyle style;
        style.title = "ground truth: " + opt.scene;
        io::WriteMapPng(png_tmp, map, style);
    }
    outputs.Publish();
    const auto [lo, hi] = std::minmax_element(map.data.begin(), map.data.end());
    std::printf("wrote %s: %d x %d cells of %g m, elevation %.4f .. %.4f m (%s rule)\n",
                opt.out.c_str(), grid.rows, grid.cols, grid.cell_m, static_cast<double>(*lo),
                static_cast<double>(*hi), opt.rule.c_str());
}

}  // namespace

void AddTruthCommand(CLI::App& app, CommonOptions& common) {
    auto opt = std::make_shared<TruthOptions>();
    CLI::App* sub = app.add_subcommand("truth", "exact ground-truth elevation map of a scene");
    sub->add_option("--scene", opt->scene, "scene YAML file")->required();
    sub->add_option("--grid", opt->grid, "map grid X0,Y0,CELL_M,ROWS,COLS (rows along x)")
        ->required();
    sub->add_option("--out", opt->out, "output 32-bit float TIFF (metres)")->required();
    sub->add_option("--rule", opt->rule,
                    "highest: highest surface point in the cell (default); centre: at the cell "
                    "centre")
        ->check(CLI::IsMember({"highest", "centre"}));
    sub->add_option("--png", opt->png, "also write a colour PNG of the map");
    sub->add_flag("--keep-below-datum", opt->keep_below_datum,
                  "keep surfaces below z = 0 (the default for scenes with terrain)");
    sub->add_flag("--clamp-to-datum", opt->clamp_to_datum,
                  "report 0 where the surface lies below z = 0 (the default for scenes "
                  "without terrain, as the paper's flat floor)");
    AddThreadsOption(sub, common);
    sub->callback([opt, &common] { RunTruth(*opt, common); });
}

}  // namespace casmap::app
