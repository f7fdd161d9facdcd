// The `plateball._plateball` extension module (pybind11). The Python package
// (python/plateball/__init__.py) re-exports it and adds keyword-argument solver calls.
#include "bind_common.h"
#include "plateball/problem_io.h"
#include "plateball/version.h"

namespace plateball::python {
void BindMonteCarlo(py::module_& m);  // bind_montecarlo.cc: error models, execution, Monte Carlo
void BindController(py::module_& m);  // bind_controller.cc: the nominal plan and the real-time controller
}  // namespace plateball::python

PYBIND11_MODULE(_plateball, m) {
  namespace py = pybind11;
  m.doc() = "plateball: impulsive control of a symmetric ball rolling without sliding or spinning (C++ core)";
  m.attr("__version__") = PLATEBALL_VERSION_STRING;
  // An unreadable problem file is an OSError (the tools' exit code 5); every other invalid
  // input (std::invalid_argument) is a ValueError with the library's message.
  py::register_exception<plateball::ProblemFileReadError>(m, "ProblemFileReadError", PyExc_OSError);
  plateball::python::BindModel(m);
  plateball::python::BindActuator(m);
  plateball::python::BindPaths(m);
  plateball::python::BindSolvers(m);
  plateball::python::BindProblem(m);
  plateball::python::BindMonteCarlo(m);
  plateball::python::BindController(m);
}
