#include "casmap/pipeline/demo.hpp"

#include <string>

#include "casmap/core/parallel.hpp"
#include "casmap/io/atomic_file.hpp"
#include "casmap/io/image.hpp"
#include "casmap/pipeline/filter_file.hpp"
#include "casmap/pipeline/map_run.hpp"

namespace casmap::pipeline {

DemoResult RunDemo(const DemoOptions& options, int threads) {
    options.params.Validate();
    mapper::SyntheticMapConfig config;
    config.seed = options.seed;
    config.a = options.params.cas.a;
    DemoResult r;
    r.map = mapper::BuildSyntheticMap(config);
    r.methods = mapper::AllFilterMethods();
    r.results.resize(r.methods.size());
    // One filter per item; each writes only its own slot, so threads change nothing.
    core::ParallelFor(r.methods.size(), threads, [&](std::size_t m) {
        r.results[m] =
            mapper::RunFilter(r.methods[m], r.map.elevation, r.map.certainty, options.params);
    });
    r.region = mapper::PaperRegion(r.map.truth.rows, r.map.truth.cols);
    for (const mapper::FilterResult& result : r.results) {
        r.metrics.push_back(mapper::EvaluateFilter(result, r.map.elevation, r.map.truth, r.region));
    }
    r.cas_classes = mapper::ClassPercentages(r.results[0].classes, r.map.certainty);
    return r;
}

void WriteDemoMaps(const DemoResult& r, const std::filesystem::path& dir) {
    io::EnsureDirectory(dir);
    const core::Raster<std::uint8_t> unknown = UnknownMask(r.map.certainty);
    WriteMapFiles(dir, "elevation", r.map.elevation, "raw elevation H", "m", &unknown);
    WriteMapFiles(dir, "certainty", r.map.certainty, "certainty C", "counts", &unknown);
    WriteMapFiles(dir, "truth", r.map.truth, "ground truth", "m", nullptr);
    for (std::size_t m = 0; m < r.methods.size(); ++m) {
        const std::string name(mapper::ToString(r.methods[m]));
        WriteMapFiles(dir, "filtered_" + name, r.results[m].elevation, "filtered: " + name, "m",
                      nullptr);
    }
    io::WriteClassesPng(dir / "cas_classes.png", r.results[0].classes, CasClassLegend(),
                        "CAS classes (Eq. 7)");
}

}  // namespace casmap::pipeline
