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
#include <numbers>
#include <optional>
#include <string>
#include <vector>

#include "apps/casmap/commands.hpp"
#include "casmap/core/input_error.hpp"
#include "casmap/core/pose.hpp"
#include "casmap/core/text.hpp"
#include "casmap/io/scene_file.hpp"
#include "casmap/io/sensor_config.hpp"
#include "casmap/sensor_models/lms200_model.hpp"
#include "casmap/sim/simulator.hpp"
#include "casmap/sim/world.hpp"

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
    bool range_mode_given = false;
    bool units_given = false;
};

/// "X,Y,Z,ROLL_DEG,PITCH_DEG,YAW_DEG" -> world_T_sensor; throws InputError naming --pose.
core::Pose ParsePose(const std::string& text) {
    const std::optional<std::vector<double>> v = core::ParseNumberList(text, 6);
    if (!v) {
        throw MakeInputError("command line", "--pose", text,
                             "must be six numbers X,Y,Z,ROLL_DEG,PITCH_DEG,YAW_DEG");
    }
    constexpr double kDeg = std::numbers::pi / 180.0;
    const std::vector<double>& p = *v;
    return core::PoseFromXyzRpy({p[0], p[1], p[2]}, {p[3] * kDeg, p[4] * kDeg, p[5] * kDeg});
}

sensor_models::Lms200Config MakeConfig(const ScanOptions& o) {
    sensor_models::Lms200Config c;
    if (!o.sensor.empty()) {
        c = io::LoadLms200Config(o.sensor);
    }
    c.ideal = c.ideal || o.ideal;
    if (o.sensor.empty() || o.range_mode_given) {
        c.format.mode = o.range_mode_m == 16   ? core::RangeMode::k16m
                        : o.range_mode_m == 32 ? core::RangeMode::k32m
                                               : core::RangeMode::k8m;
    }
    if (o.sensor.empty() || o.units_given) {
        c.format.units =
            o.units == "cm" ? core::RangeUnits::kCentimetre : core::RangeUnits::kMillimetre;
    }
    return c;
}

void PrintJson(const sensor_models::Lms200Model& model, const sim::ScanResult& r, bool ideal) {
    constexpr double kDeg = 180.0 / std::numbers::pi;
    const std::size_t n = r.scan.beams.size();
    const auto list = [n](const char* key, const auto& item, bool last) {
        std::printf("  \"%s\": [", key);
        for (std::size_t i = 0; i < n; ++i) {
            std::printf(i == 0 ? "" : ", ");
            item(i);
        }
        std::printf(last ? "]\n" : "],\n");
    };
    const double unit = model.config().format.UnitM();
    std::printf("{\n");
    list(
        "angles_deg", [&](std::size_t i) { std::printf("%.6g", r.scan.BeamAngle(i) * kDeg); },
        false);
    list(
        "ranges_m",
        [&](std::size_t i) {
            const core::Beam& b = r.scan.beams[i];
            if (b.status != core::BeamStatus::kOk) {
                std::printf("null");
            } else if (ideal) {
                std::printf("%.6f", static_cast<double>(b.range_m));
            } else {
                std::printf(unit < 0.005 ? "%.3f" : "%.2f", b.raw * unit);
            }
        },
        false);
    list(
        "status",
        [&](std::size_t i) {
            std::printf("\"%s\"", std::string(core::ToString(r.scan.beams[i].status)).c_str());
        },
        false);
    list(
        "labels",
        [&](std::size_t i) {
            std::printf("\"%s\"", std::string(core::ToString(r.truth.labels[i])).c_str());
        },
        false);
    list(
        "raw", [&](std::size_t i) { std::printf("%u", unsigned{r.scan.beams[i].raw}); }, true);
    std::printf("}\n");
}

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
        options->range_mode_given = mode->count() > 0;
        options->units_given = units->count() > 0;
        const core::Pose pose = ParsePose(options->pose);
        const sensor_models::Lms200Model model(MakeConfig(*options), options->seed);
        const sim::World world(io::LoadScene(options->scene));
        const sim::ScanResult r = sim::CastScanAt(world, model, pose, 0.0, 0);
        PrintJson(model, r, model.config().ideal);
    });
}

}  // namespace casmap::app
