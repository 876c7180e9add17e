// casmap scan --scene FILE --pose X,Y,Z,ROLL_DEG,PITCH_DEG,YAW_DEG [--ideal] [--seed N]
//             [--range-mode 8|16|32] [--units mm|cm] [--sensor LMS200.yaml]
// One simulated LMS 200 scan from a fixed pose, printed as one JSON object (DESIGN.md):
// angles_deg, ranges_m (null when the beam reports no range), status, labels, plus raw.
// --ideal: one centre ray per beam, exact distances, no footprint, noise or errors.
// --sensor: the LMS 200 config file (config/lms200.yaml); --ideal, --range-mode and --units
// override it when given.
#include <cstdint>
#include <cstdio>
#include <memory>
#include <string>

#include "apps/casmap/commands.hpp"
#include "apps/casmap/flag_names.hpp"
#include "casmap/pipeline/scan_at.hpp"

namespace casmap::app {
namespace {

struct ScanOptions {
    std::string scene;
    std::string pose;
    bool ideal = false;
    std::uint64_t seed = 0;
    int range_mode_m = 8;
    std::string units = "mm";
    std::string sensor;  // --sensor file; empty: the built-in defaults
};

}  // namespace

void AddScanCommand(CLI::App& app, CommonOptions& common) {
    auto options = std::make_shared<ScanOptions>();
    CLI::App* sub = app.add_subcommand("scan", "one simulated LMS 200 scan at a pose, as JSON");
    sub->add_option("--scene", options->scene, "scene YAML file")->required();
    sub->add_option("--pose", options->pose, "X,Y,Z,ROLL_DEG,PITCH_DEG,YAW_DEG (world frame)")
        ->required();
    sub->add_flag("--ideal", options->ideal, "one exact centre ray per beam, no sensor errors");
    sub->add_option("--seed", options->seed, "run seed (noise, footprint rotation, artifacts)");
    CLI::Option* mode =
        sub->add_option("--range-mode", options->range_mode_m, "measuring range in m: 8, 16 or 32")
            ->check(CLI::IsMember({8, 16, 32}));
    CLI::Option* units = sub->add_option("--units", options->units, "range units: mm or cm")
                             ->check(CLI::IsMember({"mm", "cm"}));
    sub->add_option(
        "--sensor", options->sensor,
        "LMS 200 YAML (config/lms200.yaml); --ideal, --range-mode, --units override it");
    AddThreadsOption(sub, common);
    sub->callback([options, mode, units] {
        pipeline::ScanAtOptions o;
        o.scene = options->scene;
        o.sensor = {options->sensor, options->ideal, std::nullopt, std::nullopt};
        if (mode->count() > 0) {  // given flags override the sensor file
            o.sensor.range_mode_m = options->range_mode_m;
        }
        if (units->count() > 0) {
            o.sensor.units = options->units;
        }
        o.seed = options->seed;
        WithCommandLineFlags({{"pose", "--pose"}}, [&] {
            o.world_T_sensor = pipeline::ParsePoseXyzRpyDeg(options->pose);
        });
        std::fputs(pipeline::ScanJson(pipeline::ScanAt(o)).c_str(), stdout);
    });
}

}  // namespace casmap::app
