#include "casmap/drivers/scan_codec.hpp"

#include <numbers>
#include <string>

#include "casmap/core/input_error.hpp"

namespace casmap::drivers {
namespace {
constexpr double kDegToRad = std::numbers::pi / 180.0;
}  // namespace

double StartAngleRad(const Variant& variant) {
    return -0.5 * static_cast<double>(variant.angle_deg) * kDegToRad;
}

double SweepDurationS(const Variant& variant) {
    const double turn_s = core::Lms200Timing::kTurnPeriodS;
    return static_cast<double>(variant.Turns() - 1) * turn_s +
           static_cast<double>(variant.angle_deg) / 360.0 * turn_s;
}

double ScanPeriodS(const Variant& variant) {
    return static_cast<double>(variant.Turns()) * core::Lms200Timing::kTurnPeriodS;
}

double TransmissionTimeS(std::size_t frame_bytes, int baud) {
    return static_cast<double>(frame_bytes) * ByteTimeS(baud);
}

core::Scan ScanFromValues(const MeasuredValues& values,
                          const core::Lms200Format& format,
                          const Variant& variant,
                          double stamp_s) {
    const std::size_t count = values.values.size();
    if (count != static_cast<std::size_t>(variant.BeamCount())) {
        throw MakeInputError("LMS 200 telegram 0xB0", "value count", std::to_string(count),
                             "variant " + std::to_string(variant.angle_deg) + " deg / " +
                                 std::to_string(variant.resolution_cdeg) + " cdeg has " +
                                 std::to_string(variant.BeamCount()));
    }
    core::Lms200Format f = format;
    f.units = values.units;
    core::Scan scan;
    scan.stamp_s = stamp_s;
    const double res_deg = static_cast<double>(variant.resolution_cdeg) / 100.0;
    scan.start_angle_rad = StartAngleRad(variant);
    scan.angle_step_rad = res_deg * kDegToRad;
    const double turn_s = core::Lms200Timing::kTurnPeriodS;
    scan.beam_period_s = res_deg / 360.0 * turn_s;
    const int turns = variant.Turns();
    if (turns > 1) {
        scan.beam_time_offset_s.resize(count);
        for (std::size_t i = 0; i < count; ++i) {
            scan.beam_time_offset_s[i] = static_cast<double>(static_cast<int>(i) % turns) * turn_s +
                                         static_cast<double>(i) * scan.beam_period_s;
        }
    }
    scan.beams.resize(count);
    for (std::size_t i = 0; i < count; ++i) {
        scan.beams[i] = f.Decode(values.values[i]);
    }
    return scan;
}

std::uint16_t EncodeBeam(const core::Beam& beam, const core::Lms200Format& format) {
    if (beam.raw != 0) {
        const core::Beam decoded = format.Decode(beam.raw);
        if (decoded.status == beam.status &&
            (beam.status != core::BeamStatus::kOk || decoded.range_m == beam.range_m)) {
            return beam.raw;
        }
    }
    if (beam.status == core::BeamStatus::kOk) {
        return format.EncodeRange(static_cast<double>(beam.range_m));
    }
    return format.CodeFor(beam.status);
}

void ValuesFromScan(const core::Scan& scan, const core::Lms200Format& format, MeasuredValues& out) {
    out.values.resize(scan.beams.size());
    for (std::size_t i = 0; i < scan.beams.size(); ++i) {
        out.values[i] = EncodeBeam(scan.beams[i], format);
    }
    out.units = format.units;
}

}  // namespace casmap::drivers
