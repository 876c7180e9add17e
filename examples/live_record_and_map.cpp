// live_record_and_map: an LMS 200 on a serial line -> the terrain mapper, no simulator needed
// (builds in the robot build, -DCASMAP_BUILD_SIM=OFF).
//
//   live_record_and_map DEVICE [SCANS] [SPEED_M_S]
//
// DEVICE is a real scanner (/dev/ttyUSB0) or the virtual one: `casmap serve --run RUN.h5
// --link /tmp/lms` in another shell, then `live_record_and_map /tmp/lms 100`. A robot would take
// the sensor pose from its odometry; here the scanner is assumed to move along world +x at
// SPEED_M_S (default 0.5), 1 m above the floor, pitched 40 deg down (the paper's table in test T).
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <optional>

#include "casmap/core/input_error.hpp"
#include "casmap/core/trajectory.hpp"
#include "casmap/drivers/lms200_driver.hpp"
#include "casmap/mapper/terrain_mapper.hpp"

namespace {
// world_T_sensor at `t_s` seconds after the first scan.
casmap::core::Pose AssumedPose(double t_s, double speed_m_s) {
    const double pitch_rad = 40.0 * 3.14159265358979 / 180.0;  // nose down
    return casmap::core::PoseFromXyzRpy({speed_m_s * t_s, 0.0, 1.0}, {0.0, pitch_rad, 0.0});
}
}  // namespace

int main(int argc, char** argv) {
    if (argc < 2) {
        std::fprintf(stderr, "usage: %s DEVICE [SCANS] [SPEED_M_S]\n", argv[0]);
        return 2;
    }
    const int scans_wanted = argc > 2 ? std::atoi(argv[2]) : 100;
    const double speed_m_s = argc > 3 ? std::atof(argv[3]) : 0.5;
    try {
        // 1. Connect: 9600 baud, then the driver switches to config.baud and starts streaming.
        casmap::drivers::DriverConfig config;
        config.device = argv[1];
        casmap::drivers::Lms200Driver driver(config);
        driver.Connect();

        // 2. A map 4 m along-track from x = 0.5 m, 2 m across, 25 mm cells (the paper's grid).
        casmap::mapper::TerrainMapperConfig mc;
        mc.grid = {0.5, -1.0, 0.025, 160, 80};
        casmap::mapper::TerrainMapper mapper(mc);

        // 3. Each scan with the poses over its sweep (scans are stamped on the system clock).
        std::optional<double> t0_s;
        int scans = 0;
        while (scans < scans_wanted) {
            const std::optional<casmap::core::Scan> scan = driver.NextScan(2.0);
            if (!scan) {
                break;  // no scan for 2 s: the stream ended
            }
            if (!t0_s) {
                t0_s = scan->stamp_s;
            }
            // Poses over 0.1 s cover the sweep (13.3 ms; 53 ms in the interleaved 0.25 deg mode).
            const double t_s = scan->stamp_s - *t0_s;
            const casmap::core::Trajectory poses(
                {{scan->stamp_s, AssumedPose(t_s, speed_m_s)},
                 {scan->stamp_s + 0.1, AssumedPose(t_s + 0.1, speed_m_s)}});
            mapper.AddScan(*scan, poses);
            ++scans;
        }
        driver.Close();

        // 4. What the mapper did (mapper.elevation() and certainty() hold the maps).
        long observed = 0;
        for (const float c : mapper.certainty().data) {
            observed += c > 0.0F;
        }
        std::printf("%d scans, %llu of %llu beams mapped; %ld of %zu cells observed\n", scans,
                    static_cast<unsigned long long>(mapper.stats().beams_mapped),
                    static_cast<unsigned long long>(mapper.stats().beams_seen), observed,
                    mapper.certainty().data.size());
        return scans > 0 ? 0 : 1;
    } catch (const casmap::InputError& e) {
        std::fprintf(stderr, "live_record_and_map: %s\n", e.what());
        return 2;
    } catch (const std::exception& e) {  // SerialError: no LMS 200 answered
        std::fprintf(stderr, "live_record_and_map: error: %s\n", e.what());
        return 1;
    }
}
