#include "casmap/pipeline/scan_at.hpp"

#include <cmath>
#include <cstdio>
#include <numbers>

#include "casmap/core/check.hpp"
#include "casmap/core/text.hpp"
#include "casmap/io/scene_file.hpp"
#include "casmap/io/sensor_config.hpp"
#include "casmap/sensor_models/lms200_model.hpp"
#include "casmap/sim/world.hpp"

namespace casmap::pipeline {

void ScanSensorOptions::Validate() const {
    const core::Check check;
    if (range_mode_m) {
        const int m = *range_mode_m;
        check.That(m == 8 || m == 16 || m == 32, "range_mode_m", m, "allowed: 8, 16, 32");
    }
    if (units) {
        check.That(*units == "mm" || *units == "cm", "units", *units, "allowed: mm, cm");
    }
}

sensor_models::Lms200Config MakeScanSensorConfig(const ScanSensorOptions& o) {
    o.Validate();
    sensor_models::Lms200Config c;
    if (!o.sensor.empty()) {
        c = io::LoadLms200Config(o.sensor);
    }
    c.ideal = c.ideal || o.ideal;
    if (o.range_mode_m) {
        c.format.mode = *o.range_mode_m == 16   ? core::RangeMode::k16m
                        : *o.range_mode_m == 32 ? core::RangeMode::k32m
                                                : core::RangeMode::k8m;
    }
    if (o.units) {
        c.format.units =
            *o.units == "cm" ? core::RangeUnits::kCentimetre : core::RangeUnits::kMillimetre;
    }
    return c;
}

core::Pose PoseFromXyzRpyDeg(const std::vector<double>& v, const std::string& field) {
    const char* const rule = "must be six numbers X,Y,Z,ROLL_DEG,PITCH_DEG,YAW_DEG";
    core::Check().That(v.size() == 6, field, std::to_string(v.size()) + " numbers", rule);
    std::string text;
    bool finite = true;
    for (const double x : v) {
        text += (text.empty() ? "" : ",") + core::FormatNumber(x);
        finite = finite && std::isfinite(x);
    }
    core::Check().That(finite, field, text, rule);
    constexpr double kDeg = std::numbers::pi / 180.0;
    return core::PoseFromXyzRpy({v[0], v[1], v[2]}, {v[3] * kDeg, v[4] * kDeg, v[5] * kDeg});
}

core::Pose ParsePoseXyzRpyDeg(std::string_view text, const std::string& field) {
    const std::optional<std::vector<double>> v = core::ParseNumberList(text, 6);
    core::Check().That(v.has_value(), field, text,
                       "must be six numbers X,Y,Z,ROLL_DEG,PITCH_DEG,YAW_DEG");
    return PoseFromXyzRpyDeg(*v, field);
}

ScanAtResult ScanAt(const ScanAtOptions& o) {
    ScanAtResult r;
    r.sensor = MakeScanSensorConfig(o.sensor);
    const sensor_models::Lms200Model model(r.sensor, o.seed);
    const sim::World world(io::LoadScene(o.scene));
    r.scan = sim::CastScanAt(world, model, o.world_T_sensor, 0.0, 0);
    return r;
}

std::string ScanJson(const ScanAtResult& result) {
    constexpr double kDeg = 180.0 / std::numbers::pi;
    const core::Scan& scan = result.scan.scan;
    const double unit = result.sensor.format.UnitM();
    std::string json = "{\n";
    const auto list = [&](const char* key, const auto& item, bool last) {
        json += std::string("  \"") + key + "\": [";
        for (std::size_t i = 0; i < scan.beams.size(); ++i) {
            json += (i == 0 ? "" : ", ") + item(i);
        }
        json += last ? "]\n" : "],\n";
    };
    const auto printf_text = [](const char* format, double value) {
        char buffer[64];
        std::snprintf(buffer, sizeof(buffer), format, value);
        return std::string(buffer);
    };
    list(
        "angles_deg", [&](std::size_t i) { return printf_text("%.6g", scan.BeamAngle(i) * kDeg); },
        false);
    list(
        "ranges_m",
        [&](std::size_t i) {
            const core::Beam& b = scan.beams[i];
            if (b.status != core::BeamStatus::kOk) {
                return std::string("null");
            }
            if (result.sensor.ideal) {
                return printf_text("%.6f", static_cast<double>(b.range_m));
            }
            return printf_text(unit < 0.005 ? "%.3f" : "%.2f", b.raw * unit);
        },
        false);
    list(
        "status",
        [&](std::size_t i) {
            return "\"" + std::string(core::ToString(scan.beams[i].status)) + "\"";
        },
        false);
    list(
        "labels",
        [&](std::size_t i) {
            return "\"" + std::string(core::ToString(result.scan.truth.labels[i])) + "\"";
        },
        false);
    list(
        "raw", [&](std::size_t i) { return std::to_string(unsigned{scan.beams[i].raw}); }, true);
    return json + "}\n";
}

}  // namespace casmap::pipeline
