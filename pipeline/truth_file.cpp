#include "casmap/pipeline/truth_file.hpp"

#include <algorithm>
#include <filesystem>

#include "casmap/core/check.hpp"
#include "casmap/io/image.hpp"
#include "casmap/io/output_set.hpp"
#include "casmap/io/scene_file.hpp"

namespace casmap::pipeline {

void TruthFileOptions::Validate() const {
    const core::Check check;
    const std::string ext = std::filesystem::path(out).extension().string();
    check.That(ext == ".tiff" || ext == ".tif", "out", out, "must end in .tiff or .tif");
    check.That(png.empty() || std::filesystem::path(png).extension() == ".png", "png", png,
               "must end in .png");
    grid.Validate();
    truth.Validate();
}

TruthFileResult WriteTruthFiles(const TruthFileOptions& o, int threads) {
    o.Validate();
    io::OutputSet outputs;  // TIFF and PNG: checked first, published together
    const std::filesystem::path tiff_tmp = outputs.AddFile(o.out, "out");
    const std::filesystem::path png_tmp =
        o.png.empty() ? std::filesystem::path() : outputs.AddFile(o.png, "png");
    const core::Scene scene = io::LoadScene(o.scene);
    TruthFileResult r;
    r.map = sim::GroundTruthElevation(scene, o.grid, o.truth, threads);
    io::WriteMapTiff(tiff_tmp, r.map);
    if (!o.png.empty()) {
        io::PngStyle style;
        style.title = "ground truth: " + o.scene;
        io::WriteMapPng(png_tmp, r.map, style);
    }
    outputs.Publish();
    const auto [lo, hi] = std::minmax_element(r.map.data.begin(), r.map.data.end());
    r.min_m = *lo;
    r.max_m = *hi;
    return r;
}

}  // namespace casmap::pipeline
