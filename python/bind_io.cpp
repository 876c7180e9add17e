// casmap.read_run, write_run (HDF5 run files, docs/run-file.md) and the map TIFFs.
#include <pybind11/stl.h>
#include <pybind11/stl/filesystem.h>

#include <algorithm>
#include <filesystem>
#include <limits>
#include <string>

#include "bindings.hpp"
#include "casmap/core/input_error.hpp"
#include "casmap/io/image.hpp"
#include "convert.hpp"

namespace casmap::python {
namespace {

template <typename T>
py::array_t<T> Matrix(std::size_t rows, std::size_t cols) {
    return py::array_t<T>({static_cast<py::ssize_t>(rows), static_cast<py::ssize_t>(cols)});
}

py::dict ScansToDict(const io::RunData& run) {
    const std::size_t n = run.scans.size();
    const std::size_t b = n == 0 ? 0 : run.scans.front().beams.size();
    py::array_t<double> stamp(static_cast<py::ssize_t>(n));
    auto ranges = Matrix<float>(n, b);
    auto raw = Matrix<std::uint16_t>(n, b);
    auto status = Matrix<std::uint8_t>(n, b);
    for (std::size_t k = 0; k < n; ++k) {
        const core::Scan& s = run.scans[k];
        stamp.mutable_at(k) = s.stamp_s;
        for (std::size_t i = 0; i < b; ++i) {
            ranges.mutable_at(k, i) = s.beams[i].range_m;
            raw.mutable_at(k, i) = s.beams[i].raw;
            status.mutable_at(k, i) = static_cast<std::uint8_t>(s.beams[i].status);
        }
    }
    py::dict d;
    d["stamp_s"] = stamp;
    d["ranges_m"] = ranges;
    d["raw"] = raw;
    d["status"] = status;
    d["labels"] = py::none();
    d["true_range_m"] = py::none();
    if (!run.truth.empty()) {
        auto labels = Matrix<std::uint8_t>(n, b);
        auto true_range = Matrix<float>(n, b);
        for (std::size_t k = 0; k < n; ++k) {
            for (std::size_t i = 0; i < b; ++i) {
                labels.mutable_at(k, i) = static_cast<std::uint8_t>(run.truth[k].labels[i]);
                true_range.mutable_at(k, i) = run.truth[k].true_range_m[i];
            }
        }
        d["labels"] = labels;
        d["true_range_m"] = true_range;
    }
    const core::Scan first = n == 0 ? core::Scan{} : run.scans.front();
    d["start_angle_rad"] = first.start_angle_rad;
    d["angle_step_rad"] = first.angle_step_rad;
    d["beam_period_s"] = first.beam_period_s;
    d["beam_time_offset_s"] = first.beam_time_offset_s.empty()
                                  ? py::object(py::none())
                                  : py::object(py::array_t<double>(
                                        static_cast<py::ssize_t>(first.beam_time_offset_s.size()),
                                        first.beam_time_offset_s.data()));
    return d;
}

py::dict PosesToDict(const core::Trajectory& poses) {
    const std::size_t p = poses.size();
    py::array_t<double> stamp(static_cast<py::ssize_t>(p));
    auto xyz = Matrix<double>(p, 3);
    auto quat = Matrix<double>(p, 4);
    for (std::size_t i = 0; i < p; ++i) {
        const core::TimedPose& s = poses.samples()[i];
        stamp.mutable_at(i) = s.stamp_s;
        for (int j = 0; j < 3; ++j) {
            xyz.mutable_at(i, j) = s.world_T_sensor.translation[j];
        }
        const Eigen::Quaterniond& q = s.world_T_sensor.rotation;
        quat.mutable_at(i, 0) = q.x();
        quat.mutable_at(i, 1) = q.y();
        quat.mutable_at(i, 2) = q.z();
        quat.mutable_at(i, 3) = q.w();
    }
    py::dict d;
    d["stamp_s"] = stamp;
    d["xyz_m"] = xyz;
    d["quat_xyzw"] = quat;
    return d;
}

py::object OptionalMap(const std::optional<core::MapF>& map) {
    return map ? py::object(FromMap(*map)) : py::object(py::none());
}

py::dict MapsToDict(const io::RunMaps& maps) {
    py::dict d;
    d["grid"] = maps.grid ? py::cast(*maps.grid) : py::object(py::none());
    d["elevation_m"] = OptionalMap(maps.elevation_m);
    d["certainty"] = OptionalMap(maps.certainty);
    d["truth_m"] = OptionalMap(maps.truth_m);
    py::dict filtered;
    for (const auto& [name, map] : maps.filtered) {
        filtered[py::str(name)] = FromMap(map);
    }
    d["filtered"] = filtered;
    return d;
}

// Key `key` of `d`; InputError naming `where.key` if it is missing.
py::object Get(const py::dict& d, const std::string& where, const char* key) {
    if (!d.contains(key)) {
        throw MakeInputError("", where + key, "missing", "required key");
    }
    return d[key];
}

std::optional<core::MapF> MapOrNone(const py::dict& d, const char* key) {
    const py::object v = Get(d, "maps.", key);
    return v.is_none() ? std::nullopt
                       : std::optional<core::MapF>(ToMap(v, "maps." + std::string(key)));
}

void ScansFromDict(const py::dict& d, io::RunData& run) {
    const auto stamp = Checked<double>(Get(d, "scans.", "stamp_s"), "scans.stamp_s", 1);
    const auto ranges = Checked<float>(Get(d, "scans.", "ranges_m"), "scans.ranges_m", 2);
    const auto raw = Checked<std::uint16_t>(Get(d, "scans.", "raw"), "scans.raw", 2);
    const auto status = Checked<std::uint8_t>(Get(d, "scans.", "status"), "scans.status", 2);
    const py::ssize_t n = ranges.shape(0);
    const py::ssize_t b = ranges.shape(1);
    const auto same = [&](const py::array& a, const char* name) {
        if (a.shape(0) != n || (a.ndim() == 2 && a.shape(1) != b)) {
            throw MakeInputError(
                "", std::string("scans.") + name, "wrong shape",
                "must match scans.ranges_m (" + std::to_string(n) + ", " + std::to_string(b) + ")");
        }
    };
    same(stamp, "stamp_s");
    same(raw, "raw");
    same(status, "status");
    std::vector<double> offsets;
    if (const py::object o = Get(d, "scans.", "beam_time_offset_s"); !o.is_none()) {
        const auto a = Checked<double>(o, "scans.beam_time_offset_s", 1);
        offsets.assign(a.data(), a.data() + a.shape(0));
    }
    const py::object labels_obj = Get(d, "scans.", "labels");
    const py::object true_obj = Get(d, "scans.", "true_range_m");
    py::array_t<std::uint8_t, py::array::c_style> labels;
    py::array_t<float, py::array::c_style> true_range;
    if (!labels_obj.is_none()) {
        labels = Checked<std::uint8_t>(labels_obj, "scans.labels", 2);
        true_range = true_obj.is_none() ? py::array_t<float, py::array::c_style>({n, b})
                                        : Checked<float>(true_obj, "scans.true_range_m", 2);
        if (true_obj.is_none()) {
            std::fill_n(true_range.mutable_data(), n * b, std::numeric_limits<float>::quiet_NaN());
        }
        same(labels, "labels");
        same(true_range, "true_range_m");
    }
    const double start = Get(d, "scans.", "start_angle_rad").cast<double>();
    const double step = Get(d, "scans.", "angle_step_rad").cast<double>();
    const double period = Get(d, "scans.", "beam_period_s").cast<double>();
    run.scans.resize(static_cast<std::size_t>(n));
    for (py::ssize_t k = 0; k < n; ++k) {
        core::Scan& s = run.scans[static_cast<std::size_t>(k)];
        s = core::Scan{stamp.at(k), start, step, period, offsets, {}};
        s.beams.resize(static_cast<std::size_t>(b));
        for (py::ssize_t i = 0; i < b; ++i) {
            if (status.at(k, i) >= core::kBeamStatusCount) {
                throw MakeInputError(
                    "", "scans.status[" + std::to_string(k) + ", " + std::to_string(i) + "]",
                    std::to_string(status.at(k, i)), "allowed: 0..6");
            }
            s.beams[static_cast<std::size_t>(i)] = core::Beam{
                ranges.at(k, i), static_cast<core::BeamStatus>(status.at(k, i)), raw.at(k, i)};
        }
        if (!labels_obj.is_none()) {
            core::ScanTruth t;
            for (py::ssize_t i = 0; i < b; ++i) {
                if (labels.at(k, i) >= core::kBeamLabelCount) {
                    throw MakeInputError(
                        "", "scans.labels[" + std::to_string(k) + ", " + std::to_string(i) + "]",
                        std::to_string(labels.at(k, i)), "allowed: 0..4");
                }
                t.labels.push_back(static_cast<core::BeamLabel>(labels.at(k, i)));
                t.true_range_m.push_back(true_range.at(k, i));
            }
            run.truth.push_back(std::move(t));
        }
    }
}

}  // namespace

py::dict RunToDict(const io::RunData& run) {
    py::dict d;
    d["scans"] = ScansToDict(run);
    d["poses"] = PosesToDict(run.poses);
    d["maps"] = MapsToDict(run.maps);
    d["seed"] = run.seed ? py::cast(*run.seed) : py::object(py::none());
    d["config_yaml"] = run.config_yaml;
    if (run.format) {
        d["format"] =
            py::make_tuple(run.format->mode == core::RangeMode::k8m    ? "8m"
                           : run.format->mode == core::RangeMode::k16m ? "16m"
                                                                       : "32m",
                           run.format->units == core::RangeUnits::kMillimetre ? "mm" : "cm");
    } else {
        d["format"] = py::none();
    }
    return d;
}

io::RunData RunFromDict(const py::dict& d) {
    io::RunData run;
    ScansFromDict(Get(d, "", "scans").cast<py::dict>(), run);
    const py::dict poses = Get(d, "", "poses").cast<py::dict>();
    run.poses = ToTrajectory(Get(poses, "poses.", "stamp_s"), Get(poses, "poses.", "xyz_m"),
                             Get(poses, "poses.", "quat_xyzw"));
    const py::dict maps = Get(d, "", "maps").cast<py::dict>();
    if (const py::object g = Get(maps, "maps.", "grid"); !g.is_none()) {
        run.maps.grid = g.cast<core::GridGeometry>();
    }
    run.maps.elevation_m = MapOrNone(maps, "elevation_m");
    run.maps.certainty = MapOrNone(maps, "certainty");
    run.maps.truth_m = MapOrNone(maps, "truth_m");
    for (const auto& [name, map] : Get(maps, "maps.", "filtered").cast<py::dict>()) {
        const std::string key = py::str(name);
        run.maps.filtered[key] = ToMap(map, "maps.filtered." + key);
    }
    if (const py::object seed = Get(d, "", "seed"); !seed.is_none()) {
        run.seed = seed.cast<std::uint64_t>();
    }
    run.config_yaml = Get(d, "", "config_yaml").cast<std::string>();
    if (const py::object f = Get(d, "", "format"); !f.is_none()) {
        const auto [mode, units] = f.cast<std::pair<std::string, std::string>>();
        core::Lms200Format format;
        if (mode != "8m" && mode != "16m" && mode != "32m") {
            throw MakeInputError("", "format[0]", mode, "allowed: 8m|16m|32m");
        }
        if (units != "mm" && units != "cm") {
            throw MakeInputError("", "format[1]", units, "allowed: mm|cm");
        }
        format.mode = mode == "8m"    ? core::RangeMode::k8m
                      : mode == "16m" ? core::RangeMode::k16m
                                      : core::RangeMode::k32m;
        format.units =
            units == "mm" ? core::RangeUnits::kMillimetre : core::RangeUnits::kCentimetre;
        run.format = format;
    }
    return run;
}

void BindIo(py::module_& m) {
    m.def("_read_run", [](const std::filesystem::path& path) {
        io::RunData run;
        {
            py::gil_scoped_release release;
            run = io::ReadRunFile(path);
        }
        return RunToDict(run);
    });
    m.def("_write_run", [](const std::filesystem::path& path, const py::dict& d) {
        const io::RunData run = RunFromDict(d);
        py::gil_scoped_release release;
        io::WriteRunFile(path, run);
    });
    m.def(
        "read_map_tiff",
        [](const std::filesystem::path& path) { return FromMap(io::ReadMapTiff(path)); },
        py::arg("path"),
        "A single-channel 32-bit float TIFF (casmap map/filter output) as a float32 array, "
        "rows along-track.");
    m.def(
        "write_map_tiff",
        [](const std::filesystem::path& path, const py::handle& map) {
            io::WriteMapTiff(path, ToMap(map, "map"));
        },
        py::arg("path"), py::arg("map"),
        "Writes a 2-D float32 array as a 32-bit float TIFF, atomically.");
}

}  // namespace casmap::python
