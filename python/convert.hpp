#pragma once

// numpy <-> casmap conversions for the bindings. Arrays are checked, never silently converted
// between element types: a float64 map is rejected with a ValueError naming the argument (its
// values would change in float32), a non-contiguous array of the right type is copied.

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include <cstdint>
#include <string>

#include "casmap/core/grid.hpp"
#include "casmap/core/trajectory.hpp"

namespace casmap::python {

namespace py = pybind11;

/// 2-D float32 array (rows along-track) -> MapF; InputError naming `name` otherwise.
[[nodiscard]] core::MapF ToMap(const py::handle& array, const std::string& name);
/// MapF -> new (rows, cols) float32 array.
[[nodiscard]] py::array_t<float> FromMap(const core::MapF& map);
/// Raster<uint8> -> new (rows, cols) uint8 array.
[[nodiscard]] py::array_t<std::uint8_t> FromClasses(const core::Raster<std::uint8_t>& raster);
/// 2-D uint8 array -> Raster<uint8>; InputError naming `name` otherwise.
[[nodiscard]] core::Raster<std::uint8_t> ToClasses(const py::handle& array,
                                                   const std::string& name);

/// A C-contiguous copy-free view of `array` if it has element type T and `ndim` dimensions
/// (any shape when ndim < 0); InputError naming `name` and the rule otherwise.
template <typename T>
[[nodiscard]] py::array_t<T, py::array::c_style> Checked(const py::handle& array,
                                                         const std::string& name,
                                                         int ndim);

/// Poses (stamp_s (P,), xyz_m (P, 3), quat_xyzw (P, 4)) -> Trajectory; InputError otherwise.
[[nodiscard]] core::Trajectory ToTrajectory(const py::handle& stamp_s,
                                            const py::handle& xyz_m,
                                            const py::handle& quat_xyzw);

}  // namespace casmap::python
