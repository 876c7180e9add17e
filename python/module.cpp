// The `_casmap` extension module; python/casmap/__init__.py is the documented API on top.
#include <pybind11/pybind11.h>

#include "bindings.hpp"
#include "casmap/core/input_error.hpp"

PYBIND11_MODULE(_casmap, m) {
    namespace py = pybind11;
    m.doc() = "casmap: LMS 200 simulator, terrain mapper and CAS filter (C++ bindings)";
    // Bad input raises ValueError with the message the CLI prints after "casmap: ".
    py::register_exception_translator([](std::exception_ptr p) {
        try {
            if (p) {
                std::rethrow_exception(p);
            }
        } catch (const casmap::InputError& e) {
            PyErr_SetString(PyExc_ValueError, e.what());
        }
    });
    casmap::python::BindMapper(m);
    casmap::python::BindIo(m);
#ifdef CASMAP_WITH_SIM
    casmap::python::BindSim(m);
    m.attr("with_simulator") = true;
#else
    m.attr("with_simulator") = false;
#endif
}
