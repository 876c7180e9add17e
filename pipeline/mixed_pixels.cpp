#include "casmap/pipeline/mixed_pixels.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <sstream>
#include <stdexcept>

#include "casmap/core/check.hpp"
#include "casmap/core/input_error.hpp"
#include "casmap/core/parallel.hpp"
#include "casmap/core/pose.hpp"
#include "casmap/core/scene.hpp"
#include "casmap/io/sensor_config.hpp"
#include "casmap/sim/simulator.hpp"
#include "casmap/sim/world.hpp"

namespace casmap::pipeline {
namespace {

// A plate whose front face is at x = D_f covering y < 0 (the edge at y = 0) and a wall at
// x = D_f + gap covering everything behind it.
core::Scene EdgeScene(const MixedPixelsOptions& o, double gap_m) {
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

MixedPixelsGap RunGap(const MixedPixelsOptions& o,
                      const sensor_models::Lms200Model& model,
                      double gap_m) {
    const sim::World world(EdgeScene(o, gap_m));
    const sensor_models::Lms200Config& c = model.config();
    const double a = 0.5 * (c.spot_diameter_at_exit_m + c.divergence_rad * o.foreground_m);
    MixedPixelsGap r;
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
        r.mixed += std::abs(range - o.foreground_m) > kMixedPixelThresholdM &&
                   std::abs(range - (o.foreground_m + gap_m)) > kMixedPixelThresholdM;
    }
    return r;
}

/// `"sensor_file": ..., "sensor": {...}` lines (every key of the config) for --sensor runs.
std::string SensorJson(const MixedPixelsOptions& o, const sensor_models::Lms200Config& c) {
    std::string s = "  \"sensor_file\": \"";
    for (const char ch : o.sensor_file) {
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

}  // namespace

void MixedPixelsOptions::Validate() const {
    const core::Check check;
    check.That(from_m > 0.0, "from_m", from_m, "must be > 0");
    check.That(to_m >= from_m, "to_m", to_m, "must be >= from_m");
    check.That(step_m > 0.0, "step_m", step_m, "must be > 0");
    // Bounds the result table and the run time (docs/limits.md): Fig. 3 has 24 gaps.
    constexpr double kMaxGaps = 10000.0;
    check.That(std::isfinite(to_m) && (to_m - from_m) / step_m <= kMaxGaps, "step_m", step_m,
               "more than 10000 gaps from from_m to to_m");
    check.That(readings > 0 && readings <= 1000000, "readings", readings, "allowed: 1..1000000");
    check.That(foreground_m > 0.3 && foreground_m < 8.0, "foreground_m", foreground_m,
               "allowed: 0.3 < x < 8 (the 8 m mode)");
    check.That(reflectivity > 0.0 && reflectivity <= 1.0, "reflectivity", reflectivity,
               "allowed: 0 < x <= 1");
}

MixedPixelsResult RunMixedPixels(const MixedPixelsOptions& o,
                                 int threads,
                                 const core::ProgressFn& progress) {
    o.Validate();
    const sensor_models::Lms200Model model(
        o.sensor_file.empty() ? sensor_models::Lms200Config{} : io::LoadLms200Config(o.sensor_file),
        o.seed);
    std::vector<double> gaps;
    for (int i = 0;; ++i) {
        const double g = o.from_m + i * o.step_m;
        if (g > o.to_m + 1e-9) {
            break;
        }
        gaps.push_back(g);
    }
    MixedPixelsResult result;
    result.sensor = model.config();
    result.gaps.resize(gaps.size());
    core::ProgressCounter counter(progress, gaps.size());
    core::ParallelFor(gaps.size(), threads, [&](std::size_t i) {
        result.gaps[i] = RunGap(o, model, gaps[i]);
        counter.Advance();
    });
    return result;
}

std::string MixedPixelsJson(const MixedPixelsOptions& o, const MixedPixelsResult& result) {
    const std::vector<MixedPixelsGap>& results = result.gaps;
    std::ostringstream s;
    s << "{\n  \"foreground_m\": " << o.foreground_m << ",\n  \"readings_per_gap\": " << o.readings
      << ",\n  \"reflectivity\": " << o.reflectivity << ",\n  \"seed\": " << o.seed
      << ",\n  \"mixed_threshold_m\": " << kMixedPixelThresholdM << ",\n";
    if (!o.sensor_file.empty()) {
        s << SensorJson(o, result.sensor);
    }
    const auto list = [&](const char* key, auto value, bool last) {
        s << "  \"" << key << "\": [";
        for (std::size_t i = 0; i < results.size(); ++i) {
            s << (i == 0 ? "" : ", ") << value(results[i]);
        }
        s << (last ? "]\n" : "],\n");
    };
    list(
        "delta_d_m", [](const MixedPixelsGap& g) { return g.delta_d_m; }, false);
    list(
        "valid", [](const MixedPixelsGap& g) { return g.valid; }, false);
    list(
        "mixed", [](const MixedPixelsGap& g) { return g.mixed; }, true);
    s << "}\n";
    return s.str();
}

// Mixed pixels against Delta D, drawn like the paper's Fig. 3.
std::vector<unsigned char> MixedPixelsPng(const MixedPixelsOptions& o,
                                          const MixedPixelsResult& result) {
    const std::vector<MixedPixelsGap>& results = result.gaps;
    const int w = 720;
    const int h = 440;
    const int left = 70;
    const int right = 20;
    const int top = 40;
    const int bottom = 60;
    cv::Mat img(h, w, CV_8UC3, cv::Scalar(255, 255, 255));
    int y_max = 1;
    for (const MixedPixelsGap& g : results) {
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
    for (const MixedPixelsGap& g : results) {
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
    std::vector<unsigned char> bytes;
    if (!cv::imencode(".png", img, bytes)) {
        throw std::runtime_error("cannot encode the plot as PNG");
    }
    return bytes;
}

}  // namespace casmap::pipeline
