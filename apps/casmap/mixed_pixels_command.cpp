// casmap mixed-pixels [--from M] [--to M] [--step M] [--readings N] [--foreground-m M]
//                     [--reflectivity R] [--seed N] [--png FILE] [--json FILE]
//                     [--sensor LMS200.yaml]
// The paper's Fig. 3 experiment with the simulated LMS 200: the scanner's straight-ahead beam
// (beam 90) at the vertical edge of a foreground plate D_f ahead, a background wall Delta D
// behind it. For each Delta D the edge moves across the beam: `readings` pulses with the
// sensor stepped uniformly across the footprint (lateral offsets -a..+a, a = its 1/e^2 radius
// at D_f), each with its own pulse index (fresh footprint rotation and noise). A reading is a
// mixed pixel when it is a valid range more than 60 mm from both surfaces (as the paper).
// Prints a table; writes a PNG plot and JSON when asked. --sensor: the LMS 200 config file
// (config/lms200.yaml); the JSON then names it and lists every key of the config used.
#include <cctype>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <fstream>
#include <memory>
#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "apps/casmap/commands.hpp"
#include "casmap/core/input_error.hpp"
#include "casmap/core/parallel.hpp"
#include "casmap/core/pose.hpp"
#include "casmap/core/scene.hpp"
#include "casmap/io/atomic_file.hpp"
#include "casmap/io/sensor_config.hpp"
#include "casmap/sensor_models/lms200_model.hpp"
#include "casmap/sim/simulator.hpp"
#include "casmap/sim/world.hpp"

namespace casmap::app {
namespace {

constexpr double kMixedThresholdM = 0.060;  // the paper's Fig. 3 criterion

struct MixedOptions {
    double from_m = 0.2;
    double to_m = 2.5;
    double step_m = 0.1;
    int readings = 4000;
    double foreground_m = 2.0;
    double reflectivity = 0.5;
    std::uint64_t seed = 0;
    std::string png;
    std::string json;
    std::string sensor;  // --sensor file; empty: the built-in defaults
};

struct GapResult {
    double delta_d_m = 0.0;
    int valid = 0;
    int mixed = 0;
};

void Validate(const MixedOptions& o) {
    const auto bad = [](const std::string& flag, double v, const std::string& rule) {
        std::ostringstream s;
        s << v;
        return MakeInputError("command line", flag, s.str(), rule);
    };
    if (!(o.from_m > 0.0)) {
        throw bad("--from", o.from_m, "must be > 0");
    }
    if (!(o.to_m >= o.from_m)) {
        throw bad("--to", o.to_m, "must be >= --from");
    }
    if (!(o.step_m > 0.0)) {
        throw bad("--step", o.step_m, "must be > 0");
    }
    // Bounds the result table and the run time (docs/limits.md): Fig. 3 has 24 gaps.
    constexpr double kMaxGaps = 10000.0;
    if (!std::isfinite(o.to_m) || (o.to_m - o.from_m) / o.step_m > kMaxGaps) {
        throw bad("--step", o.step_m, "more than 10000 gaps from --from to --to");
    }
    if (o.readings <= 0 || o.readings > 1000000) {
        throw bad("--readings", o.readings, "allowed: 1..1000000");
    }
    if (!(o.foreground_m > 0.3 && o.foreground_m < 8.0)) {
        throw bad("--foreground-m", o.foreground_m, "allowed: 0.3 < x < 8 (the 8 m mode)");
    }
    if (!(o.reflectivity > 0.0 && o.reflectivity <= 1.0)) {
        throw bad("--reflectivity", o.reflectivity, "allowed: 0 < x <= 1");
    }
}

// A plate whose front face is at x = D_f covering y < 0 (the edge at y = 0) and a wall at
// x = D_f + gap covering everything behind it.
core::Scene EdgeScene(const MixedOptions& o, double gap_m) {
    core::Scene scene;
    const auto box = [&](const char* name, const Eigen::Vector3d& size, const Eigen::Vector3d& c) {
        core::SceneObject obj;
        obj.name = name;
        obj.shape = core::BoxShape{size};
        obj.world_T_object = core::PoseFromXyzRpy(c, Eigen::Vector3d::Zero());
        obj.reflectivity = o.reflectivity;
        scene.objects.push_back(obj);
    };
    box("foreground", {0.02, 4.0, 2.0}, {o.foreground_m + 0.01, -2.0, 0.0});
    box("background", {0.02, 20.0, 4.0}, {o.foreground_m + gap_m + 0.01, 0.0, 0.0});
    return scene;
}

GapResult RunGap(const MixedOptions& o, const sensor_models::Lms200Model& model, double gap_m) {
    const sim::World world(EdgeScene(o, gap_m));
    const sensor_models::Lms200Config& c = model.config();
    const double a = 0.5 * (c.spot_diameter_at_exit_m + c.divergence_rad * o.foreground_m);
    GapResult r;
    r.delta_d_m = gap_m;
    for (int k = 0; k < o.readings; ++k) {
        const double y = -a + 2.0 * a * (k + 0.5) / o.readings;
        sensor_models::PulseContext pulse;
        pulse.scan_index = static_cast<std::uint64_t>(k);
        pulse.beam = static_cast<std::uint32_t>((model.BeamCount() - 1) / 2);  // straight ahead
        const core::Pose pose{{0.0, y, 0.0}, Eigen::Quaterniond::Identity()};
        const sensor_models::PulseResult p = sim::CastPulse(world, model, pose, pulse);
        if (p.beam.status != core::BeamStatus::kOk) {
            continue;
        }
        ++r.valid;
        const double range = p.beam.range_m;
        r.mixed += std::abs(range - o.foreground_m) > kMixedThresholdM &&
                   std::abs(range - (o.foreground_m + gap_m)) > kMixedThresholdM;
    }
    return r;
}

/// `"sensor_file": ..., "sensor": {...}` lines (every key of the config) for --sensor runs.
std::string SensorJson(const MixedOptions& o, const sensor_models::Lms200Config& c) {
    std::string s = "  \"sensor_file\": \"";
    for (const char ch : o.sensor) {
        s += ch == '"' || ch == '\\' ? std::string("\\") + ch : std::string(1, ch);
    }
    s += "\",\n  \"sensor\": {";
    std::stringstream in(io::Lms200ConfigToYaml(c));
    bool first = true;
    for (std::string line; std::getline(in, line);) {
        const std::size_t colon = line.find(": ");
        const std::string key = line.substr(0, colon);
        const std::string value = line.substr(colon + 2);
        const bool text = std::isalpha(static_cast<unsigned char>(value[0])) != 0 &&
                          value != "true" && value != "false";
        s += std::string(first ? "" : ",") + "\n    \"" + key +
             "\": " + (text ? "\"" + value + "\"" : value);
        first = false;
    }
    return s + "\n  },\n";
}

std::string Json(const MixedOptions& o,
                 const sensor_models::Lms200Config& c,
                 const std::vector<GapResult>& results) {
    std::ostringstream s;
    s << "{\n  \"foreground_m\": " << o.foreground_m << ",\n  \"readings_per_gap\": " << o.readings
      << ",\n  \"reflectivity\": " << o.reflectivity << ",\n  \"seed\": " << o.seed
      << ",\n  \"mixed_threshold_m\": " << kMixedThresholdM << ",\n";
    if (!o.sensor.empty()) {
        s << SensorJson(o, c);
    }
    const auto list = [&](const char* key, auto value, bool last) {
        s << "  \"" << key << "\": [";
        for (std::size_t i = 0; i < results.size(); ++i) {
            s << (i == 0 ? "" : ", ") << value(results[i]);
        }
        s << (last ? "]\n" : "],\n");
    };
    list(
        "delta_d_m", [](const GapResult& g) { return g.delta_d_m; }, false);
    list(
        "valid", [](const GapResult& g) { return g.valid; }, false);
    list(
        "mixed", [](const GapResult& g) { return g.mixed; }, true);
    s << "}\n";
    return s.str();
}

// Mixed pixels against Delta D, drawn like the paper's Fig. 3.
cv::Mat Plot(const MixedOptions& o, const std::vector<GapResult>& results) {
    const int w = 720;
    const int h = 440;
    const int left = 70;
    const int right = 20;
    const int top = 40;
    const int bottom = 60;
    cv::Mat img(h, w, CV_8UC3, cv::Scalar(255, 255, 255));
    int y_max = 1;
    for (const GapResult& g : results) {
        y_max = std::max(y_max, g.mixed);
    }
    const double x_lo = 0.0;
    const double x_hi = std::max(o.to_m, results.back().delta_d_m) + 0.1;
    const auto px = [&](double x, double y) {
        return cv::Point(left + static_cast<int>((x - x_lo) / (x_hi - x_lo) * (w - left - right)),
                         h - bottom - static_cast<int>(y / y_max * (h - top - bottom)));
    };
    const cv::Scalar black(0, 0, 0);
    const cv::Scalar grey(200, 200, 200);
    cv::line(img, px(x_lo, 0), px(x_hi, 0), black, 1);
    cv::line(img, px(x_lo, 0), px(x_lo, y_max), black, 1);
    for (double x = 0.0; x <= x_hi + 1e-9; x += 0.5) {
        cv::line(img, px(x, 0), px(x, y_max), grey, 1);
        std::ostringstream t;
        t << x;
        cv::putText(img, t.str(), px(x, 0) + cv::Point(-10, 20), cv::FONT_HERSHEY_SIMPLEX, 0.45,
                    black, 1, cv::LINE_AA);
    }
    for (int i = 0; i <= 4; ++i) {
        const double y = y_max * i / 4.0;
        cv::putText(img, std::to_string(static_cast<int>(y)), px(x_lo, y) + cv::Point(-60, 5),
                    cv::FONT_HERSHEY_SIMPLEX, 0.45, black, 1, cv::LINE_AA);
    }
    std::vector<cv::Point> line;
    for (const GapResult& g : results) {
        line.push_back(px(g.delta_d_m, g.mixed));
    }
    cv::polylines(img, line, false, cv::Scalar(180, 60, 20), 2, cv::LINE_AA);
    for (const cv::Point& p : line) {
        cv::circle(img, p, 3, cv::Scalar(180, 60, 20), cv::FILLED, cv::LINE_AA);
    }
    cv::putText(img, "Delta D (m)", cv::Point(w / 2 - 40, h - 15), cv::FONT_HERSHEY_SIMPLEX, 0.55,
                black, 1, cv::LINE_AA);
    std::ostringstream title;
    title << "Mixed pixels (>60 mm from both surfaces) of " << o.readings
          << " readings, D_f = " << o.foreground_m << " m";
    cv::putText(img, title.str(), cv::Point(left, 25), cv::FONT_HERSHEY_SIMPLEX, 0.5, black, 1,
                cv::LINE_AA);
    return img;
}

void WritePng(const std::string& path, const cv::Mat& img) {
    std::vector<unsigned char> bytes;
    if (!cv::imencode(".png", img, bytes)) {
        throw std::runtime_error("cannot encode the plot as PNG");
    }
    io::WriteAtomically(path, [&](const std::filesystem::path& tmp) {
        std::ofstream out(tmp, std::ios::binary);
        out.write(reinterpret_cast<const char*>(bytes.data()),
                  static_cast<std::streamsize>(bytes.size()));
        if (!out) {
            throw MakeInputError(path, "--png", "", "cannot write the file");
        }
    });
}

void Run(const MixedOptions& o, int threads) {
    Validate(o);
    const sensor_models::Lms200Model model(
        o.sensor.empty() ? sensor_models::Lms200Config{} : io::LoadLms200Config(o.sensor), o.seed);
    std::vector<double> gaps;
    for (int i = 0;; ++i) {
        const double g = o.from_m + i * o.step_m;
        if (g > o.to_m + 1e-9) {
            break;
        }
        gaps.push_back(g);
    }
    std::vector<GapResult> results(gaps.size());
    core::ParallelFor(gaps.size(), threads,
                      [&](std::size_t i) { results[i] = RunGap(o, model, gaps[i]); });
    std::printf(
        "# Fig. 3 with the simulated LMS 200: D_f = %.3f m, %d readings per gap, seed %llu\n",
        o.foreground_m, o.readings, static_cast<unsigned long long>(o.seed));
    if (!o.sensor.empty()) {
        std::printf("# sensor: %s\n", o.sensor.c_str());
    }
    std::printf("%10s %8s %8s %8s\n", "delta_d_m", "valid", "mixed", "mixed_%");
    for (const GapResult& g : results) {
        std::printf("%10.2f %8d %8d %8.2f\n", g.delta_d_m, g.valid, g.mixed,
                    100.0 * g.mixed / o.readings);
    }
    if (!o.json.empty()) {
        io::WriteTextAtomically(o.json, Json(o, model.config(), results));
    }
    if (!o.png.empty()) {
        WritePng(o.png, Plot(o, results));
    }
}

}  // namespace

void AddMixedPixelsCommand(CLI::App& app, CommonOptions& common) {
    auto o = std::make_shared<MixedOptions>();
    CLI::App* sub = app.add_subcommand(
        "mixed-pixels", "the paper's Fig. 3: mixed pixels at an edge against the gap Delta D");
    sub->add_option("--from", o->from_m, "smallest Delta D (m)");
    sub->add_option("--to", o->to_m, "largest Delta D (m)");
    sub->add_option("--step", o->step_m, "Delta D step (m)");
    sub->add_option("--readings", o->readings, "readings per Delta D");
    sub->add_option("--foreground-m", o->foreground_m, "distance to the foreground edge (m)");
    sub->add_option("--reflectivity", o->reflectivity, "reflectivity of both surfaces");
    sub->add_option("--seed", o->seed, "run seed");
    sub->add_option("--png", o->png, "write the plot here");
    sub->add_option("--json", o->json, "write the counts here");
    sub->add_option("--sensor", o->sensor,
                    "LMS 200 YAML (config/lms200.yaml; default: the built-in config)");
    AddThreadsOption(sub, common);
    sub->callback([o, &common] { Run(*o, common.threads); });
}

}  // namespace casmap::app
