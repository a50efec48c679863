#pragma once
// The parts of the `_regodem` extension module (module.cpp puts them together); each
// file binds one layer: scenarios, runs, designs and fits.
#include <pybind11/pybind11.h>

namespace regodem::python {

/// The module's exceptions (module.cpp): InputError (a ValueError: the scenario, a value
/// or a call is wrong; the text names file:line where there is one), SimulationError (a
/// RuntimeError: the run went wrong), CheckpointError.
void register_exceptions(pybind11::module_& m);

void bind_scenario(pybind11::module_& m);  // scenario_binding.cpp
void bind_run(pybind11::module_& m);       // run_binding.cpp
void bind_doe(pybind11::module_& m);       // doe_binding.cpp

}  // namespace regodem::python
