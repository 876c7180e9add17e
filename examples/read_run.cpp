// read_run: open a run file (`casmap simulate` or `casmap record` output), walk its scans and
// poses, and count the beams per status and, for simulated runs, per truth label.
//
//   read_run RUN.h5
#include <array>
#include <cstdio>
#include <exception>
#include <string>

#include "casmap/core/input_error.hpp"
#include "casmap/core/scan.hpp"
#include "casmap/io/run_file.hpp"

int main(int argc, char** argv) {
    if (argc != 2) {
        std::fprintf(stderr, "usage: %s RUN.h5\n", argv[0]);
        return 2;
    }
    try {
        // The whole run in memory: scans, per-beam truth (simulated runs), poses, maps.
        const casmap::io::RunData run = casmap::io::ReadRunFile(argv[1]);
        std::printf("%zu scans, %zu poses, seed %s\n", run.scans.size(), run.poses.size(),
                    run.seed ? std::to_string(*run.seed).c_str() : "none (recorded)");

        std::array<long, casmap::core::kBeamStatusCount> by_status{};
        std::array<long, casmap::core::kBeamLabelCount> by_label{};
        long with_pose = 0;
        for (std::size_t k = 0; k < run.scans.size(); ++k) {
            const casmap::core::Scan& scan = run.scans[k];
            for (std::size_t i = 0; i < scan.beams.size(); ++i) {
                ++by_status[static_cast<std::size_t>(scan.beams[i].status)];
                // The pose of beam i (world_T_sensor, interpolated), if the run covers its time.
                if (run.poses.PoseAt(scan.BeamTime(i))) {
                    ++with_pose;
                }
                if (!run.truth.empty()) {  // one ScanTruth per scan in simulated runs
                    ++by_label[static_cast<std::size_t>(run.truth[k].labels[i])];
                }
            }
        }
        std::printf("beams with a pose: %ld\n", with_pose);
        for (int s = 0; s < casmap::core::kBeamStatusCount; ++s) {
            const auto status = static_cast<casmap::core::BeamStatus>(s);
            std::printf("status %-10s %ld\n", std::string(ToString(status)).c_str(),
                        by_status[static_cast<std::size_t>(s)]);
        }
        for (int l = 0; !run.truth.empty() && l < casmap::core::kBeamLabelCount; ++l) {
            const auto label = static_cast<casmap::core::BeamLabel>(l);
            std::printf("label  %-10s %ld\n", std::string(ToString(label)).c_str(),
                        by_label[static_cast<std::size_t>(l)]);
        }
        return 0;
    } catch (const casmap::InputError& e) {
        std::fprintf(stderr, "read_run: %s\n", e.what());
        return 2;
    } catch (const std::exception& e) {
        std::fprintf(stderr, "read_run: error: %s\n", e.what());
        return 1;
    }
}
