// Scores the wave-2 mapper modes and filters on simulated run files against their truth, over
// the paper's region (mapper::PaperRegion), without the benchmark pipeline:
//   build/bench/variants_score [--unknown nan] RUN.h5...
// Maps every run with TerrainMapper (Eq. 1-6; optionally with a scan pre-filter) and with
// KalmanMapper, runs the paper's filters and the CAS variants, and prints per run and map/filter
// PI, RMSE (all scored cells and truth edges), surviving spikes and coverage.
#include <cstdio>
#include <cstring>
#include <exception>
#include <string>
#include <vector>

#include "casmap/io/run_file.hpp"
#include "casmap/mapper/filters.hpp"
#include "casmap/mapper/kalman_mapper.hpp"
#include "casmap/mapper/metrics.hpp"
#include "casmap/mapper/scan_filters.hpp"
#include "casmap/mapper/terrain_mapper.hpp"

namespace {

using namespace casmap;

struct Maps {
    std::string name;
    core::MapF h, c;
};

double ScanPeriod(const std::vector<core::Scan>& scans) {
    return scans.size() > 1 ? (scans.back().stamp_s - scans.front().stamp_s) /
                                  static_cast<double>(scans.size() - 1)
                            : 1.0 / 75.0;
}

Maps MapRun(const io::RunData& run, mapper::Unknown unknown, int prefilter) {
    mapper::TerrainMapperConfig cfg;
    cfg.grid = *run.maps.grid;
    cfg.scan_period_s = ScanPeriod(run.scans);
    cfg.unknown = unknown;
    mapper::TerrainMapper m(cfg);
    for (const core::Scan& s : run.scans) {
        if (prefilter == 1) {
            m.AddScan(s, run.poses, mapper::ShadowFilterLabels(s, {}));
        } else if (prefilter == 2) {
            m.AddScan(s, run.poses, mapper::RangeJumpLabels(s, {}));
        } else {
            m.AddScan(s, run.poses);
        }
    }
    const char* names[] = {"raw", "raw+shadow", "raw+jump"};
    return {names[prefilter], m.elevation(), m.certainty()};
}

Maps KalmanRun(const io::RunData& run, mapper::Unknown unknown) {
    mapper::KalmanMapperConfig cfg;
    cfg.grid = *run.maps.grid;
    cfg.scan_period_s = ScanPeriod(run.scans);
    cfg.unknown = unknown;
    mapper::KalmanMapper m(cfg);
    for (const core::Scan& s : run.scans) {
        m.AddScan(s, run.poses);
    }
    return {"kalman", m.elevation(), m.certainty()};
}

void Print(const std::string& run, const std::string& what, const mapper::FilterMetrics& m) {
    std::printf("%-22s %-22s %7.3f %8.1f %8.1f %7lld %8.3f\n", run.c_str(), what.c_str(), m.pi,
                1000 * m.rmse_m, 1000 * m.edge_rmse_m, static_cast<long long>(m.spikes),
                m.coverage);
}

}  // namespace

int main(int argc, char** argv) {
    mapper::Unknown unknown = mapper::Unknown::kZero;
    int first = 1;
    if (argc > 2 && std::strcmp(argv[1], "--unknown") == 0) {
        unknown = mapper::ParseUnknown(argv[2], "command line", "--unknown");
        first = 3;
    }
    if (argc <= first) {
        std::fprintf(stderr, "usage: variants_score [--unknown zero|nan] RUN.h5...\n");
        return 2;
    }
    try {
        std::printf("%-22s %-22s %7s %8s %8s %7s %8s\n", "run", "map/filter", "PI", "rmse_mm",
                    "edge_mm", "spikes", "coverage");
        for (int a = first; a < argc; ++a) {
            const io::RunData run = io::ReadRunFile(argv[a]);
            if (!run.maps.grid || !run.maps.truth_m) {
                std::fprintf(stderr, "%s: /maps: needs a simulated run with truth\n", argv[a]);
                return 2;
            }
            const core::MapF& truth = *run.maps.truth_m;
            const mapper::Region region = mapper::PaperRegion(truth.rows, truth.cols);
            const Maps raw = MapRun(run, unknown, 0);
            mapper::FilterParams params;
            params.Set("unknown", std::string(mapper::ToString(unknown)));
            std::string name = argv[a];
            name = name.substr(name.find_last_of('/') + 1);
            for (const Maps& maps :
                 {raw, MapRun(run, unknown, 1), MapRun(run, unknown, 2), KalmanRun(run, unknown)}) {
                // Every map is scored against the plain raw map's error (Eq. 11's denominator).
                Print(name, maps.name, mapper::EvaluateFilter({maps.h, {}}, raw.h, truth, region));
            }
            for (const mapper::FilterMethod f : mapper::AllFilterMethodsWithVariants()) {
                const mapper::FilterResult r = mapper::RunFilter(f, raw.h, raw.c, params);
                Print(name, std::string(mapper::ToString(f)),
                      mapper::EvaluateFilter(r, raw.h, truth, region));
            }
        }
    } catch (const std::exception& e) {
        std::fprintf(stderr, "%s\n", e.what());
        return 2;
    }
    return 0;
}
