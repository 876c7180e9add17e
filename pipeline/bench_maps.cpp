#include "casmap/pipeline/bench_maps.hpp"

#include <string>
#include <vector>

#include "casmap/io/atomic_file.hpp"
#include "casmap/io/image.hpp"
#include "casmap/pipeline/bench_pipelines.hpp"

namespace casmap::pipeline {
namespace {

std::string Layer(const std::string& name,
                  const std::string& label,
                  const std::string& kind,
                  const std::string& unit) {
    return "{\"name\": " + JsonString(name) + ", \"label\": " + JsonString(label) +
           ", \"kind\": " + JsonString(kind) + ", \"unit\": " + JsonString(unit) +
           ", \"file\": " + JsonString(name + ".tif") + "}";
}

}  // namespace

void WriteBenchMaps(const std::filesystem::path& dir,
                    const SheetMaps& maps,
                    const core::GridGeometry& grid) {
    io::EnsureDirectory(dir);
    std::string layers;
    const auto add = [&](const std::string& name, const core::MapF& map, const std::string& label,
                         const std::string& kind, const std::string& unit) {
        io::WriteMapTiff(dir / (name + ".tif"), map);
        layers += (layers.empty() ? "\n  " : ",\n  ") + Layer(name, label, kind, unit);
    };
    add("raw", maps.raw, "raw h", "elevation", "m");
    add("truth", maps.truth, "truth", "elevation", "m");
    std::vector<std::string> names;
    for (const auto& [name, map] : maps.filtered) {
        if (name != "raw") {  // pipeline "raw" is the raw map itself, written above
            names.push_back(name);
        }
    }
    for (const std::string& name : InPipelineOrder(names)) {  // the paper's five first
        add(name, maps.filtered.at(name), FilterDisplayName(name), "elevation", "m");
    }
    add("certainty", maps.certainty, "certainty", "certainty", "");
    if (maps.cas_classes.rows > 0) {
        core::MapF classes(maps.cas_classes.rows, maps.cas_classes.cols);
        for (std::size_t i = 0; i < classes.data.size(); ++i) {
            classes.data[i] = static_cast<float>(maps.cas_classes.data[i]);
        }
        add("cas_classes", classes, "CAS class", "classes", "");
    }
    const std::string json =
        "{\"grid\": {\"x0_m\": " + JsonNumber(grid.x0_m) + ", \"y0_m\": " + JsonNumber(grid.y0_m) +
        ", \"cell_m\": " + JsonNumber(grid.cell_m) + ", \"rows\": " + std::to_string(grid.rows) +
        ", \"cols\": " + std::to_string(grid.cols) + "},\n \"layers\": [" + layers + "\n]}\n";
    io::WriteTextAtomically(dir / "maps.json", json);
}

}  // namespace casmap::pipeline
