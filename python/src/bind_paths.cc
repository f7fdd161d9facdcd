// Python binding: planar curves and paths (path.h) and partitions (partition.h).
#include "bind_common.h"
#include "plateball/partition.h"
#include "plateball/path.h"

namespace plateball::python {
namespace {

void BindCurves(py::module_& m) {
  py::class_<SmoothCurve>(m, "SmoothCurve", "A smooth planar curve p(tau) with exact p' and p''.")
      .def_static(
          "line", &SmoothCurve::Line, py::arg("start"), py::arg("end"), "p = from + tau (to - from), tau in [0, 1].")
      .def_static("circle",
                  &SmoothCurve::Circle,
                  py::arg("center"),
                  py::arg("radius"),
                  py::arg("tau_begin"),
                  py::arg("tau_end"),
                  "p = center + radius (cos tau, sin tau).")
      .def_static("ellipse",
                  &SmoothCurve::Ellipse,
                  py::arg("center"),
                  py::arg("semi_axes"),
                  py::arg("rotation"),
                  py::arg("tau_begin"),
                  py::arg("tau_end"),
                  "p = center + Rot(rotation) (a cos tau, b sin tau) with (a, b) = semi_axes.")
      .def_static("lemniscate",
                  &SmoothCurve::Lemniscate,
                  py::arg("center"),
                  py::arg("scale"),
                  py::arg("rotation"),
                  py::arg("tau_begin"),
                  py::arg("tau_end"),
                  "Lemniscate of Bernoulli of half-width `scale`: p = center + Rot(rotation) scale (cos tau, sin tau "
                  "cos tau) / (1 + sin^2 tau).")
      .def_static("sine",
                  &SmoothCurve::Sine,
                  py::arg("start"),
                  py::arg("rotation"),
                  py::arg("length"),
                  py::arg("amplitude"),
                  py::arg("wavelength"),
                  "p = from + Rot(rotation) (tau, amplitude sin(2 pi tau / wavelength)), tau in [0, length].")
      .def_static("samples",
                  &SmoothCurve::Samples,
                  py::arg("points"),
                  "Natural C^2 cubic spline through the samples, tau = cumulative chord length.")
      .def_property_readonly("kind", [](const SmoothCurve& c) { return ToString(c.kind()); })
      .def_property_readonly("begin", &SmoothCurve::Begin)
      .def_property_readonly("end", &SmoothCurve::End)
      .def_property_readonly("start_point", &SmoothCurve::StartPoint)
      .def_property_readonly("end_point", &SmoothCurve::EndPoint)
      .def_property_readonly("length", &SmoothCurve::Length)
      .def("value", &SmoothCurve::Value, py::arg("tau"), "The point p(tau).")
      .def("derivative", &SmoothCurve::Derivative, py::arg("tau"), "p'(tau).")
      .def("second_derivative", &SmoothCurve::SecondDerivative, py::arg("tau"), "p''(tau).")
      .def("arc_length",
           &SmoothCurve::ArcLength,
           py::arg("a"),
           py::arg("b"),
           "Arc length between parameters a and b (negative for b < a): adaptive Gauss-Kronrod (G15/K31) with an error "
           "estimate on panels where ``|p'|`` is smooth, accurate to about 1e-12 relative.")
      .def(
          "points",
          [](const SmoothCurve& c, int n) {
            RequireCount("n", n, 2, 1000000);
            std::vector<int> i(static_cast<std::size_t>(n));
            for (std::size_t k = 0; k < i.size(); ++k) i[k] = static_cast<int>(k);
            const double last = static_cast<double>(i.size() - 1);
            return Stack<2>(i, [&](int k) {
              return Eigen::RowVector2d(c.Value(c.Begin() + (c.End() - c.Begin()) * k / last).transpose());
            });
          },
          py::arg("n") = 200,
          "(n, 2) points at equally spaced tau");
  py::class_<Path>(m, "Path", "A chain of smooth pieces sharing end points.")
      .def(py::init<std::vector<SmoothCurve>>(), py::arg("pieces"))
      .def(py::init([](const SmoothCurve& c) { return Path({c}); }), py::arg("curve"))
      .def_property_readonly("pieces", &Path::pieces)
      .def_property_readonly("start_point", &Path::StartPoint)
      .def_property_readonly("end_point", &Path::EndPoint)
      .def_property_readonly("length", &Path::Length);
  py::implicitly_convertible<SmoothCurve, Path>();
}

void BindPartitions(py::module_& m) {
  py::class_<UniformParameter>(m, "UniformParameter", "n equal steps of the curve parameter.")
      .def(py::init([](int n) { return UniformParameter{n}; }), py::arg("n") = 16)
      .def_readwrite("n", &UniformParameter::n);
  py::class_<UniformArcLength>(m, "UniformArcLength", "n steps of equal arc length.")
      .def(py::init([](int n) { return UniformArcLength{n}; }), py::arg("n") = 16)
      .def_readwrite("n", &UniformArcLength::n);
  py::class_<ExplicitTaus>(m, "ExplicitTaus", "Explicit partition parameters (single-piece paths).")
      .def(py::init([](std::vector<double> taus) { return ExplicitTaus{std::move(taus)}; }), py::arg("taus"))
      .def_readwrite("taus", &ExplicitTaus::taus);
  m.def("make_partition",
        &MakePartition,
        py::arg("path"),
        py::arg("rules"),
        py::arg("field") = "partition",
        "The partition of a path by the rules of a problem file's partition section (`field` names it in errors).");
}

}  // namespace

void BindPaths(py::module_& m) {
  BindCurves(m);
  BindPartitions(m);
}

}  // namespace plateball::python
