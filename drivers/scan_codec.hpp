#pragma once

// Conversion between 0xB0 measured values and core::Scan, and the LMS 200 timing the driver
// uses for its latency correction.

#include <cstddef>
#include <cstdint>

#include "casmap/core/lms200.hpp"
#include "casmap/core/scan.hpp"
#include "casmap/drivers/output_mode.hpp"
#include "casmap/drivers/telegram.hpp"

namespace casmap::drivers {

/// First beam's angle (rad, sensor frame): -90 deg for the 180 deg field, -50 deg for the
/// 100 deg field (which covers the physical 40..140 deg of the 180 deg frame).
[[nodiscard]] double StartAngleRad(const Variant& variant);
/// Seconds from beam 0 to the last beam of a complete scan: (turns - 1) mirror turns plus the
/// angular sweep of the field at 75 Hz.
[[nodiscard]] double SweepDurationS(const Variant& variant);
/// Seconds between completed scans: turns / 75 Hz.
[[nodiscard]] double ScanPeriodS(const Variant& variant);
/// Seconds a telegram of `frame_bytes` takes on the line at `baud` (10 bits per byte).
[[nodiscard]] double TransmissionTimeS(std::size_t frame_bytes, int baud);

/// Measured values -> Scan with beam 0 at `stamp_s`. The value mask (measuring mode) comes from
/// `format`; the units come from the telegram header. Beam timing: beam i is taken in turn
/// (i mod turns) at angle i * resolution, i.e. stamp_s + (i mod turns) / 75 + angle / (360 * 75).
/// Throws InputError if the value count does not match the variant.
[[nodiscard]] core::Scan ScanFromValues(const MeasuredValues& values,
                                        const core::Lms200Format& format,
                                        const Variant& variant,
                                        double stamp_s);

/// Seconds between telegrams of `mode` on the sweep grid: the scan period (continuous,
/// sub-range), n scan periods (mean values), one mirror turn (partial scans).
[[nodiscard]] double TelegramPeriodS(const OutputMode& mode, const Variant& variant);
/// Seconds from beam 0 of the last sweep a telegram carries to the end of that sweep:
/// SweepDurationS(variant), or one turn's angular sweep for a partial scan.
[[nodiscard]] double TelegramSweepS(const OutputMode& mode, const Variant& variant);

/// Any measured-value telegram -> Scan over the beams it carries. `sweep_stamp_s` is the time
/// of beam 0 of the (last) complete sweep, or of the turn for a partial scan. Sub-ranges start
/// at beam first - 1 (start_angle_rad and stamp_s moved accordingly; in interleaved variants
/// beam_time_offset_s may be negative for beams measured in an earlier turn than the first);
/// a partial scan p carries beams p, p + turns, ... of one turn (angle step = turns x
/// resolution). Mean values are stamped like their last scan. Throws InputError if the value
/// count does not match `mode` and `variant`.
[[nodiscard]] core::Scan ScanFromFrame(const MeasuredValues& values,
                                       const FrameExpectation& expect,
                                       double sweep_stamp_s);

/// One beam as a raw word: its `raw` field when that decodes back to the same status and range
/// under `format`, otherwise the range (or the status's special code) encoded in `format`.
[[nodiscard]] std::uint16_t EncodeBeam(const core::Beam& beam, const core::Lms200Format& format);

/// Scan -> measured values in `format` (values in `out`, reusing its capacity).
void ValuesFromScan(const core::Scan& scan, const core::Lms200Format& format, MeasuredValues& out);

}  // namespace casmap::drivers
