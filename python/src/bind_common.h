// Shared helpers of the plateball Python binding: keyword-argument constructors and the
// registration functions of each part. The binding is thin: it converts types (Eigen <-> NumPy,
// std::vector <-> list, status enums <-> their ToString words) and calls the library.
#pragma once

#include <pybind11/eigen.h>
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <Eigen/Core>
#include <stdexcept>
#include <string>
#include <vector>

#include "plateball/free_motion.h"

namespace plateball::python {

namespace py = pybind11;

// "must be TYPE" from a setter's TypeError: a field property's "CLASS.FIELD: value V: must be TYPE"
// (field_binding.h), or pybind11's message about a setter's argument ("... (self: C, arg0: TYPE) -> None").
inline std::string WrongTypeText(const std::string& pybind_message) {
  const auto own = pybind_message.rfind(": must be ");
  if (own != std::string::npos) return pybind_message.substr(own + 2, pybind_message.find('\n', own) - own - 2);
  const auto at = pybind_message.find("arg0: ");
  const auto end = at == std::string::npos ? at : pybind_message.find(") ->", at);
  if (end == std::string::npos) return "has the wrong type";
  return "must be " + pybind_message.substr(at + 6, end - at - 6);
}

// Adds `T(**kwargs)`: a default value whose attributes are set from the keywords, so that
// `JoinOptions(max_iterations=50)` works; an unknown keyword is a TypeError naming it.
template <typename T, typename... Extra>
py::class_<T, Extra...>& WithKeywordInit(py::class_<T, Extra...>& cls) {
  cls.def(py::init([](const py::kwargs& kwargs) {
            T value{};
            {
              py::object view = py::cast(&value, py::return_value_policy::reference);
              for (const auto& item : kwargs) {
                const std::string key = py::str(item.first);
                if (key.rfind("_", 0) == 0 || !py::hasattr(py::type::of(view), key.c_str()))
                  throw py::type_error(std::string(py::str(py::type::of(view).attr("__name__"))) +
                                       "(): unexpected keyword argument '" + key + "'");
                try {
                  py::setattr(view, item.first, item.second);
                } catch (py::error_already_set& e) {
                  if (!e.matches(PyExc_TypeError)) throw;
                  // pybind11's setter names neither the attribute nor the value: "CLS(): KEY: value V: ...".
                  throw py::type_error(std::string(py::str(py::type::of(view).attr("__name__"))) + "(): " + key +
                                       ": value " + std::string(py::repr(item.second)) + ": " +
                                       WrongTypeText(e.what()));
                }
              }
            }
            return value;
          }),
          "Default values, then every keyword argument set as an attribute.");
  return cls;
}

// A count argument of the binding's own helpers (samples per arc, points): FIELD: value V: range.
inline void RequireCount(const char* field, int value, int lo, int hi) {
  if (value < lo || value > hi)
    throw std::invalid_argument(std::string(field) + ": value " + std::to_string(value) + ": must be in [" +
                                std::to_string(lo) + ", " + std::to_string(hi) + "]");
}

// Samples of a free motion (free_motion.h) as NumPy arrays: t (n), x (n, 2), z and omega (n, 3),
// orientation (n, 3, 3), theta/phi/psi (n, canonical), energy (n).
struct Trajectory {
  std::vector<MotionSample> samples;
};

// Rows of a matrix built from one vector per element.
template <int Cols, typename Seq, typename F>
Eigen::Matrix<double, Eigen::Dynamic, Cols, (Cols == 1 ? Eigen::ColMajor : Eigen::RowMajor)> Stack(const Seq& seq,
                                                                                                   F&& f) {
  Eigen::Matrix<double, Eigen::Dynamic, Cols, (Cols == 1 ? Eigen::ColMajor : Eigen::RowMajor)> m(
      static_cast<Eigen::Index>(seq.size()), Cols);
  Eigen::Index i = 0;
  for (const auto& e : seq) m.row(i++) = f(e);
  return m;
}
// An (n, 3, 3) array of rotation matrices (rows as in the tools' JSON).
template <typename Seq, typename F>
py::array_t<double> StackMatrices(const Seq& seq, F&& f) {
  py::array_t<double> a({static_cast<py::ssize_t>(seq.size()), py::ssize_t{3}, py::ssize_t{3}});
  auto r = a.mutable_unchecked<3>();
  py::ssize_t i = 0;
  for (const auto& e : seq) {
    const Eigen::Matrix3d m = f(e);
    for (int j = 0; j < 3; ++j)
      for (int k = 0; k < 3; ++k) r(i, j, k) = m(j, k);
    ++i;
  }
  return a;
}

// status (word), usable, message, report: the shape every summary shares.
template <typename S>
void AddSummaryShape(py::class_<S>& cls) {
  cls.def_property_readonly(
         "status",
         [](const S& s) { return ToString(s.status); },
         "The outcome as the tools' \"status\" word (e.g. \"converged\", \"success\"; \"not run\" before a solve).")
      .def_readonly("message",
                    &S::message,
                    "What went wrong or what limits the result, in words; empty when there is nothing to say.")
      .def_property_readonly(
          "usable", &S::IsSolutionUsable, "Whether the result can be used (the tools' \"usable\" field).")
      .def_property_readonly("report",
                             &S::BriefReport,
                             "The status and the result's key numbers in one line (the tools' \"report\" field).")
      .def("__repr__", &S::BriefReport, "The one-line report.");
}

void BindModel(py::module_& m);     // model, states, impulses, free motion, rolling, SO(3)
void BindPaths(py::module_& m);     // curves, paths, partitions
void BindSolvers(py::module_& m);   // join, reach, plan, converge, isoparallel, exact arrival
void BindProblem(py::module_& m);   // problem files and task adapters
void BindActuator(py::module_& m);  // the actuator's commands: plate impulse, pulse forces and friction

}  // namespace plateball::python
