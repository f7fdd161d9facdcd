// Python binding: identification of lambda, mu and the state from a track (identify.h):
// identify(t, xy, sigma=None, options=None, ..., orientation=None, body_rate=None, **option_keywords)
// with NumPy arrays in.
#include <charconv>
#include <cmath>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "bind_common.h"
#include "plateball/identify.h"

namespace plateball::python {

namespace {

using Array = py::array_t<double, py::array::forcecast>;

/// A 1-dimensional array argument (or None) into out; `name` names it in the error.
void ReadVector(const std::optional<Array>& a, const char* name, std::vector<double>* out) {
  if (!a) return;
  if (a->ndim() != 1)
    throw std::invalid_argument(std::string(name) + ": value (array of " + std::to_string(a->ndim()) +
                                " dimensions): must be 1-dimensional");
  const auto v = a->unchecked<1>();
  for (py::ssize_t i = 0; i < v.shape(0); ++i) out->push_back(v(i));
}

/// A 2-dimensional (n, cols) array argument (or None), row by row into push(row pointer).
template <typename Push>
void ReadRows(const std::optional<Array>& a, const char* name, int cols, Push push) {
  if (!a) return;
  if (a->ndim() != 2 || a->shape(1) != cols)
    throw std::invalid_argument(std::string(name) + ": value (array of shape not (n, " + std::to_string(cols) +
                                ")): must have shape (n, " + std::to_string(cols) + ")");
  const auto v = a->unchecked<2>();
  for (py::ssize_t i = 0; i < v.shape(0); ++i) {
    double row[4] = {0, 0, 0, 0};
    for (int c = 0; c < cols; ++c) row[c] = v(i, c);
    push(row);
  }
}

/// "NAME[i][c]: value V: must be finite" for the first non-finite entry of rows of `cols` numbers:
/// the arguments' own names (the library names the track file's columns: "y[5]", "orientation[2].w").
template <typename Row>
void RequireFiniteRows(const std::vector<Row>& rows, const char* name) {
  for (std::size_t i = 0; i < rows.size(); ++i)
    for (Eigen::Index c = 0; c < rows[i].size(); ++c)
      if (!std::isfinite(rows[i][c])) {
        char buf[32];
        const auto end = std::to_chars(buf, buf + sizeof buf, rows[i][c]).ptr;
        throw std::invalid_argument(std::string(name) + "[" + std::to_string(i) + "][" + std::to_string(c) +
                                    "]: value " + std::string(buf, end) + ": must be finite");
      }
}

/// The optional columns of a track besides t, xy and sigma (each None or an array).
struct TrackColumns {
  std::optional<Array> impulse_times, spin, sigma_spin, orientation, sigma_orientation, body_rate, sigma_body_rate;
};

/// The track from NumPy arrays: t (n,), xy (n, 2), orientation (n, 4), body_rate (n, 3), the others
/// 1-d, or None. Shapes are checked here (naming the argument); values by
/// IdentifyProblem::Validate (naming the row).
IdentifyProblem TrackFromArrays(const Array& t,
                                const Array& xy,
                                const std::optional<Array>& sigma,
                                const TrackColumns& c) {
  if (t.ndim() != 1)
    throw std::invalid_argument("t: value (array of " + std::to_string(t.ndim()) +
                                " dimensions): must be 1-dimensional");
  if (xy.ndim() != 2 || xy.shape(1) != 2)
    throw std::invalid_argument("xy: value (array of shape not (n, 2)): must have shape (n, 2)");
  IdentifyProblem p;
  const auto tv = t.unchecked<1>();
  const auto xv = xy.unchecked<2>();
  for (py::ssize_t i = 0; i < tv.shape(0); ++i) p.t.push_back(tv(i));
  for (py::ssize_t i = 0; i < xv.shape(0); ++i) p.x.emplace_back(xv(i, 0), xv(i, 1));
  if (p.x.size() != p.t.size())
    throw std::invalid_argument("xy (rows): value " + std::to_string(p.x.size()) + ": must have one row per time (" +
                                std::to_string(p.t.size()) + ")");
  RequireFiniteRows(p.x, "xy");
  ReadVector(sigma, "sigma", &p.sigma);
  ReadVector(c.impulse_times, "impulse_times", &p.impulse_times);
  ReadVector(c.spin, "spin", &p.spin);
  ReadVector(c.sigma_spin, "sigma_spin", &p.sigma_spin);
  ReadRows(
      c.orientation, "orientation", 4, [&](const double* r) { p.orientation.emplace_back(r[0], r[1], r[2], r[3]); });
  RequireFiniteRows(p.orientation, "orientation");
  ReadVector(c.sigma_orientation, "sigma_orientation", &p.sigma_orientation);
  ReadRows(c.body_rate, "body_rate", 3, [&](const double* r) { p.body_rate.emplace_back(r[0], r[1], r[2]); });
  ReadVector(c.sigma_body_rate, "sigma_body_rate", &p.sigma_body_rate);
  return p;
}

void BindIdentifyInputs(py::module_& m) {
  py::class_<IdentifyGuess> guess(
      m, "IdentifyGuess", "Start of the fit instead of the multi-start (at the track's first time).");
  WithKeywordInit(guess)
      .def_readwrite("lambda_", &IdentifyGuess::lambda)
      .def_readwrite("mu", &IdentifyGuess::mu)
      .def_readwrite("angles", &IdentifyGuess::angles)
      .def_readwrite("x0", &IdentifyGuess::x0)
      .def_readwrite(
          "delta_psi",
          &IdentifyGuess::delta_psi,
          "The first delta psi of the impulses (at most one per impulse); the rest are chosen from the track.");
  py::class_<IdentifyOptions> options(
      m,
      "IdentifyOptions",
      "Options of identify(): the ball's radius in the track's unit, the search range and multi-start grid of lambda "
      "and the angles, the identifiability thresholds and the fit's tolerances.");
  WithKeywordInit(options)
      .def_readwrite("radius", &IdentifyOptions::radius)
      .def_readwrite("lambda_min", &IdentifyOptions::lambda_min)
      .def_readwrite("lambda_max", &IdentifyOptions::lambda_max)
      .def_readwrite("theta_starts", &IdentifyOptions::theta_starts)
      .def_readwrite("phase_starts", &IdentifyOptions::phase_starts)
      .def_readwrite("lambda_starts", &IdentifyOptions::lambda_starts)
      .def_readwrite("guess", &IdentifyOptions::guess)
      .def_readwrite("max_iterations", &IdentifyOptions::max_iterations)
      .def_readwrite("max_lambda_relative_error", &IdentifyOptions::max_lambda_relative_error)
      .def_readwrite("no_fit_significance", &IdentifyOptions::no_fit_significance)
      .def_readwrite("max_relative_residual", &IdentifyOptions::max_relative_residual)
      .def_readwrite("profile_interval", &IdentifyOptions::profile_interval)
      .def_readwrite("threads", &IdentifyOptions::threads)
      .def_readwrite("integration", &IdentifyOptions::integration)
      .def("validate",
           &IdentifyOptions::Validate,
           "Empty when valid, else the first offending field, its value and the bound.");
}

}  // namespace

void BindIdentify(py::module_& m) {
  BindIdentifyInputs(m);
  py::class_<IdentifiedFlight> flight(
      m, "IdentifiedFlight", "The fitted state at the start of one flight (just after its impulse).");
  flight.def_readonly("t_start", &IdentifiedFlight::t_start, "The flight's start time (the impulse's, or t_ref).")
      .def_readonly("angles", &IdentifiedFlight::angles, "(theta, phi, psi) at the start, theta in [0, pi].")
      .def_readonly("x", &IdentifiedFlight::x, "The contact point at the start (radii).");
  py::class_<IdentifySummary> summary(
      m,
      "IdentifySummary",
      "The result of identify(): the fitted lambda, mu, angles and start point with their standard errors and lambda's "
      "interval, the residuals and whether lambda is identified; status \"not run\" until fitted.");
  AddSummaryShape(summary);
  summary.def_readonly("t_ref", &IdentifySummary::t_ref)
      .def_readonly("lambda_", &IdentifySummary::lambda)
      .def_readonly("mu", &IdentifySummary::mu)
      .def_readonly("angles", &IdentifySummary::angles)
      .def_readonly("x0", &IdentifySummary::x0)
      .def_readonly("period", &IdentifySummary::period)
      .def_readonly("impulse_times", &IdentifySummary::impulse_times, "The times of the impulses between the flights.")
      .def_readonly(
          "delta_psi",
          &IdentifySummary::delta_psi,
          "The fitted delta psi of each impulse, in (-pi, pi]; their standard errors follow chi (when frame_fitted) "
          "in standard_errors (see parameters).")
      .def_readonly("frame_fitted",
                    &IdentifySummary::frame_fitted,
                    "True with orientations or body rates: the frame is fitted, with one more parameter chi (the turn "
                    "about the axis at t_ref).")
      .def_readonly(
          "orientation",
          &IdentifySummary::orientation,
          "With frame_fitted: the fitted orientation A(t_ref) = R_WB as the unit quaternion (w, x, y, z), w >= 0.")
      .def_readonly(
          "parameters",
          &IdentifySummary::parameters,
          "The names of the fitted parameters in the order of standard_errors (parameter_names, chi, delta_psi[k]).")
      .def_readonly(
          "flights", &IdentifySummary::flights, "The fitted state at the start of each flight (IdentifiedFlight).")
      .def_readonly("standard_errors", &IdentifySummary::standard_errors)
      .def_readonly("correlation", &IdentifySummary::correlation)
      .def_property_readonly("lambda_interval",
                             [](const IdentifySummary& s) { return py::make_tuple(s.lambda_low, s.lambda_high); })
      .def_readonly("interval_method", &IdentifySummary::interval_method)
      .def_readonly("lambda_identified", &IdentifySummary::lambda_identified)
      .def_readonly("lambda_relative_error", &IdentifySummary::lambda_relative_error)
      .def_readonly("scaled_condition", &IdentifySummary::scaled_condition)
      .def_readonly("path_deviation",
                    &IdentifySummary::path_deviation,
                    "Largest distance of the fitted contact path from its least-squares line (radii).")
      .def_readonly("straight_path",
                    &IdentifySummary::straight_path,
                    "True when the fitted path is a straight line within the noise: lambda is then not identifiable "
                    "from the contact track alone (axial spin 0, or lambda = 1 where the ball rolls like a sphere).")
      .def_readonly("unidentified", &IdentifySummary::unidentified)
      .def_readonly("samples", &IdentifySummary::samples)
      .def_readonly("rms_residual", &IdentifySummary::rms_residual)
      .def_readonly("max_residual", &IdentifySummary::max_residual)
      .def_readonly("sigma", &IdentifySummary::sigma)
      .def_readonly("sigma_estimated", &IdentifySummary::sigma_estimated)
      .def_readonly("chi_square", &IdentifySummary::chi_square)
      .def_readonly("track_spread", &IdentifySummary::track_spread)
      .def_property_readonly(
          "fitted",
          [](const IdentifySummary& s) {
            return Stack<2>(s.fitted, [](const Eigen::Vector2d& v) { return v.transpose(); });
          },
          "The fitted contact points x(t_i), (n, 2), radii.")
      .def_readonly(
          "fitted_spin", &IdentifySummary::fitted_spin, "With a measured spin: the fitted axial spin v0(t_i).")
      .def_readonly("spin_rms_residual", &IdentifySummary::spin_rms_residual, "RMS of the fitted - measured spin.")
      .def_readonly("spin_max_residual",
                    &IdentifySummary::spin_max_residual,
                    "Largest absolute difference of the fitted and the measured spin.")
      .def_property_readonly(
          "fitted_orientation",
          [](const IdentifySummary& s) {
            return Stack<4>(s.fitted_orientation, [](const Eigen::Vector4d& v) { return v.transpose(); });
          },
          "With measured orientations: the fitted A(t_i) as unit quaternions (w, x, y, z), (n, 4).")
      .def_readonly("orientation_rms_residual",
                    &IdentifySummary::orientation_rms_residual,
                    "RMS component of the rotation vectors LogSO3(A_i^T A(t_i)) (rad).")
      .def_readonly("orientation_max_residual",
                    &IdentifySummary::orientation_max_residual,
                    "Largest angle of the rotation LogSO3(A_i^T A(t_i)) (rad).")
      .def_property_readonly(
          "fitted_body_rate",
          [](const IdentifySummary& s) {
            return Stack<3>(s.fitted_body_rate, [](const Eigen::Vector3d& v) { return v.transpose(); });
          },
          "With measured body rates: the fitted A^T omega (t_i), (n, 3).")
      .def_readonly("body_rate_rms_residual",
                    &IdentifySummary::body_rate_rms_residual,
                    "RMS component of the fitted - measured body rates.")
      .def_readonly("body_rate_max_residual",
                    &IdentifySummary::body_rate_max_residual,
                    "Largest norm of the fitted - measured body rate.")
      .def_readonly("starts", &IdentifySummary::starts)
      .def_readonly("iterations", &IdentifySummary::iterations)
      .def_readonly("profile_fits", &IdentifySummary::profile_fits)
      .def_property_readonly_static("parameter_names", [](const py::object&) {
        std::vector<std::string> names(std::begin(kIdentifyParameterNames), std::end(kIdentifyParameterNames));
        return names;
      });
  m.def(
      "_identify",
      [](const Array& t,
         const Array& xy,
         const std::optional<Array>& sigma,
         const std::optional<Array>& impulse_times,
         const std::optional<Array>& spin,
         const std::optional<Array>& sigma_spin,
         const std::optional<Array>& orientation,
         const std::optional<Array>& sigma_orientation,
         const std::optional<Array>& body_rate,
         const std::optional<Array>& sigma_body_rate,
         const IdentifyOptions& options) {
        const IdentifyProblem p = TrackFromArrays(
            t,
            xy,
            sigma,
            {impulse_times, spin, sigma_spin, orientation, sigma_orientation, body_rate, sigma_body_rate});
        py::gil_scoped_release release;
        return Identify(p, options);
      },
      py::arg("t"),
      py::arg("xy"),
      py::arg("sigma"),
      py::arg("impulse_times"),
      py::arg("spin"),
      py::arg("sigma_spin"),
      py::arg("orientation"),
      py::arg("sigma_orientation"),
      py::arg("body_rate"),
      py::arg("sigma_body_rate"),
      py::arg("options"),
      "The native identify(): the track's arrays (None when absent) and IdentifyOptions; use plateball.identify.");
}

}  // namespace plateball::python
