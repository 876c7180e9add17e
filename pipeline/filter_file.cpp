#include "casmap/pipeline/filter_file.hpp"

#include "casmap/core/check.hpp"
#include "casmap/mapper/filter_inputs.hpp"

namespace casmap::pipeline {
namespace fs = std::filesystem;

void FilterFileOptions::Validate() const {
    const mapper::FilterMethod m = mapper::ParseFilterMethod(method, "method");
    params.Validate();
    const core::Check check;
    const fs::path path(out);
    const std::string ext = path.extension().string();
    check.That(ext == ".tiff" || ext == ".tif", "out", out, "must end in .tiff or .tif");
    const fs::path dir = path.has_parent_path() ? path.parent_path() : fs::path(".");
    check.That(fs::is_directory(dir), "out", out, "directory " + dir.string() + " does not exist");
    if (mapper::NeedsCertainty(m) && certainty.empty()) {  // before reading any map
        mapper::CheckFilterInputs(m, {}, {}, params);
    }
}

const std::vector<io::ClassLegendEntry>& CasClassLegend() {
    static const std::vector<io::ClassLegendEntry> legend = {
        {"untouched", 200, 200, 200},
        {"removed", 40, 40, 220},
        {"filled", 220, 120, 30},
        {"border", 90, 90, 90},
    };
    return legend;
}

fs::path BesideOutput(const fs::path& out, const std::string& suffix, const std::string& ext) {
    return out.parent_path() / (out.stem().string() + suffix + ext);
}

FilterFileResult FilterMapFiles(const FilterFileOptions& o) {
    o.Validate();
    const mapper::FilterMethod method = mapper::ParseFilterMethod(o.method, "method");
    const core::MapF elevation = io::ReadMapTiff(o.elevation);
    const core::MapF certainty = o.certainty.empty() ? core::MapF() : io::ReadMapTiff(o.certainty);
    mapper::CheckFilterInputs(method, elevation, certainty, o.params, {o.elevation, o.certainty});

    FilterFileResult r;
    r.result = mapper::RunFilter(method, elevation, certainty, o.params);
    core::Raster<std::uint8_t> unknown;  // never observed and left empty by the filter
    if (!certainty.data.empty()) {
        unknown = core::Raster<std::uint8_t>(certainty.rows, certainty.cols, 0);
        for (std::size_t i = 0; i < certainty.data.size(); ++i) {
            unknown.data[i] = certainty.data[i] == 0.0F && r.result.elevation.data[i] == 0.0F;
        }
    }
    io::PngStyle style;
    style.title = "casmap filter --method " + o.method;
    style.unknown = unknown.data.empty() ? nullptr : &unknown;

    const fs::path out(o.out);
    r.written = {out, BesideOutput(out, "", ".png")};
    io::WriteMapTiff(r.written[0], r.result.elevation);
    io::WriteMapPng(r.written[1], r.result.elevation, style);
    if (mapper::NeedsCertainty(method)) {
        core::MapF codes(r.result.classes.rows, r.result.classes.cols);
        for (std::size_t i = 0; i < codes.data.size(); ++i) {
            codes.data[i] = static_cast<float>(r.result.classes.data[i]);
        }
        r.written.push_back(BesideOutput(out, "_classes", ".tiff"));
        io::WriteMapTiff(r.written.back(), codes);
        r.written.push_back(BesideOutput(out, "_classes", ".png"));
        io::WriteClassesPng(r.written.back(), r.result.classes, CasClassLegend(),
                            "CAS classes (Eq. 7)");
        r.classes = mapper::ClassPercentages(r.result.classes, certainty);
    }
    return r;
}

}  // namespace casmap::pipeline
