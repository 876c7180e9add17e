// filter_tiff: the CAS filter on an elevation/certainty TIFF pair, then Table II's classes.
//
//   filter_tiff H.tiff C.tiff [NAME=VALUE ...]
//
// H.tiff holds elevations (metres) and C.tiff certainty counts, both single-channel 32-bit float
// with rows along-track (what `casmap map` writes). NAME=VALUE pairs set CAS parameters by the
// names `casmap filter --set` takes, e.g. `k=3` or `A=12`. Prints the share of removed, filled
// and untouched cells, as the paper's Table II does.
#include <cstdio>
#include <exception>

#include "casmap/core/input_error.hpp"
#include "casmap/io/image.hpp"
#include "casmap/mapper/filters.hpp"
#include "casmap/mapper/metrics.hpp"

int main(int argc, char** argv) {
    if (argc < 3) {
        std::fprintf(stderr, "usage: %s H.tiff C.tiff [NAME=VALUE ...]\n", argv[0]);
        return 2;
    }
    try {
        // 1. Read the maps (InputError names the file if it is not a float TIFF).
        const casmap::core::MapF elevation = casmap::io::ReadMapTiff(argv[1]);
        const casmap::core::MapF certainty = casmap::io::ReadMapTiff(argv[2]);

        // 2. The paper's parameters, overridden by NAME=VALUE arguments.
        casmap::mapper::FilterParams params;
        for (int i = 3; i < argc; ++i) {
            params.SetAssignment(argv[i]);
        }
        params.Validate();

        // 3. Filter. `classes` says per pixel what Eq. 7 did (untouched/removed/filled/border).
        const casmap::mapper::FilterResult result = casmap::mapper::RunFilter(
            casmap::mapper::FilterMethod::kCas, elevation, certainty, params);

        // 4. Table II: shares over the processed cells (all of them, and without cells that
        //    were never observed and stayed empty).
        const casmap::mapper::ClassReport report =
            casmap::mapper::ClassPercentages(result.classes, certainty);
        std::printf("A = %g, G = %g, %dx%d cells\n", params.cas.EffectiveA(),
                    params.cas.EffectiveG(), elevation.rows, elevation.cols);
        std::printf("all:      removed %.2f %%  filled %.2f %%  untouched %.2f %%\n",
                    report.all.removed_pct, report.all.filled_pct, report.all.untouched_pct);
        std::printf("observed: removed %.2f %%  filled %.2f %%  untouched %.2f %%\n",
                    report.observed.removed_pct, report.observed.filled_pct,
                    report.observed.untouched_pct);
        return 0;
    } catch (const casmap::InputError& e) {
        std::fprintf(stderr, "filter_tiff: %s\n", e.what());  // bad file or parameter
        return 2;
    } catch (const std::exception& e) {
        std::fprintf(stderr, "filter_tiff: error: %s\n", e.what());
        return 1;
    }
}
