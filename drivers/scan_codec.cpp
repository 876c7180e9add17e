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

double TelegramPeriodS(const OutputMode& mode, const Variant& variant) {
    if (mode.kind == OutputKind::kPartial) {
        return core::Lms200Timing::kTurnPeriodS;
    }
    return ScanPeriodS(variant) * (mode.HasMean() ? static_cast<double>(mode.mean_scans) : 1.0);
}

double TelegramSweepS(const OutputMode& mode, const Variant& variant) {
    if (mode.kind == OutputKind::kPartial) {
        return static_cast<double>(variant.angle_deg) / 360.0 * core::Lms200Timing::kTurnPeriodS;
    }
    return SweepDurationS(variant);
}

core::Scan ScanFromFrame(const MeasuredValues& values,
                         const FrameExpectation& expect,
                         double sweep_stamp_s) {
    const Variant& variant = expect.variant;
    const OutputMode& mode = expect.mode;
    if (!mode.HasSubRange() && mode.kind != OutputKind::kPartial) {
        return ScanFromValues(values, expect.format, variant, sweep_stamp_s);
    }
    const int turns = variant.Turns();
    const int partial = mode.kind == OutputKind::kPartial ? PartialNumber(values, variant) : 0;
    const std::size_t count = values.values.size();
    if (count != static_cast<std::size_t>(ValueCount(mode, variant, partial))) {
        throw MakeInputError("LMS 200 telegram " + CommandName(values.command), "value count",
                             std::to_string(count), "does not match mode " + mode.ToString());
    }
    core::Lms200Format f = expect.format;
    f.units = values.units;
    const double res_rad = static_cast<double>(variant.resolution_cdeg) / 100.0 * kDegToRad;
    const double beam_s = static_cast<double>(variant.resolution_cdeg) / 100.0 / 360.0 *
                          core::Lms200Timing::kTurnPeriodS;
    const double turn_s = core::Lms200Timing::kTurnPeriodS;
    core::Scan scan;
    scan.beams.resize(count);
    for (std::size_t i = 0; i < count; ++i) {
        scan.beams[i] = f.Decode(values.values[i]);
    }
    if (mode.kind == OutputKind::kPartial) {  // beams p, p + turns, ... of one turn
        scan.start_angle_rad = StartAngleRad(variant) + partial * res_rad;
        scan.angle_step_rad = turns * res_rad;
        scan.beam_period_s = turns * beam_s;
        scan.stamp_s = sweep_stamp_s + partial * beam_s;
        return scan;
    }
    const int first = mode.first_beam - 1;  // global index of beam 0
    const auto global_time = [&](int g) { return (g % turns) * turn_s + g * beam_s; };
    scan.start_angle_rad = StartAngleRad(variant) + first * res_rad;
    scan.angle_step_rad = res_rad;
    scan.beam_period_s = beam_s;
    scan.stamp_s = sweep_stamp_s + global_time(first);
    if (turns > 1) {
        scan.beam_time_offset_s.resize(count);
        for (std::size_t i = 0; i < count; ++i) {
            scan.beam_time_offset_s[i] =
                global_time(first + static_cast<int>(i)) - global_time(first);
        }
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
