#pragma once

// The pieces of the `casmap` Python module (python/casmap/__init__.py wraps them): one Bind*
// function per module, and run files as plain dicts of numpy arrays (the layout of
// docs/run-file.md) shared by read_run, write_run, simulate and map_run.

#include <pybind11/pybind11.h>

#include <vector>

#include "casmap/io/run_file.hpp"

namespace casmap::python {

namespace py = pybind11;

/// Beam angles and timing shared by every scan of a run (core::Scan fields).
struct ScanGeometry {
    double start_angle_rad = 0.0;
    double angle_step_rad = 0.0;
    double beam_period_s = 0.0;
    std::vector<double> beam_time_offset_s;  // empty: i * beam_period_s
};

/// {"scans": {...}, "poses": {...}, "maps": {...}, "seed", "config_yaml", "format"}.
[[nodiscard]] py::dict RunToDict(const io::RunData& run);
/// The inverse; InputError naming the key for a missing key or a wrong array.
[[nodiscard]] io::RunData RunFromDict(const py::dict& run);

void BindMapper(py::module_& m);
void BindIo(py::module_& m);
#ifdef CASMAP_WITH_SIM
void BindSim(py::module_& m);
#endif

}  // namespace casmap::python
