// casmap.filter, performance_index, cas_classes_percent, Grid, Mapper, map_scans: the mapper
// (Eq. 1-6), the five filters (Eq. 7-10 and the baselines) and the metrics (Eq. 11).
#include <pybind11/operators.h>
#include <pybind11/stl.h>

#include <cmath>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "bindings.hpp"
#include "casmap/core/input_error.hpp"
#include "casmap/mapper/filter_inputs.hpp"
#include "casmap/mapper/filters.hpp"
#include "casmap/mapper/metrics.hpp"
#include "casmap/mapper/terrain_mapper.hpp"
#include "casmap/mapper/unknown.hpp"
#include "casmap/pipeline/map_run.hpp"
#include "casmap/pipeline/stream_mapper.hpp"
#include "convert.hpp"

namespace casmap::python {
namespace {

py::tuple Filter(const std::string& method_name,
                 const py::handle& elevation_array,
                 const py::handle& certainty_array,
                 const std::vector<std::pair<std::string, std::string>>& params_text) {
    const mapper::FilterMethod method = mapper::ParseFilterMethod(method_name, "method");
    mapper::FilterParams params;
    for (const auto& [name, value] : params_text) {
        params.Set(name, value);
    }
    params.Validate();
    const core::MapF elevation = ToMap(elevation_array, "elevation");
    const core::MapF certainty =
        certainty_array.is_none() ? core::MapF() : ToMap(certainty_array, "certainty");
    mapper::CheckFilterInputs(method, elevation, certainty, params);  // the CLI's checks
    mapper::FilterResult result;
    {
        py::gil_scoped_release release;
        result = mapper::RunFilter(method, elevation, certainty, params);
    }
    if (!mapper::NeedsCertainty(method)) {  // the baselines; every CAS method has classes
        return py::make_tuple(FromMap(result.elevation), py::none());
    }
    return py::make_tuple(FromMap(result.elevation), FromClasses(result.classes));
}

mapper::Region RegionOf(const py::handle& region, int rows, int cols) {
    if (region.is_none()) {
        return mapper::PaperRegion(rows, cols);
    }
    if (py::isinstance<py::str>(region) && region.cast<std::string>() == "full") {
        return mapper::FullRegion(rows, cols);
    }
    const std::string rule =
        "must be None (the paper's region), 'full' or (row0, col0, rows, cols)";
    std::vector<int> t;
    try {
        t = region.cast<std::vector<int>>();
    } catch (const py::cast_error&) {  // a str other than 'full', floats, ...
        throw MakeInputError("", "region", std::string(py::repr(region)), rule);
    }
    if (t.size() != 4) {
        throw MakeInputError("", "region", std::to_string(t.size()) + " numbers", rule);
    }
    return mapper::Region{t[0], t[1], t[2], t[3]};
}

double PerformanceIndex(const py::handle& filtered,
                        const py::handle& raw,
                        const py::handle& truth,
                        const py::handle& region) {
    const core::MapF f = ToMap(filtered, "filtered");
    const core::MapF r = ToMap(raw, "raw");
    const core::MapF t = ToMap(truth, "truth");
    return mapper::PerformanceIndex(f, r, t, RegionOf(region, r.rows, r.cols));
}

py::dict Shares(const mapper::ClassShares& s) {
    py::dict d;
    d["cells"] = s.cells;
    d["removed"] = s.removed_pct;
    d["filled"] = s.filled_pct;
    d["untouched"] = s.untouched_pct;
    return d;
}

py::dict ClassesPercent(const py::handle& classes_array, const py::handle& certainty_array) {
    const core::Raster<std::uint8_t> classes = ToClasses(classes_array, "classes");
    core::MapF certainty;
    if (!certainty_array.is_none()) {
        certainty = ToMap(certainty_array, "certainty");
        if (certainty.rows != classes.rows || certainty.cols != classes.cols) {
            throw MakeInputError(
                "certainty", "shape",
                std::to_string(certainty.rows) + "x" + std::to_string(certainty.cols),
                "must equal the classes' " + std::to_string(classes.rows) + "x" +
                    std::to_string(classes.cols));
        }
    }
    const mapper::ClassReport report = mapper::ClassPercentages(classes, certainty);
    py::dict d = Shares(report.all);
    if (!certainty_array.is_none()) {
        d["observed"] = Shares(report.observed);
    }
    return d;
}

py::dict StatsDict(const mapper::MapperStats& s) {
    py::dict d;
    d["beams_seen"] = s.beams_seen;
    d["beams_not_ok"] = s.beams_not_ok;
    d["beams_rejected"] = s.beams_rejected;
    d["beams_no_pose"] = s.beams_no_pose;
    d["beams_outside"] = s.beams_outside;
    d["beams_mapped"] = s.beams_mapped;
    return d;
}

/// One scan from numpy: ranges_m float32 (B,), status uint8 (B,) and the scan geometry.
core::Scan MakeScan(double stamp_s,
                    const py::handle& ranges_m,
                    const py::handle& status,
                    const ScanGeometry& geometry) {
    const auto r = Checked<float>(ranges_m, "ranges_m", 1);
    const auto s = Checked<std::uint8_t>(status, "status", 1);
    if (s.shape(0) != r.shape(0)) {
        throw MakeInputError("", "status", "length " + std::to_string(s.shape(0)),
                             "must equal len(ranges_m) = " + std::to_string(r.shape(0)));
    }
    core::Scan scan;
    scan.stamp_s = stamp_s;
    scan.start_angle_rad = geometry.start_angle_rad;
    scan.angle_step_rad = geometry.angle_step_rad;
    scan.beam_period_s = geometry.beam_period_s;
    scan.beam_time_offset_s = geometry.beam_time_offset_s;
    scan.beams.resize(static_cast<std::size_t>(r.shape(0)));
    for (py::ssize_t i = 0; i < r.shape(0); ++i) {
        if (s.at(i) >= core::kBeamStatusCount) {
            throw MakeInputError("", "status[" + std::to_string(i) + "]", std::to_string(s.at(i)),
                                 "allowed: 0..6 (core::BeamStatus)");
        }
        core::Beam& b = scan.beams[static_cast<std::size_t>(i)];
        b.range_m = r.at(i);
        b.status = static_cast<core::BeamStatus>(s.at(i));
    }
    if (!scan.beam_time_offset_s.empty() && scan.beam_time_offset_s.size() != scan.beams.size()) {
        throw MakeInputError("", "beam_time_offset_s",
                             "length " + std::to_string(scan.beam_time_offset_s.size()),
                             "must equal len(ranges_m) = " + std::to_string(scan.beams.size()));
    }
    return scan;
}

}  // namespace

void BindMapper(py::module_& m) {
    py::class_<core::GridGeometry>(m, "Grid",
                                   "Map grid: cell (row, col) covers x in [x0_m + row cell_m, ...),"
                                   " y in [y0_m + col cell_m, ...); rows along-track.")
        .def(py::init([](double x0_m, double y0_m, double cell_m, int rows, int cols) {
                 core::GridGeometry g{x0_m, y0_m, cell_m, rows, cols};
                 g.Validate();
                 return g;
             }),
             py::arg("x0_m"), py::arg("y0_m"), py::arg("cell_m"), py::arg("rows"), py::arg("cols"))
        .def_readonly("x0_m", &core::GridGeometry::x0_m)
        .def_readonly("y0_m", &core::GridGeometry::y0_m)
        .def_readonly("cell_m", &core::GridGeometry::cell_m)
        .def_readonly("rows", &core::GridGeometry::rows)
        .def_readonly("cols", &core::GridGeometry::cols)
        .def(py::self == py::self)
        .def("__repr__", [](const core::GridGeometry& g) {
            return "casmap.Grid(x0_m=" + pipeline::FormatNumber(g.x0_m) +
                   ", y0_m=" + pipeline::FormatNumber(g.y0_m) +
                   ", cell_m=" + pipeline::FormatNumber(g.cell_m) +
                   ", rows=" + std::to_string(g.rows) + ", cols=" + std::to_string(g.cols) + ")";
        });

    m.def("_filter", &Filter);
    m.def("performance_index", &PerformanceIndex, py::arg("filtered"), py::arg("raw"),
          py::arg("truth"), py::arg("region") = py::none(),
          "Eq. 11: sum (h_f - h_t)^2 / sum (h_r - h_t)^2 over `region`: None = the paper's "
          "200 x 80 region centred in the map (as casmap bench), 'full', or "
          "(row0, col0, rows, cols).");
    m.def("cas_classes_percent", &ClassesPercent, py::arg("classes"),
          py::arg("certainty") = py::none(),
          "Table II shares (percent) of CAS's classes over the processed cells (border cells "
          "left out): {'cells', 'removed', 'filled', 'untouched'} and, given the certainty map, "
          "'observed': the same without never-observed cells that stayed empty.");

    py::class_<core::Trajectory>(m, "_Trajectory")
        .def(py::init(&ToTrajectory))
        .def("__len__", &core::Trajectory::size);

    py::class_<pipeline::StreamMapper>(m, "_Mapper")
        .def(py::init([](const core::GridGeometry& grid, int a, double delta_l_m,
                         double scan_period_s, const std::string& mapper_mode,
                         const std::string& unknown, const std::string& prefilter,
                         std::optional<double> consensus_spread_m, int consensus_min_hits,
                         const std::vector<std::string>& stage_sets) {
            pipeline::MapSettings settings;
            settings.a = a;
            settings.delta_l_m = delta_l_m;
            settings.mode = pipeline::ParseMapperMode(mapper_mode, "mapper");
            settings.unknown = mapper::ParseUnknown(unknown, "Mapper", "unknown");
            settings.prefilter = pipeline::ParsePrefilter(prefilter, "prefilter");
            if (consensus_spread_m) {
                if (settings.mode != pipeline::MapperMode::kConsensus) {
                    throw MakeInputError("Mapper", "consensus_spread_m",
                                         pipeline::FormatNumber(*consensus_spread_m),
                                         "the consensus mapper's parameter, but the mapper mode "
                                         "is " +
                                             std::string(pipeline::ToString(settings.mode)));
                }
                settings.consensus =
                    mapper::ConsensusConfig{*consensus_spread_m, consensus_min_hits};
            }
            pipeline::ApplyStageSettings(settings, stage_sets, "params");
            return pipeline::StreamMapper(grid, settings, scan_period_s);
        }))
        .def("add_scan",
             [](pipeline::StreamMapper& self, double stamp_s, const py::handle& ranges_m,
                const py::handle& status, const core::Trajectory& poses,
                const ScanGeometry& geometry) {
                 core::Scan scan = MakeScan(stamp_s, ranges_m, status, geometry);
                 py::gil_scoped_release release;
                 self.AddScan(std::move(scan), poses);
             })
        .def("finish", &pipeline::StreamMapper::Finish)
        .def_property_readonly(
            "elevation",
            [](const pipeline::StreamMapper& self) { return FromMap(self.elevation()); })
        .def_property_readonly(
            "certainty",
            [](const pipeline::StreamMapper& self) { return FromMap(self.certainty()); })
        .def_property_readonly("grid", &pipeline::StreamMapper::grid)
        .def_property_readonly("waiting", &pipeline::StreamMapper::waiting)
        .def_property_readonly("finished", &pipeline::StreamMapper::finished)
        .def_property_readonly(
            "stats", [](const pipeline::StreamMapper& self) { return StatsDict(self.stats()); });

    py::class_<ScanGeometry>(m, "_ScanGeometry")
        .def(py::init([](double start, double step, double period, std::vector<double> offsets) {
            return ScanGeometry{start, step, period, std::move(offsets)};
        }));

    m.def("_map_scans",
          [](const py::dict& run_dict, const py::handle& grid_or_none, double cell_m, int a,
             double delta_l_m, const std::string& mapper_mode, const std::string& unknown,
             const std::string& prefilter, const std::vector<std::string>& stage_sets) {
              const io::RunData run = RunFromDict(run_dict);
              std::optional<core::GridGeometry> grid;
              if (!grid_or_none.is_none()) {
                  grid = grid_or_none.cast<core::GridGeometry>();
              }
              pipeline::MapSettings settings;
              settings.a = a;
              settings.delta_l_m = delta_l_m;
              settings.mode = pipeline::ParseMapperMode(mapper_mode, "mapper");
              settings.unknown = mapper::ParseUnknown(unknown, "map_run", "unknown");
              settings.prefilter = pipeline::ParsePrefilter(prefilter, "prefilter");
              pipeline::ApplyStageSettings(settings, stage_sets, "params");  // validates
              pipeline::MappedRun mapped;
              {
                  py::gil_scoped_release release;
                  if (!grid) {
                      grid = pipeline::GridCoveringBeams(run.scans, run.poses, cell_m, "run");
                  }
                  mapped = pipeline::MapScans(run.scans, run.poses, *grid, settings);
              }
              py::dict d;
              d["elevation"] = FromMap(mapped.elevation);
              d["certainty"] = FromMap(mapped.certainty);
              d["grid"] = mapped.config.grid;
              d["scan_period_s"] = mapped.config.scan_period_s;
              d["stats"] = StatsDict(mapped.stats);
              return d;
          });
}

}  // namespace casmap::python
