// casmap truth --scene FILE --grid X0,Y0,CELL_M,ROWS,COLS --out FILE.tiff [--png FILE.png]
//              [--rule highest|centre] [--keep-below-datum | --clamp-to-datum]
// The exact ground-truth elevation map of a scene (sim/ground_truth.hpp) as a single-channel
// 32-bit float TIFF in metres; rows along world x, columns along y (DESIGN.md "Map grid").
#include <cstdio>
#include <memory>
#include <string>

#include "apps/casmap/commands.hpp"
#include "apps/casmap/flag_names.hpp"
#include "casmap/core/input_error.hpp"
#include "casmap/pipeline/map_run.hpp"
#include "casmap/pipeline/truth_file.hpp"

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
    if (opt.keep_below_datum && opt.clamp_to_datum) {
        throw MakeInputError("command line", "--clamp-to-datum", "--keep-below-datum",
                             "the two flags exclude each other");
    }
    pipeline::TruthFileOptions options{opt.scene, {}, opt.out, opt.png, {}};
    options.truth.rule =
        opt.rule == "centre" ? sim::TruthRule::kCellCentre : sim::TruthRule::kHighestInCell;
    if (opt.keep_below_datum || opt.clamp_to_datum) {
        options.truth.clamp_to_datum = opt.clamp_to_datum;
    }  // neither: clamp unless the scene has terrain (sim::ClampsToDatum)
    pipeline::TruthFileResult r;
    WithCommandLineFlags({{"out", "--out"}, {"png", "--png"}},
                         [&] {
                             options.grid = pipeline::ParseGrid(opt.grid, "--grid");
                             r = pipeline::WriteTruthFiles(options, common.threads);
                         },
                         {{"out", opt.out}, {"png", opt.png}});
    std::printf("wrote %s: %d x %d cells of %g m, elevation %.4f .. %.4f m (%s rule)\n",
                opt.out.c_str(), options.grid.rows, options.grid.cols, options.grid.cell_m,
                static_cast<double>(r.min_m), static_cast<double>(r.max_m), opt.rule.c_str());
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
