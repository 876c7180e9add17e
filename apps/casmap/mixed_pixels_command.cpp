// casmap mixed-pixels [--from M] [--to M] [--step M] [--readings N] [--foreground-m M]
//                     [--reflectivity R] [--seed N] [--png FILE] [--json FILE]
//                     [--sensor LMS200.yaml]
// The paper's Fig. 3 experiment with the simulated LMS 200 (pipeline::RunMixedPixels): mixed
// pixels at the edge of a plate D_f ahead against the gap Delta D to the wall behind it.
// Prints a table; writes a PNG plot and JSON when asked. --sensor: the LMS 200 config file
// (config/lms200.yaml); the JSON then names it and lists every key of the config used.
#include <cstdio>
#include <fstream>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "apps/casmap/commands.hpp"
#include "apps/casmap/flag_names.hpp"
#include "casmap/core/input_error.hpp"
#include "casmap/io/atomic_file.hpp"
#include "casmap/pipeline/mixed_pixels.hpp"

namespace casmap::app {
namespace {

struct MixedOptions {
    pipeline::MixedPixelsOptions run;
    std::string png;
    std::string json;
};

void WritePng(const std::string& path, const std::vector<unsigned char>& bytes) {
    io::WriteAtomically(path, [&](const std::filesystem::path& tmp) {
        std::ofstream out(tmp, std::ios::binary);
        out.write(reinterpret_cast<const char*>(bytes.data()),
                  static_cast<std::streamsize>(bytes.size()));
        if (!out) {
            throw MakeInputError(path, "--png", "", "cannot write the file");
        }
    });
}

pipeline::MixedPixelsResult RunWithFlagNames(const pipeline::MixedPixelsOptions& o, int threads) {
    static const FlagNames kFlags = {{"from_m", "--from"},
                                     {"to_m", "--to"},
                                     {"step_m", "--step"},
                                     {"readings", "--readings"},
                                     {"foreground_m", "--foreground-m"},
                                     {"reflectivity", "--reflectivity"}};
    pipeline::MixedPixelsResult result;
    try {
        WithFlagNames(kFlags, [&] { result = pipeline::RunMixedPixels(o, threads); });
    } catch (const InputError& e) {
        if (!e.where().empty() || e.field().rfind("--", 0) != 0) {
            throw;  // not about a flag (a file's error, a message-only error)
        }
        std::string rule = e.rule();  // "must be >= from_m" names another field
        for (const auto& [field, flag] :
             {std::pair{"from_m", "--from"}, std::pair{"to_m", "--to"}}) {
            for (std::size_t at = rule.find(field); at != std::string::npos;
                 at = rule.find(field)) {
                rule.replace(at, std::string(field).size(), flag);
            }
        }
        throw MakeInputError("command line", e.field(), e.value(), rule);
    }
    return result;
}

void Run(const MixedOptions& opt, int threads) {
    const pipeline::MixedPixelsOptions& o = opt.run;
    const pipeline::MixedPixelsResult result = RunWithFlagNames(o, threads);
    std::printf(
        "# Fig. 3 with the simulated LMS 200: D_f = %.3f m, %d readings per gap, seed %llu\n",
        o.foreground_m, o.readings, static_cast<unsigned long long>(o.seed));
    if (!o.sensor_file.empty()) {
        std::printf("# sensor: %s\n", o.sensor_file.c_str());
    }
    std::printf("%10s %8s %8s %8s\n", "delta_d_m", "valid", "mixed", "mixed_%");
    for (const pipeline::MixedPixelsGap& g : result.gaps) {
        std::printf("%10.2f %8d %8d %8.2f\n", g.delta_d_m, g.valid, g.mixed,
                    100.0 * g.mixed / o.readings);
    }
    if (!opt.json.empty()) {
        io::WriteTextAtomically(opt.json, pipeline::MixedPixelsJson(o, result));
    }
    if (!opt.png.empty()) {
        WritePng(opt.png, pipeline::MixedPixelsPng(o, result));
    }
}

}  // namespace

void AddMixedPixelsCommand(CLI::App& app, CommonOptions& common) {
    auto o = std::make_shared<MixedOptions>();
    CLI::App* sub = app.add_subcommand(
        "mixed-pixels", "the paper's Fig. 3: mixed pixels at an edge against the gap Delta D");
    sub->add_option("--from", o->run.from_m, "smallest Delta D (m)");
    sub->add_option("--to", o->run.to_m, "largest Delta D (m)");
    sub->add_option("--step", o->run.step_m, "Delta D step (m)");
    sub->add_option("--readings", o->run.readings, "readings per Delta D");
    sub->add_option("--foreground-m", o->run.foreground_m, "distance to the foreground edge (m)");
    sub->add_option("--reflectivity", o->run.reflectivity, "reflectivity of both surfaces");
    sub->add_option("--seed", o->run.seed, "run seed");
    sub->add_option("--png", o->png, "write the plot here");
    sub->add_option("--json", o->json, "write the counts here");
    sub->add_option("--sensor", o->run.sensor_file,
                    "LMS 200 YAML (config/lms200.yaml; default: the built-in config)");
    AddThreadsOption(sub, common);
    sub->callback([o, &common] { Run(*o, common.threads); });
}

}  // namespace casmap::app
