// The `_regodem` extension module: the C++ half of the `regodem` Python package
// (python/regodem/__init__.py is the other; docs/python.md).
#include <pybind11/pybind11.h>

#include "bindings.hpp"
#include "core/error.hpp"
#include "io/checkpoint_file.hpp"
#include "regodem/build_info.hpp"

namespace py = pybind11;

namespace regodem::python {

void register_exceptions(py::module_& m) {
  // Translators are tried newest first: the subclass after its base.
  const py::exception<InputError>& input_error = py::register_exception<InputError>(m, "InputError", PyExc_ValueError);
  py::register_exception<SimulationError>(m, "SimulationError", PyExc_RuntimeError);
  // A checkpoint that does not fit is bad input too, as in C++.
  py::register_exception<CheckpointError>(m, "CheckpointError", input_error.ptr());
}

}  // namespace regodem::python

PYBIND11_MODULE(_regodem, m) {
  m.doc() = "RegoDEM's C++ core; use the `regodem` package, which wraps it (docs/python.md)";
  m.attr("version") = regodem::build_info::version;
  m.attr("build_type") = regodem::build_info::build_type;
  regodem::python::register_exceptions(m);
  regodem::python::bind_scenario(m);
  regodem::python::bind_run(m);
  regodem::python::bind_doe(m);
}
