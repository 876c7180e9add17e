#include "convert.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <vector>

#include "casmap/core/input_error.hpp"
#include "casmap/mapper/filters.hpp"

namespace casmap::python {
namespace {

std::string Shape(const py::array& a) {
    std::string s = "(";
    for (py::ssize_t i = 0; i < a.ndim(); ++i) {
        s += (i ? ", " : "") + std::to_string(a.shape(i));
    }
    return s + (a.ndim() == 1 ? ",)" : ")");
}

template <typename T>
const char* TypeName() {
    if constexpr (std::is_same_v<T, float>) {
        return "float32";
    } else if constexpr (std::is_same_v<T, double>) {
        return "float64";
    } else if constexpr (std::is_same_v<T, std::uint8_t>) {
        return "uint8";
    } else {
        return "uint16";
    }
}

}  // namespace

template <typename T>
py::array_t<T, py::array::c_style> Checked(const py::handle& array,
                                           const std::string& name,
                                           int ndim) {
    if (!py::isinstance<py::array>(array)) {
        throw MakeInputError("", name, std::string(py::str(py::type::of(array))),
                             std::string("must be a numpy array of ") + TypeName<T>());
    }
    const auto a = py::reinterpret_borrow<py::array>(array);
    if (!a.dtype().is(py::dtype::of<T>())) {
        throw MakeInputError("", name, std::string(py::str(a.dtype())) + " array",
                             std::string("must have dtype ") + TypeName<T>() +
                                 " (convert with .astype(numpy." + TypeName<T>() + "))");
    }
    if (ndim >= 0 && a.ndim() != ndim) {
        throw MakeInputError("", name, "shape " + Shape(a),
                             "must have " + std::to_string(ndim) + " dimensions");
    }
    return py::array_t<T, py::array::c_style>::ensure(a);
}

template py::array_t<float, py::array::c_style> Checked<float>(const py::handle&,
                                                               const std::string&,
                                                               int);
template py::array_t<double, py::array::c_style> Checked<double>(const py::handle&,
                                                                 const std::string&,
                                                                 int);
template py::array_t<std::uint8_t, py::array::c_style> Checked<std::uint8_t>(const py::handle&,
                                                                             const std::string&,
                                                                             int);
template py::array_t<std::uint16_t, py::array::c_style> Checked<std::uint16_t>(const py::handle&,
                                                                               const std::string&,
                                                                               int);

core::MapF ToMap(const py::handle& array, const std::string& name) {
    const auto a = Checked<float>(array, name, 2);
    core::MapF map(static_cast<int>(a.shape(0)), static_cast<int>(a.shape(1)));
    std::copy_n(a.data(), map.data.size(), map.data.begin());
    return map;
}

py::array_t<float> FromMap(const core::MapF& map) {
    py::array_t<float> out({map.rows, map.cols});
    std::copy(map.data.begin(), map.data.end(), out.mutable_data());
    return out;
}

py::array_t<std::uint8_t> FromClasses(const core::Raster<std::uint8_t>& raster) {
    py::array_t<std::uint8_t> out({raster.rows, raster.cols});
    std::copy(raster.data.begin(), raster.data.end(), out.mutable_data());
    return out;
}

core::Raster<std::uint8_t> ToClasses(const py::handle& array, const std::string& name) {
    const auto a = Checked<std::uint8_t>(array, name, 2);
    core::Raster<std::uint8_t> r(static_cast<int>(a.shape(0)), static_cast<int>(a.shape(1)));
    std::copy_n(a.data(), r.data.size(), r.data.begin());
    // A code beyond CAS_CLASSES would be counted as untouched without a word.
    const auto bad = std::find_if(r.data.begin(), r.data.end(), [](std::uint8_t v) {
        return v > static_cast<std::uint8_t>(mapper::PixelClass::kBorder);
    });
    if (bad != r.data.end()) {
        const auto i = static_cast<int>(bad - r.data.begin());
        throw MakeInputError(name,
                             "pixel (row " + std::to_string(i / r.cols) + ", col " +
                                 std::to_string(i % r.cols) + ")",
                             std::to_string(*bad),
                             "allowed: 0..3 (CAS_CLASSES: untouched, removed, filled, border)");
    }
    return r;
}

core::Trajectory ToTrajectory(const py::handle& stamp_s,
                              const py::handle& xyz_m,
                              const py::handle& quat_xyzw) {
    const auto t = Checked<double>(stamp_s, "poses.stamp_s", 1);
    const auto p = Checked<double>(xyz_m, "poses.xyz_m", 2);
    const auto q = Checked<double>(quat_xyzw, "poses.quat_xyzw", 2);
    const py::ssize_t n = t.shape(0);
    if (p.shape(0) != n || p.shape(1) != 3) {
        throw MakeInputError(
            "", "poses.xyz_m",
            "shape (" + std::to_string(p.shape(0)) + ", " + std::to_string(p.shape(1)) + ")",
            "must be (P, 3) with P = len(poses.stamp_s) = " + std::to_string(n));
    }
    if (q.shape(0) != n || q.shape(1) != 4) {
        throw MakeInputError(
            "", "poses.quat_xyzw",
            "shape (" + std::to_string(q.shape(0)) + ", " + std::to_string(q.shape(1)) + ")",
            "must be (P, 4) with P = len(poses.stamp_s) = " + std::to_string(n));
    }
    std::vector<core::TimedPose> samples(static_cast<std::size_t>(n));
    for (py::ssize_t i = 0; i < n; ++i) {
        core::TimedPose& s = samples[static_cast<std::size_t>(i)];
        s.stamp_s = t.at(i);
        s.world_T_sensor.translation = {p.at(i, 0), p.at(i, 1), p.at(i, 2)};
        Eigen::Quaterniond rotation(q.at(i, 3), q.at(i, 0), q.at(i, 1), q.at(i, 2));
        // The run file reader's rule (io/run_file.cpp): unit within 1e-3, then normalised;
        // quaternions already unit to rounding are kept bit for bit (simulate -> write_run
        // gives the CLI's file).
        if (!s.world_T_sensor.translation.allFinite() || !rotation.coeffs().allFinite() ||
            std::abs(rotation.norm() - 1.0) > 1e-3) {
            throw MakeInputError("", "poses[" + std::to_string(i) + "]",
                                 "norm " + std::to_string(rotation.norm()),
                                 "xyz_m must be finite and quat_xyzw a unit quaternion");
        }
        if (std::abs(rotation.norm() - 1.0) > 1e-12) {
            rotation.normalize();
        }
        s.world_T_sensor.rotation = rotation;
    }
    return core::Trajectory(std::move(samples));
}

}  // namespace casmap::python
