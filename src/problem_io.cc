#include "plateball/problem_io.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <initializer_list>
#include <limits>
#include <nlohmann/json.hpp>
#include <set>
#include <sstream>
#include <utility>
#include <variant>
#include <vector>

#include "check.h"
#include "plateball/exact_arrival.h"
#include "plateball/fewest_impulses.h"
#include "plateball/so3.h"

namespace plateball {
namespace {

using json = nlohmann::json;
using ojson = nlohmann::ordered_json;

// ------------------------------------------------------------------ limits of the schema
// Upper bounds on counts keep a hostile file from asking for absurd work or memory; they are the
// library's limits (check.h, README "Limits"), so what the reader accepts a solver accepts.
constexpr long long kMaxSamples = internal::kMaxSamples;        // simulate.samples, path sample points
constexpr long long kMaxCount = internal::kMaxPartitionSteps;   // partition n, impulses, indices
constexpr long long kMaxListLength = 100'000;         // targets, pieces, energy changes
constexpr double kMaxHorizonPeriods = 100.0;          // reach: x 256 candidates = the refinement budget
constexpr int kMaxPieceDepth = 8;                     // nesting of piecewise paths
constexpr std::size_t kMaxFileBytes = 16u << 20;      // 16 MiB
constexpr int kMaxNestingDepth = 64;                  // open arrays and objects
constexpr double kRotationTolerance = 1e-9;           // a "matrix" orientation must be a rotation to this
constexpr double kDegenerateNorm = 1e-12;             // quaternion / axis norms below this are zero
constexpr double kJoinTolerance = 1e-9;               // piecewise end points must match to this (relative)

// ------------------------------------------------------------------ value text for messages
std::string NumberText(double v) {
  if (std::isnan(v)) return "nan";
  if (std::isinf(v)) return v > 0 ? "inf" : "-inf";
  if (std::floor(v) == v && std::abs(v) < 1e15) {  // integral: no exponent, no ".0"
    std::ostringstream os;
    os << static_cast<long long>(v);
    return (v == 0 && std::signbit(v)) ? "-0" : os.str();
  }
  // Shortest representation that reads back to the same double.
  for (int precision = 1; precision <= 17; ++precision) {
    std::ostringstream os;
    os.precision(precision);
    os << v;
    if (std::strtod(os.str().c_str(), nullptr) == v) return os.str();
  }
  std::ostringstream os;
  os.precision(17);
  os << v;
  return os.str();
}

std::string Truncate(std::string s, std::size_t n) {
  if (s.size() > n) s = s.substr(0, n) + "...";
  return s;
}

// Compact, bounded rendering of a JSON value (bounded depth and length: never recursive without
// limit, whatever the input).
void AppendValueText(const json& j, int depth, std::string* out) {
  if (out->size() > 160) {
    *out += "...";
    return;
  }
  switch (j.type()) {
    case json::value_t::null: *out += "null"; return;
    case json::value_t::boolean: *out += j.get<bool>() ? "true" : "false"; return;
    case json::value_t::number_integer: *out += std::to_string(j.get<std::int64_t>()); return;
    case json::value_t::number_unsigned: *out += std::to_string(j.get<std::uint64_t>()); return;
    case json::value_t::number_float: *out += NumberText(j.get<double>()); return;
    case json::value_t::string:
      *out += Truncate(json(j.get<std::string>()).dump(-1, ' ', false, json::error_handler_t::replace), 64);
      return;
    case json::value_t::array: {
      if (depth >= 3 || j.size() > 12) {
        *out += "[array of " + std::to_string(j.size()) + "]";
        return;
      }
      *out += "[";
      bool first = true;
      for (const json& e : j) {
        if (!first) *out += ", ";
        first = false;
        AppendValueText(e, depth + 1, out);
      }
      *out += "]";
      return;
    }
    case json::value_t::object: {
      if (j.empty()) {
        *out += "{}";
        return;
      }
      *out += "{object with keys ";
      bool first = true;
      int shown = 0;
      for (auto it = j.begin(); it != j.end(); ++it) {
        if (++shown > 8) {
          *out += ", ...";
          break;
        }
        if (!first) *out += ", ";
        first = false;
        *out += Truncate(it.key(), 32);
      }
      *out += "}";
      return;
    }
    default: *out += "(binary)"; return;
  }
}

std::string ValueText(const json& j) {
  std::string s;
  AppendValueText(j, 0, &s);
  return s;
}

std::string VectorText(const double* v, int n) {
  std::string s = "[";
  for (int i = 0; i < n; ++i) s += (i ? ", " : "") + NumberText(v[i]);
  return s + "]";
}

const char* const kMissing = "(missing)";

// ------------------------------------------------------------------ the reader
class Reader {
 public:
  explicit Reader(std::string source) : source_(std::move(source)) {}

  [[noreturn]] void Fail(const std::string& path, const std::string& value, const std::string& what) const {
    throw std::invalid_argument(internal::InvalidValueMessage(source_ + ": " + path, value, what));
  }
  [[noreturn]] void Fail(const std::string& path, const char* value, const std::string& what) const {
    Fail(path, std::string(value), what);
  }
  [[noreturn]] void Fail(const std::string& path, const json& value, const std::string& what) const {
    Fail(path, ValueText(value), what);
  }

  // An object whose keys are all in `allowed`.
  void Object(const json& j, const std::string& path, std::initializer_list<const char*> allowed) const {
    if (!j.is_object()) Fail(path, j, "must be a JSON object");
    for (auto it = j.begin(); it != j.end(); ++it) {
      bool ok = false;
      for (const char* a : allowed) ok = ok || it.key() == a;
      if (!ok) {
        std::string list;
        for (const char* a : allowed) list += (list.empty() ? "" : ", ") + std::string(a);
        Fail(Join(path, it.key()), it.value(), "unknown key (allowed here: " + list + ")");
      }
    }
  }

  static std::string Join(const std::string& path, const std::string& key) {
    return path.empty() ? key : path + "." + key;
  }
  static std::string Index(const std::string& path, std::size_t i) { return path + "[" + std::to_string(i) + "]"; }

  // Member lookup; nullptr when absent.
  static const json* Find(const json& obj, const char* key) {
    const auto it = obj.find(key);
    return it == obj.end() ? nullptr : &*it;
  }
  const json& Require(const json& obj, const std::string& path, const char* key) const {
    const json* v = Find(obj, key);
    if (!v) Fail(Join(path, key), std::string(kMissing), "required field is missing");
    return *v;
  }

  double Number(const json& v, const std::string& path) const {
    if (!v.is_number()) Fail(path, v, "must be a number");
    const double d = v.get<double>();
    if (!std::isfinite(d)) Fail(path, v, "must be a finite number");
    return d;
  }
  double Positive(const json& v, const std::string& path) const {
    const double d = Number(v, path);
    if (!(d > 0)) Fail(path, v, "must be > 0");
    return d;
  }
  double NonNegative(const json& v, const std::string& path) const {
    const double d = Number(v, path);
    if (!(d >= 0)) Fail(path, v, "must be >= 0");
    return d;
  }
  double InRange(const json& v, const std::string& path, double lo_exclusive, double hi_inclusive) const {
    const double d = Number(v, path);
    if (!(d > lo_exclusive && d <= hi_inclusive))
      Fail(path, v, "must be in (" + NumberText(lo_exclusive) + ", " + NumberText(hi_inclusive) + "]");
    return d;
  }

  // A coordinate or a length on the plate: |v| <= internal::kMaxCoordinate (README, "Limits").
  double Coordinate(const json& v, const std::string& path) const {
    const double d = Number(v, path);
    if (!(std::abs(d) <= internal::kMaxCoordinate))
      Fail(path, v, "|coordinate| must be <= " + internal::FormatNumber(internal::kMaxCoordinate) + " (precision limit)");
    return d;
  }
  double PositiveLength(const json& v, const std::string& path) const {
    Positive(v, path);
    return Coordinate(v, path);
  }
  Eigen::Vector2d Point(const json& v, const std::string& path) const {
    const Eigen::Vector2d p = Vector<2>(v, path);
    for (std::size_t i = 0; i < 2; ++i) Coordinate(v[i], Index(path, i));
    return p;
  }
  double InClosedRange(const json& v, const std::string& path, double lo, double hi) const {
    const double d = Number(v, path);
    if (!(d >= lo && d <= hi))
      Fail(path, v, "must be in [" + internal::FormatNumber(lo) + ", " + internal::FormatNumber(hi) + "]");
    return d;
  }

  // An integer in [lo, hi]; a float with an integral value is accepted.
  long long Integer(const json& v, const std::string& path, long long lo, long long hi) const {
    long long n = 0;
    if (v.is_number_integer() && !v.is_number_unsigned()) {
      n = v.get<std::int64_t>();
    } else if (v.is_number_unsigned()) {
      const std::uint64_t u = v.get<std::uint64_t>();
      if (u > static_cast<std::uint64_t>(hi)) Fail(path, v, "must be <= " + std::to_string(hi));
      n = static_cast<long long>(u);
    } else if (v.is_number_float()) {
      const double d = v.get<double>();
      if (!std::isfinite(d) || std::floor(d) != d) Fail(path, v, "must be an integer");
      if (d < static_cast<double>(lo)) Fail(path, v, "must be >= " + std::to_string(lo));
      if (d > static_cast<double>(hi)) Fail(path, v, "must be <= " + std::to_string(hi));
      n = static_cast<long long>(d);
    } else {
      Fail(path, v, "must be an integer");
    }
    if (n < lo) Fail(path, v, "must be >= " + std::to_string(lo));
    if (n > hi) Fail(path, v, "must be <= " + std::to_string(hi));
    return n;
  }

  std::uint64_t Seed(const json& v, const std::string& path) const {
    if (v.is_number_unsigned()) return v.get<std::uint64_t>();
    if (v.is_number_integer()) Fail(path, v, "must be a non-negative integer");
    if (v.is_number_float()) {
      const double d = v.get<double>();
      if (std::isfinite(d) && std::floor(d) == d && d >= 0 && d < 18446744073709551616.0)
        return static_cast<std::uint64_t>(d);
    }
    Fail(path, v, "must be a non-negative integer");
  }

  std::string String(const json& v, const std::string& path) const {
    if (!v.is_string()) Fail(path, v, "must be a string");
    return v.get<std::string>();
  }

  // An array of `n` finite numbers.
  template <int N>
  Eigen::Matrix<double, N, 1> Vector(const json& v, const std::string& path) const {
    if (!v.is_array() || v.size() != static_cast<std::size_t>(N))
      Fail(path, v, "must be an array of " + std::to_string(N) + " numbers");
    Eigen::Matrix<double, N, 1> out;
    for (int i = 0; i < N; ++i) out(i) = Number(v[static_cast<std::size_t>(i)], Index(path, static_cast<std::size_t>(i)));
    return out;
  }

  const json& Array(const json& v, const std::string& path, long long min_size, long long max_size) const {
    if (!v.is_array()) Fail(path, v, "must be an array");
    const long long n = static_cast<long long>(v.size());
    if (n < min_size) Fail(path, v, "must have at least " + std::to_string(min_size) + " element(s)");
    if (n > max_size) Fail(path, v, "must have at most " + std::to_string(max_size) + " elements");
    return v;
  }

  std::vector<Eigen::Vector2d> Points(const json& v, const std::string& path, long long min_size,
                                      long long max_size) const {
    Array(v, path, min_size, max_size);
    std::vector<Eigen::Vector2d> out;
    out.reserve(v.size());
    for (std::size_t i = 0; i < v.size(); ++i) out.push_back(Point(v[i], Index(path, i)));
    return out;
  }

  // ---------------------------------------------------------------- orientation (3 forms)
  Eigen::Matrix3d Orientation(const json& j, const std::string& path) const {
    Object(j, path, {"quaternion", "matrix", "axis_angle"});
    if (j.size() != 1)
      Fail(path, j, "must have exactly one of the keys quaternion, matrix, axis_angle");
    if (const json* q = Find(j, "quaternion")) {
      const std::string p = Join(path, "quaternion");
      const Eigen::Vector4d wxyz = Vector<4>(*q, p);
      const double n = wxyz.norm();
      if (!(n > kDegenerateNorm) || !std::isfinite(n))
        Fail(p, *q, "must be a non-zero quaternion [w, x, y, z] (it is normalised)");
      return QuaternionToRotation(wxyz, p);
    }
    if (const json* m = Find(j, "matrix")) {
      const std::string p = Join(path, "matrix");
      if (!m->is_array() || m->size() != 3) Fail(p, *m, "must be an array of 3 rows of 3 numbers");
      Eigen::Matrix3d r;
      for (std::size_t i = 0; i < 3; ++i) r.row(static_cast<Eigen::Index>(i)) = Vector<3>((*m)[i], Index(p, i)).transpose();
      const double orth = (r.transpose() * r - Eigen::Matrix3d::Identity()).cwiseAbs().maxCoeff();
      const double det = r.determinant();
      if (!IsRotation(r, kRotationTolerance) || !(orth <= kRotationTolerance) ||
          !(std::abs(det - 1.0) <= kRotationTolerance)) {
        Fail(p, *m,
             "not a rotation matrix to 1e-9: max |R^T R - I| = " + NumberText(orth) + ", det R = " + NumberText(det) +
                 (det < 0 ? " (a reflection)" : ""));
      }
      return r;
    }
    const json& aa = *Find(j, "axis_angle");
    const std::string p = Join(path, "axis_angle");
    Object(aa, p, {"axis", "angle"});
    const Eigen::Vector3d axis = Vector<3>(Require(aa, p, "axis"), Join(p, "axis"));
    const double angle = Number(Require(aa, p, "angle"), Join(p, "angle"));
    const double n = axis.norm();
    if (!(n > kDegenerateNorm) || !std::isfinite(n)) Fail(Join(p, "axis"), aa["axis"], "must be a non-zero vector (it is normalised)");
    return ExpSO3(axis / n * angle);
  }

  // ---------------------------------------------------------------- sections
  void Integration(const json& j, const std::string& path, IntegrationOptions* o) const {
    Object(j, path, {"absolute_tolerance", "relative_tolerance", "max_steps"});
    if (const json* v = Find(j, "absolute_tolerance")) o->absolute_tolerance = Tolerance(*v, Join(path, "absolute_tolerance"));
    if (const json* v = Find(j, "relative_tolerance")) o->relative_tolerance = Tolerance(*v, Join(path, "relative_tolerance"));
    if (const json* v = Find(j, "max_steps"))
      o->max_steps = static_cast<long>(Integer(*v, Join(path, "max_steps"), 1, std::numeric_limits<long>::max()));
  }
  // A tolerance in [1e-15, 1): below, the step size underflows in double precision.
  double Tolerance(const json& v, const std::string& path) const {
    const double d = Number(v, path);
    if (!(d >= internal::kMinTolerance && d < 1)) Fail(path, v, "must be in [1e-15, 1)");
    return d;
  }

  void Ball(const json& j, const std::string& path, Problem* p) const {
    Object(j, path, {"lambda", "alpha", "beta", "physical"});
    const bool has_lambda = Find(j, "lambda"), has_alpha = Find(j, "alpha"), has_beta = Find(j, "beta"),
               has_physical = Find(j, "physical");
    const int forms = int(has_lambda) + int(has_alpha || has_beta) + int(has_physical);
    if (forms != 1)
      Fail(path, j, "must give exactly one of {lambda}, {alpha, beta} or {physical}");
    if (has_lambda) {
      Positive(j["lambda"], Join(path, "lambda"));
      p->model = BallModel::FromLambda(InClosedRange(j["lambda"], Join(path, "lambda"), internal::kMinLambda, internal::kMaxLambda));
      p->physical.reset();
      return;
    }
    if (has_alpha || has_beta) {
      const double alpha = Positive(Require(j, path, "alpha"), Join(path, "alpha"));
      const double beta = NonNegative(Require(j, path, "beta"), Join(path, "beta"));
      RequireLambdaOf(alpha, beta, Join(path, "alpha"), j["alpha"]);
      p->model = BallModel::FromAlphaBeta(alpha, beta);
      p->physical.reset();
      return;
    }
    const std::string pp = Join(path, "physical");
    const json& ph = j["physical"];
    Object(ph, pp, {"inertia_1", "inertia_3", "ball_mass", "radius", "plate_mass"});
    PhysicalParameters par;
    par.inertia_1 = Positive(Require(ph, pp, "inertia_1"), Join(pp, "inertia_1"));
    par.inertia_3 = Positive(Require(ph, pp, "inertia_3"), Join(pp, "inertia_3"));
    if (par.inertia_3 > 2.0 * par.inertia_1 * (1.0 + 1e-12))
      Fail(Join(pp, "inertia_3"), ph["inertia_3"], "a rigid body has I3 <= I1 + I2 = 2 inertia_1 = " +
                                                       NumberText(2.0 * par.inertia_1));
    par.ball_mass = NonNegative(Require(ph, pp, "ball_mass"), Join(pp, "ball_mass"));
    par.radius = Positive(Require(ph, pp, "radius"), Join(pp, "radius"));
    par.plate_mass = NonNegative(Require(ph, pp, "plate_mass"), Join(pp, "plate_mass"));
    const double moment_sum = 2.0 * par.inertia_1 + par.inertia_3;
    if (!(moment_sum <= 2.0 * par.ball_mass * par.radius * par.radius * (1.0 + 1e-12)))
      Fail(Join(pp, "ball_mass"), ph["ball_mass"],
           "a rigid ball holds its mass within its radius, 2 I1 + I3 <= 2 ball_mass radius^2 (2 I1 + I3 = " +
               NumberText(moment_sum) + ")");
    RequireLambdaOf(par.inertia_3 / par.inertia_1, par.EffectiveMass() * par.radius * par.radius / par.inertia_1, pp, ph);
    try {
      p->model = BallModel::FromPhysical(par);
    } catch (const std::invalid_argument& e) {
      Fail(pp, ph, e.what());  // e.g. beta = M r^2 / I1 overflows
    }
    p->physical = par;
  }

  // lambda = (alpha + beta) / (1 + beta) in [1e-3, 1e3] (check.h), named by the given field.
  void RequireLambdaOf(double alpha, double beta, const std::string& path, const json& v) const {
    const double lambda = (alpha + beta) / (1.0 + beta);
    if (!(lambda >= internal::kMinLambda && lambda <= internal::kMaxLambda))
      Fail(path, v, "gives lambda = " + NumberText(lambda) + ", outside [" + NumberText(internal::kMinLambda) + ", " +
                        NumberText(internal::kMaxLambda) + "]");
  }

  void Initial(const json& j, const std::string& path, Problem* p) const {
    Object(j, path, {"theta", "phi", "psi", "mu", "x0", "orientation"});
    p->initial_angles.theta = Number(Require(j, path, "theta"), Join(path, "theta"));
    p->initial_angles.phi = Number(Require(j, path, "phi"), Join(path, "phi"));
    p->initial_angles.psi = Number(Require(j, path, "psi"), Join(path, "psi"));
    p->mu = Positive(Require(j, path, "mu"), Join(path, "mu"));
    InClosedRange(j["mu"], Join(path, "mu"), internal::kMinMu, internal::kMaxMu);
    p->x0 = Eigen::Vector2d::Zero();
    if (const json* v = Find(j, "x0")) p->x0 = Point(*v, Join(path, "x0"));
    p->A0 = Eigen::Matrix3d::Identity();
    if (const json* v = Find(j, "orientation")) p->A0 = Orientation(*v, Join(path, "orientation"));
  }

  SimulateTask Simulate(const json& j, const std::string& path) const {
    Object(j, path, {"t_end", "samples"});
    SimulateTask t;
    if (const json* v = Find(j, "t_end")) t.t_end = Positive(*v, Join(path, "t_end"));
    if (const json* v = Find(j, "samples")) t.samples = static_cast<int>(Integer(*v, Join(path, "samples"), 2, kMaxSamples));
    return t;
  }

  ReachTask Reach(const json& j, const std::string& path) const {
    Object(j, path, {"targets", "horizon_periods"});
    ReachTask t;
    t.targets = Points(Require(j, path, "targets"), Join(path, "targets"), 1, kMaxListLength);
    if (const json* v = Find(j, "horizon_periods"))
      t.horizon_periods = InRange(*v, Join(path, "horizon_periods"), 0.0, kMaxHorizonPeriods);
    return t;
  }

  // End points of a path, for the continuity check of piecewise paths.
  static Eigen::Vector2d Rot(double a, const Eigen::Vector2d& v) {
    return {std::cos(a) * v.x() - std::sin(a) * v.y(), std::sin(a) * v.x() + std::cos(a) * v.y()};
  }
  static Eigen::Vector2d LemniscatePoint(const LemniscateSpec& l, double tau) {
    const double d = 1.0 + std::sin(tau) * std::sin(tau);
    return l.center + Rot(l.rotation, l.scale * Eigen::Vector2d(std::cos(tau), std::sin(tau) * std::cos(tau)) / d);
  }
  static std::pair<Eigen::Vector2d, Eigen::Vector2d> EndPoints(const PathSpec& spec) {
    using Ends = std::pair<Eigen::Vector2d, Eigen::Vector2d>;
    struct Visitor {
      Ends operator()(const LineSpec& l) const { return {l.from, l.to}; }
      Ends operator()(const CircleSpec& c) const {
        auto at = [&](double t) -> Eigen::Vector2d { return c.center + c.radius * Eigen::Vector2d(std::cos(t), std::sin(t)); };
        return {at(c.tau_begin), at(c.tau_end)};
      }
      Ends operator()(const EllipseSpec& e) const {
        auto at = [&](double t) -> Eigen::Vector2d {
          return e.center + Rot(e.rotation, {e.semi_axes.x() * std::cos(t), e.semi_axes.y() * std::sin(t)});
        };
        return {at(e.tau_begin), at(e.tau_end)};
      }
      Ends operator()(const LemniscateSpec& l) const { return {LemniscatePoint(l, l.tau_begin), LemniscatePoint(l, l.tau_end)}; }
      Ends operator()(const SineSpec& w) const {
        return {w.from, w.from + Rot(w.rotation, {w.length, w.amplitude * std::sin(2.0 * M_PI * w.length / w.wavelength)})};
      }
      Ends operator()(const SamplesSpec& m) const { return {m.points.front(), m.points.back()}; }
      Ends operator()(const PiecewiseSpec& w) const {
        return {EndPoints(w.pieces.front()).first, EndPoints(w.pieces.back()).second};
      }
    };
    return std::visit(Visitor{}, spec.shape);
  }

  template <class Spec>
  void TauRange(const json& j, const std::string& path, Spec* s) const {
    s->tau_begin = Number(Require(j, path, "tau_begin"), Join(path, "tau_begin"));
    s->tau_end = Number(Require(j, path, "tau_end"), Join(path, "tau_end"));
    if (s->tau_end == s->tau_begin) Fail(Join(path, "tau_end"), j["tau_end"], "must differ from tau_begin (empty path)");
  }
  double OptionalRotation(const json& j, const std::string& path) const {
    const json* v = Find(j, "rotation");
    return v ? Number(*v, Join(path, "rotation")) : 0.0;
  }

  PathSpec Path(const json& j, const std::string& path, int depth) const {
    if (!j.is_object()) Fail(path, j, "must be a JSON object with a \"type\"");
    const std::string type = String(Require(j, path, "type"), Join(path, "type"));
    if (type == "line") {
      Object(j, path, {"type", "from", "to"});
      LineSpec s;
      s.from = Point(Require(j, path, "from"), Join(path, "from"));
      s.to = Point(Require(j, path, "to"), Join(path, "to"));
      if (s.from == s.to) Fail(Join(path, "to"), j["to"], "must differ from from (a line of length 0)");
      return {s};
    }
    if (type == "circle") {
      Object(j, path, {"type", "center", "radius", "tau_begin", "tau_end"});
      CircleSpec s;
      s.center = Point(Require(j, path, "center"), Join(path, "center"));
      s.radius = PositiveLength(Require(j, path, "radius"), Join(path, "radius"));
      TauRange(j, path, &s);
      return {s};
    }
    if (type == "ellipse") {
      Object(j, path, {"type", "center", "semi_axes", "rotation", "tau_begin", "tau_end"});
      EllipseSpec s;
      s.center = Point(Require(j, path, "center"), Join(path, "center"));
      const std::string sp = Join(path, "semi_axes");
      s.semi_axes = Vector<2>(Require(j, path, "semi_axes"), sp);
      for (std::size_t i = 0; i < 2; ++i) PositiveLength(j["semi_axes"][i], Index(sp, i));
      s.rotation = OptionalRotation(j, path);
      TauRange(j, path, &s);
      return {s};
    }
    if (type == "lemniscate") {
      Object(j, path, {"type", "center", "scale", "rotation", "tau_begin", "tau_end"});
      LemniscateSpec s;
      s.center = Point(Require(j, path, "center"), Join(path, "center"));
      s.scale = PositiveLength(Require(j, path, "scale"), Join(path, "scale"));
      s.rotation = OptionalRotation(j, path);
      TauRange(j, path, &s);
      return {s};
    }
    if (type == "sine") {
      Object(j, path, {"type", "from", "rotation", "length", "amplitude", "wavelength"});
      SineSpec s;
      s.from = Point(Require(j, path, "from"), Join(path, "from"));
      s.rotation = OptionalRotation(j, path);
      s.length = PositiveLength(Require(j, path, "length"), Join(path, "length"));
      s.amplitude = Coordinate(Require(j, path, "amplitude"), Join(path, "amplitude"));
      s.wavelength = PositiveLength(Require(j, path, "wavelength"), Join(path, "wavelength"));
      return {s};
    }
    if (type == "samples") return {Samples(j, path)};
    if (type == "piecewise") return {Piecewise(j, path, depth)};
    Fail(Join(path, "type"), j["type"],
         "unknown path type (one of line, circle, ellipse, lemniscate, sine, samples, piecewise)");
  }

  SamplesSpec Samples(const json& j, const std::string& path) const {
    Object(j, path, {"type", "points"});
    SamplesSpec s;
    const std::string pp = Join(path, "points");
    s.points = Points(Require(j, path, "points"), pp, 2, kMaxSamples);
    for (std::size_t i = 1; i < s.points.size(); ++i)
      if (s.points[i] == s.points[i - 1])
        Fail(Index(pp, i), j["points"][i], "repeats the previous point (consecutive samples must differ)");
    return s;
  }

  PiecewiseSpec Piecewise(const json& j, const std::string& path, int depth) const {
    Object(j, path, {"type", "pieces"});
    PiecewiseSpec s;
    const std::string pp = Join(path, "pieces");
    const json& pieces = Array(Require(j, path, "pieces"), pp, 1, kMaxListLength);
    if (depth >= kMaxPieceDepth)
      Fail(pp, pieces, "piecewise paths nested deeper than " + std::to_string(kMaxPieceDepth) + " levels");
    for (std::size_t i = 0; i < pieces.size(); ++i) {
      s.pieces.push_back(Path(pieces[i], Index(pp, i), depth + 1));
      if (i > 0) {
        const Eigen::Vector2d end = EndPoints(s.pieces[i - 1]).second;
        const Eigen::Vector2d start = EndPoints(s.pieces[i]).first;
        const double gap = (end - start).norm();
        if (!(gap <= kJoinTolerance * (1.0 + end.norm())))
          Fail(Index(pp, i), VectorText(start.data(), 2),
               "starts " + NumberText(gap) + " away from the end " + VectorText(end.data(), 2) +
                   " of the previous piece (consecutive pieces must share end points to 1e-9)");
      }
    }
    return s;
  }

  PartitionSpec Partition(const json& j, const std::string& path) const {
    Object(j, path, {"type", "n", "taus"});
    std::string type = "uniform_parameter";
    if (const json* v = Find(j, "type")) type = String(*v, Join(path, "type"));
    if (type == "explicit") {
      if (const json* v = Find(j, "n")) Fail(Join(path, "n"), *v, "not allowed for an explicit partition (n = taus - 1)");
      const std::string tp = Join(path, "taus");
      const json& taus = Array(Require(j, path, "taus"), tp, 2, kMaxCount + 1);
      ExplicitTaus s;
      for (std::size_t i = 0; i < taus.size(); ++i) {
        s.taus.push_back(Number(taus[i], Index(tp, i)));
        if (i > 0 && !(s.taus[i] > s.taus[i - 1])) Fail(Index(tp, i), taus[i], "taus must be strictly increasing");
      }
      return s;
    }
    if (type != "uniform_parameter" && type != "uniform_arc_length")
      Fail(Join(path, "type"), j["type"], "unknown partition type (one of uniform_parameter, uniform_arc_length, explicit)");
    if (const json* v = Find(j, "taus")) Fail(Join(path, "taus"), *v, "only allowed for an explicit partition");
    int n = UniformParameter{}.n;
    if (const json* v = Find(j, "n")) n = static_cast<int>(Integer(*v, Join(path, "n"), 1, kMaxCount));
    if (type == "uniform_parameter") return UniformParameter{n};
    return UniformArcLength{n};
  }

  PlanTask Plan(const json& j, const std::string& path) const {
    Object(j, path, {"path", "partition", "energy_changes", "converge_n"});
    PlanTask t;
    t.path = Path(Require(j, path, "path"), Join(path, "path"), 0);
    if (const json* v = Find(j, "partition")) t.partition = Partition(*v, Join(path, "partition"));
    if (const json* v = Find(j, "energy_changes")) {
      const std::string ep = Join(path, "energy_changes");
      Array(*v, ep, 0, kMaxListLength);
      for (std::size_t i = 0; i < v->size(); ++i) {
        const std::string e = Index(ep, i);
        const json& c = (*v)[i];
        Object(c, e, {"index", "factor"});
        EnergyChangeSpec spec;
        spec.index = static_cast<int>(Integer(Require(c, e, "index"), Join(e, "index"), 0, kMaxCount));
        spec.factor = Positive(Require(c, e, "factor"), Join(e, "factor"));
        t.energy_changes.push_back(spec);
      }
    }
    if (const json* v = Find(j, "converge_n")) {
      const std::string cp = Join(path, "converge_n");
      Array(*v, cp, 0, kMaxListLength);
      for (std::size_t i = 0; i < v->size(); ++i)
        t.converge_n.push_back(static_cast<int>(Integer((*v)[i], Index(cp, i), 1, kMaxCount)));
    }
    return t;
  }

  IsoparallelTask Isoparallel(const json& j, const std::string& path) const {
    Object(j, path, {"start", "goal", "start_orientation", "goal_orientation", "impulses", "solver"});
    IsoparallelTask t;
    t.start = Point(Require(j, path, "start"), Join(path, "start"));
    t.goal = Point(Require(j, path, "goal"), Join(path, "goal"));
    const double chord = (t.goal - t.start).norm();
    if (!(chord <= internal::kMaxIsoparallelChord))  // the family search grows like chord^3
      Fail(Join(path, "goal"), j["goal"], "|goal - start| = " + NumberText(chord) + " must be <= " +
                                              NumberText(internal::kMaxIsoparallelChord));
    if (const json* v = Find(j, "start_orientation")) t.start_orientation = Orientation(*v, Join(path, "start_orientation"));
    if (const json* v = Find(j, "goal_orientation")) t.goal_orientation = Orientation(*v, Join(path, "goal_orientation"));
    if (const json* v = Find(j, "impulses")) t.impulses = static_cast<int>(Integer(*v, Join(path, "impulses"), 1, kMaxCount));
    if (const json* v = Find(j, "solver")) {
      const std::string sp = Join(path, "solver");
      Object(*v, sp, {"starts", "length_cap_factor", "max_iterations", "tolerance", "threads", "enumerate_families"});
      // The solver's own options and ranges (isoparallel.h), so that the reader and the solver agree.
      IsoparallelOptions& s = t.solver;
      using O = IsoparallelOptions;
      if (const json* w = Find(*v, "starts")) s.starts = static_cast<int>(Integer(*w, Join(sp, "starts"), 1, O::kMaxStarts));
      if (const json* w = Find(*v, "length_cap_factor")) {
        s.length_cap_factor = Number(*w, Join(sp, "length_cap_factor"));
        if (!(s.length_cap_factor >= 1.0 && s.length_cap_factor <= O::kMaxLengthCapFactor))
          Fail(Join(sp, "length_cap_factor"), *w, "must be in [1, " + internal::FormatNumber(O::kMaxLengthCapFactor) + "]");
      }
      if (const json* w = Find(*v, "max_iterations"))
        s.max_iterations = static_cast<int>(Integer(*w, Join(sp, "max_iterations"), 1, O::kMaxIterations));
      if (const json* w = Find(*v, "tolerance")) s.tolerance = Tolerance(*w, Join(sp, "tolerance"));
      if (const json* w = Find(*v, "threads")) s.threads = static_cast<int>(Integer(*w, Join(sp, "threads"), 1, O::kMaxThreads));
      if (const json* w = Find(*v, "enumerate_families")) {
        if (!w->is_boolean()) Fail(Join(sp, "enumerate_families"), *w, "must be true or false");
        s.enumerate_families = w->get<bool>();
      }
    }
    return t;
  }

  bool Boolean(const json& v, const std::string& path) const {
    if (!v.is_boolean()) Fail(path, v, "must be true or false");
    return v.get<bool>();
  }

  SteerTask::Fewest Fewest(const json& j, const std::string& path) const {
    Object(j, path, {"max_impulses", "starts", "pareto_counts", "max_total_time", "orientation_only"});
    SteerTask::Fewest f;
    using O = FewestImpulsesOptions;
    if (const json* v = Find(j, "max_impulses")) f.max_impulses = static_cast<int>(Integer(*v, Join(path, "max_impulses"), 1, O::kMaxImpulses));
    if (const json* v = Find(j, "starts")) f.starts = static_cast<int>(Integer(*v, Join(path, "starts"), 1, O::kMaxStarts));
    if (const json* v = Find(j, "pareto_counts")) f.pareto_counts = static_cast<int>(Integer(*v, Join(path, "pareto_counts"), 1, O::kMaxImpulses));
    if (const json* v = Find(j, "max_total_time")) {
      f.max_total_time = NonNegative(*v, Join(path, "max_total_time"));
      if (f.max_total_time > 1e6) Fail(Join(path, "max_total_time"), *v, "must be in [0, 1e6] (0: automatic)");
    }
    if (const json* v = Find(j, "orientation_only")) f.orientation_only = Boolean(*v, Join(path, "orientation_only"));
    return f;
  }

  SteerTask Steer(const json& j, const std::string& path) const {
    Object(j, path, {"goal", "goal_orientation", "impulses", "start_at_rest", "stop_at_goal", "fewest"});
    SteerTask t;
    t.goal = Point(Require(j, path, "goal"), Join(path, "goal"));
    if (const json* v = Find(j, "goal_orientation")) t.goal_orientation = Orientation(*v, Join(path, "goal_orientation"));
    if (const json* v = Find(j, "impulses"))
      t.impulses = static_cast<int>(Integer(*v, Join(path, "impulses"), 3, kMaxExactImpulses));
    if (const json* v = Find(j, "start_at_rest")) t.start_at_rest = Boolean(*v, Join(path, "start_at_rest"));
    if (const json* v = Find(j, "stop_at_goal")) t.stop_at_goal = Boolean(*v, Join(path, "stop_at_goal"));
    if (const json* v = Find(j, "fewest")) t.fewest = Fewest(*v, Join(path, "fewest"));
    return t;
  }

  std::map<std::string, ExpectedValue> Expected(const json& j, const std::string& path) const {
    if (!j.is_object()) Fail(path, j, "must be a JSON object of name: {value, tolerance}");
    std::map<std::string, ExpectedValue> out;
    for (auto it = j.begin(); it != j.end(); ++it) {
      const std::string e = Join(path, it.key());
      if (it.key().empty()) Fail(e, it.value(), "golden value names must be non-empty");
      Object(it.value(), e, {"value", "tolerance"});
      ExpectedValue v;
      v.value = Number(Require(it.value(), e, "value"), Join(e, "value"));
      v.tolerance = NonNegative(Require(it.value(), e, "tolerance"), Join(e, "tolerance"));
      out[it.key()] = v;
    }
    return out;
  }

  Problem Document(const json& root) const {
    if (!root.is_object()) Fail("(document)", root, "a problem file must be a JSON object");
    Object(root, "", {"name", "description", "seed", "integration", "ball", "initial", "simulate", "reach",
                      "plan", "isoparallel", "steer", "expected"});
    Problem p;
    p.source = source_;
    if (const json* v = Find(root, "name")) p.name = String(*v, "name");
    if (const json* v = Find(root, "description")) p.description = String(*v, "description");
    if (const json* v = Find(root, "seed")) p.seed = Seed(*v, "seed");
    if (const json* v = Find(root, "integration")) Integration(*v, "integration", &p.integration);
    Ball(Require(root, "", "ball"), "ball", &p);
    Initial(Require(root, "", "initial"), "initial", &p);
    if (const json* v = Find(root, "simulate")) p.simulate = Simulate(*v, "simulate");
    if (const json* v = Find(root, "reach")) p.reach = Reach(*v, "reach");
    if (const json* v = Find(root, "plan")) p.plan = Plan(*v, "plan");
    if (const json* v = Find(root, "isoparallel")) p.isoparallel = Isoparallel(*v, "isoparallel");
    if (const json* v = Find(root, "steer")) p.steer = Steer(*v, "steer");
    if (const json* v = Find(root, "expected")) p.expected = Expected(*v, "expected");
    return p;
  }

  const std::string& source() const { return source_; }

 private:
  std::string source_;
};

// ------------------------------------------------------------------ parsing with diagnostics
// Builds the document through nlohmann's SAX interface in one pass (linear in the input: the
// callback parser rescans the parent container after each object, quadratic for a file of many
// small objects), rejects a key given twice in one object (JSON allows it, but it silently drops
// data), caps the nesting depth, and names the path of the value being parsed.
class DomBuilder {
 public:
  explicit DomBuilder(json* root) : root_(root) {}

  bool null() { return Add(json(nullptr)) != nullptr; }
  bool boolean(bool v) { return Add(json(v)) != nullptr; }
  bool number_integer(json::number_integer_t v) { return Add(json(v)) != nullptr; }
  bool number_unsigned(json::number_unsigned_t v) { return Add(json(v)) != nullptr; }
  bool number_float(json::number_float_t v, const json::string_t& /*text*/) { return Add(json(v)) != nullptr; }
  bool string(json::string_t& v) { return Add(json(std::move(v))) != nullptr; }
  bool binary(json::binary_t& v) { return Add(json::binary(std::move(v))) != nullptr; }
  bool start_object(std::size_t /*size*/) { return Open(json::object()); }
  bool start_array(std::size_t /*size*/) { return Open(json::array()); }
  bool key(json::string_t& k) {
    Frame& f = frames_.back();
    f.key = std::move(k);
    if (f.value->contains(f.key) && duplicate_path_.empty()) duplicate_path_ = CurrentPath();
    return true;
  }
  bool end_object() { return Close(); }
  bool end_array() { return Close(); }
  template <class Exception>
  bool parse_error(std::size_t /*position*/, const std::string& /*last_token*/, const Exception& e) {
    throw e;  // handled by ParseJson, as with json::parse
  }

  bool depth_exceeded() const { return depth_exceeded_; }
  const std::string& duplicate_path() const { return duplicate_path_; }
  /// Path of the value being parsed (empty at the top level).
  std::string CurrentPath() const {
    std::string s;
    for (std::size_t i = 0; i < frames_.size(); ++i) {
      const Frame& f = frames_[i];
      if (f.value->is_array()) {
        const std::size_t n = f.value->size();
        s += "[" + std::to_string(i + 1 < frames_.size() && n > 0 ? n - 1 : n) + "]";
      } else {
        s += (s.empty() ? "" : ".") + f.key;
      }
    }
    return s;
  }

 private:
  struct Frame {
    json* value;
    std::string key;
  };
  // Stores v in the open container (or as the root); returns where it went.
  json* Add(json v) {
    if (frames_.empty()) {
      *root_ = std::move(v);
      return root_;
    }
    Frame& f = frames_.back();
    if (f.value->is_array()) {
      f.value->push_back(std::move(v));
      return &f.value->back();
    }
    json& slot = (*f.value)[f.key];
    slot = std::move(v);
    return &slot;
  }
  bool Open(json container) {
    if (frames_.size() >= static_cast<std::size_t>(kMaxNestingDepth)) {
      depth_exceeded_ = true;
      return false;  // stops the parser
    }
    json* slot = Add(std::move(container));
    frames_.push_back({slot, {}});
    return true;
  }
  bool Close() {
    frames_.pop_back();
    return true;
  }

  json* root_;
  std::vector<Frame> frames_;
  std::string duplicate_path_;
  bool depth_exceeded_ = false;
};

json ParseJson(const std::string& text, const Reader& reader) {
  // nlohmann's lexer reads a NUL byte as the end of the input: anything after it would be
  // ignored silently.
  const std::size_t nul = text.find('\0');
  if (nul != std::string::npos)
    reader.Fail("(document)", "(NUL byte at offset " + std::to_string(nul) + ")",
                "a problem file is JSON text; it must not contain a NUL byte");
  json root;
  DomBuilder detector(&root);
  try {
    json::sax_parse(text, &detector, json::input_format_t::json, /*strict=*/true, /*ignore_comments=*/false);
  } catch (const json::parse_error& e) {
    // e.byte is the 1-based offset of the last character read (the offending token's end);
    // line and column are counted here (nlohmann's column is off after a newline).
    std::string what = e.what();
    const std::string marker = "column ";
    const auto at = what.find(marker);
    if (at != std::string::npos) {
      const auto colon = what.find(": ", at);
      if (colon != std::string::npos) what = what.substr(colon + 2);
    }
    const std::size_t end = std::min<std::size_t>(e.byte, text.size());
    const std::size_t last = end > 0 ? end - 1 : 0;
    std::size_t line = 1, line_start = 0;
    for (std::size_t i = 0; i < last && i < text.size(); ++i)
      if (text[i] == '\n') {
        ++line;
        line_start = i + 1;
      }
    what = "line " + std::to_string(line) + ", column " + std::to_string(last - line_start + 1) + ": " + what;
    const std::size_t begin = end > 24 ? end - 24 : 0;
    std::string excerpt = text.substr(begin, end - begin);
    for (char& c : excerpt)
      if (static_cast<unsigned char>(c) < 0x20 || static_cast<unsigned char>(c) >= 0x7f) c = ' ';
    reader.Fail("(document)", "'" + excerpt + "'", "malformed JSON at " + what);
  } catch (const json::exception& e) {
    // e.g. out_of_range.406, a number that overflows a double: name the field being parsed and
    // the offending token.
    std::string what = e.what();
    const auto close = what.find("] ");
    if (close != std::string::npos) what = what.substr(close + 2);
    std::string value = "(see message)";
    const auto q0 = what.find('\'');
    const auto q1 = q0 == std::string::npos ? q0 : what.find('\'', q0 + 1);
    if (q1 != std::string::npos) value = what.substr(q0 + 1, q1 - q0 - 1);
    const std::string field = detector.CurrentPath();
    reader.Fail(field.empty() ? "(document)" : field, value, "malformed JSON: " + what);
  }
  if (detector.depth_exceeded())
    reader.Fail(detector.CurrentPath().empty() ? "(document)" : detector.CurrentPath(), "(nested arrays/objects)",
                "nested deeper than " + std::to_string(kMaxNestingDepth) + " levels (the limit of a problem file)");
  if (!detector.duplicate_path().empty())
    reader.Fail(detector.duplicate_path(), "(duplicate)", "key given more than once in the same object");
  return root;
}

// ------------------------------------------------------------------ the writer
class Writer {
 public:
  double Num(const std::string& path, double v) const {
    if (!std::isfinite(v))
      throw std::invalid_argument("WriteProblemJson: " + path + ": value " + NumberText(v) + ": must be finite");
    return v;
  }
  ojson Vec(const std::string& path, const Eigen::Vector2d& v) const { return ojson::array({Num(path, v.x()), Num(path, v.y())}); }
  ojson Mat(const std::string& path, const Eigen::Matrix3d& m) const {
    ojson rows = ojson::array();
    for (int i = 0; i < 3; ++i) rows.push_back(ojson::array({Num(path, m(i, 0)), Num(path, m(i, 1)), Num(path, m(i, 2))}));
    return ojson{{"matrix", rows}};
  }
  ojson Points(const std::string& path, const std::vector<Eigen::Vector2d>& pts) const {
    ojson a = ojson::array();
    for (const auto& q : pts) a.push_back(Vec(path, q));
    return a;
  }

  ojson Path(const PathSpec& spec, const std::string& path) const {
    ojson o;
    o["type"] = ToString(spec);
    auto tau_range = [&](double begin, double end) {
      o["tau_begin"] = Num(path + ".tau_begin", begin);
      o["tau_end"] = Num(path + ".tau_end", end);
    };
    if (const auto* l = std::get_if<LineSpec>(&spec.shape)) {
      o["from"] = Vec(path + ".from", l->from);
      o["to"] = Vec(path + ".to", l->to);
    } else if (const auto* c = std::get_if<CircleSpec>(&spec.shape)) {
      o["center"] = Vec(path + ".center", c->center);
      o["radius"] = Num(path + ".radius", c->radius);
      tau_range(c->tau_begin, c->tau_end);
    } else if (const auto* e = std::get_if<EllipseSpec>(&spec.shape)) {
      o["center"] = Vec(path + ".center", e->center);
      o["semi_axes"] = Vec(path + ".semi_axes", e->semi_axes);
      o["rotation"] = Num(path + ".rotation", e->rotation);
      tau_range(e->tau_begin, e->tau_end);
    } else if (const auto* m = std::get_if<LemniscateSpec>(&spec.shape)) {
      o["center"] = Vec(path + ".center", m->center);
      o["scale"] = Num(path + ".scale", m->scale);
      o["rotation"] = Num(path + ".rotation", m->rotation);
      tau_range(m->tau_begin, m->tau_end);
    } else if (const auto* w = std::get_if<SineSpec>(&spec.shape)) {
      o["from"] = Vec(path + ".from", w->from);
      o["rotation"] = Num(path + ".rotation", w->rotation);
      o["length"] = Num(path + ".length", w->length);
      o["amplitude"] = Num(path + ".amplitude", w->amplitude);
      o["wavelength"] = Num(path + ".wavelength", w->wavelength);
    } else if (const auto* sm = std::get_if<SamplesSpec>(&spec.shape)) {
      o["points"] = Points(path + ".points", sm->points);
    } else {
      const PiecewiseSpec& pw = std::get<PiecewiseSpec>(spec.shape);
      ojson pieces = ojson::array();
      for (std::size_t i = 0; i < pw.pieces.size(); ++i)
        pieces.push_back(Path(pw.pieces[i], path + ".pieces[" + std::to_string(i) + "]"));
      o["pieces"] = pieces;
    }
    return o;
  }

  std::string Document(const Problem& p) const {
    ojson d;
    if (!p.name.empty()) d["name"] = p.name;
    if (!p.description.empty()) d["description"] = p.description;
    d["seed"] = p.seed;
    d["integration"] = ojson{{"absolute_tolerance", Num("integration.absolute_tolerance", p.integration.absolute_tolerance)},
                             {"relative_tolerance", Num("integration.relative_tolerance", p.integration.relative_tolerance)},
                             {"max_steps", p.integration.max_steps}};
    if (p.physical) {
      const PhysicalParameters& q = *p.physical;
      d["ball"]["physical"] = ojson{{"inertia_1", Num("ball.physical.inertia_1", q.inertia_1)},
                                    {"inertia_3", Num("ball.physical.inertia_3", q.inertia_3)},
                                    {"ball_mass", Num("ball.physical.ball_mass", q.ball_mass)},
                                    {"radius", Num("ball.physical.radius", q.radius)},
                                    {"plate_mass", Num("ball.physical.plate_mass", q.plate_mass)}};
    } else if (p.model.has_inertia()) {
      d["ball"] = ojson{{"alpha", Num("ball.alpha", p.model.alpha())}, {"beta", Num("ball.beta", p.model.beta())}};
    } else {
      d["ball"] = ojson{{"lambda", Num("ball.lambda", p.model.lambda())}};
    }
    d["initial"] = ojson{{"theta", Num("initial.theta", p.initial_angles.theta)},
                         {"phi", Num("initial.phi", p.initial_angles.phi)},
                         {"psi", Num("initial.psi", p.initial_angles.psi)},
                         {"mu", Num("initial.mu", p.mu)},
                         {"x0", Vec("initial.x0", p.x0)},
                         {"orientation", Mat("initial.orientation.matrix", p.A0)}};
    if (p.simulate)
      d["simulate"] = ojson{{"t_end", Num("simulate.t_end", p.simulate->t_end)}, {"samples", p.simulate->samples}};
    if (p.reach)
      d["reach"] = ojson{{"targets", Points("reach.targets", p.reach->targets)},
                         {"horizon_periods", Num("reach.horizon_periods", p.reach->horizon_periods)}};
    if (p.plan) {
      ojson plan;
      plan["path"] = Path(p.plan->path, "plan.path");
      ojson part;
      const PartitionSpec& rule = p.plan->partition;
      part["type"] = ToString(rule);
      if (const auto* e = std::get_if<ExplicitTaus>(&rule)) {
        ojson taus = ojson::array();
        for (double t : e->taus) taus.push_back(Num("plan.partition.taus", t));
        part["taus"] = taus;
      } else if (const auto* u = std::get_if<UniformParameter>(&rule)) {
        part["n"] = u->n;
      } else {
        part["n"] = std::get<UniformArcLength>(rule).n;
      }
      plan["partition"] = part;
      ojson changes = ojson::array();
      for (const EnergyChangeSpec& c : p.plan->energy_changes)
        changes.push_back(ojson{{"index", c.index}, {"factor", Num("plan.energy_changes.factor", c.factor)}});
      plan["energy_changes"] = changes;
      plan["converge_n"] = p.plan->converge_n;
      d["plan"] = plan;
    }
    if (p.isoparallel) {
      const IsoparallelTask& t = *p.isoparallel;
      d["isoparallel"] = ojson{
          {"start", Vec("isoparallel.start", t.start)},
          {"goal", Vec("isoparallel.goal", t.goal)},
          {"start_orientation", Mat("isoparallel.start_orientation.matrix", t.start_orientation)},
          {"goal_orientation", Mat("isoparallel.goal_orientation.matrix", t.goal_orientation)},
          {"impulses", t.impulses},
          {"solver", ojson{{"starts", t.solver.starts},
                           {"length_cap_factor", Num("isoparallel.solver.length_cap_factor", t.solver.length_cap_factor)},
                           {"max_iterations", t.solver.max_iterations},
                           {"tolerance", Num("isoparallel.solver.tolerance", t.solver.tolerance)},
                           {"threads", t.solver.threads},
                           {"enumerate_families", t.solver.enumerate_families}}}};
    }
    if (p.steer) {
      d["steer"] = ojson{{"goal", Vec("steer.goal", p.steer->goal)},
                         {"goal_orientation", Mat("steer.goal_orientation.matrix", p.steer->goal_orientation)},
                         {"impulses", p.steer->impulses},
                         {"start_at_rest", p.steer->start_at_rest},
                         {"stop_at_goal", p.steer->stop_at_goal}};
      if (const auto& f = p.steer->fewest)
        d["steer"]["fewest"] = ojson{{"max_impulses", f->max_impulses},
                                     {"starts", f->starts},
                                     {"pareto_counts", f->pareto_counts},
                                     {"max_total_time", Num("steer.fewest.max_total_time", f->max_total_time)},
                                     {"orientation_only", f->orientation_only}};
    }
    if (!p.expected.empty()) {
      ojson e = ojson::object();
      for (const auto& [name, v] : p.expected)
        e[name] = ojson{{"value", Num("expected." + name + ".value", v.value)},
                        {"tolerance", Num("expected." + name + ".tolerance", v.tolerance)}};
      d["expected"] = e;
    }
    return d.dump(2, ' ', false, ojson::error_handler_t::replace) + "\n";
  }
};

}  // namespace

std::string ToString(const PathSpec& spec) {
  static const char* const kNames[] = {"line", "circle", "ellipse", "lemniscate", "sine", "samples", "piecewise"};
  static_assert(std::variant_size_v<PathSpec::Shape> == 7, "one name per path shape");
  return kNames[spec.shape.index()];
}

// The one message for a problem text above kMaxFileBytes (a file, standard input or a string).
static std::string TooLargeMessage(const std::string& source_name) {
  return source_name + ": (file): value (more than " + std::to_string(kMaxFileBytes) + " bytes): larger than the " +
         std::to_string(kMaxFileBytes >> 20) + " MiB limit of a problem file";
}

Problem ParseProblem(const std::string& json_text, const std::string& source_name) {
  const Reader reader(source_name);
  if (json_text.size() > kMaxFileBytes) throw std::invalid_argument(TooLargeMessage(source_name));
  try {
    const json root = ParseJson(json_text, reader);
    return reader.Document(root);
  } catch (const std::invalid_argument&) {
    throw;
  } catch (const json::exception& e) {
    // Not expected (every access is checked); kept so that no input escapes as another type.
    reader.Fail("(document)", "(unknown)", std::string("unexpected JSON error: ") + e.what());
  }
}

Problem ReadProblemFile(const std::string& path) {
  std::error_code ec;
  if (std::filesystem::is_directory(path, ec))
    throw ProblemFileReadError(path + ": (file): value \"" + path + "\": is a directory, not a problem file");
  // Opening a FIFO blocks until a writer appears (an endless device is cut off by the size limit).
  if (std::filesystem::is_fifo(path, ec) || std::filesystem::is_socket(path, ec))
    throw ProblemFileReadError(path + ": (file): value \"" + path +
                               "\": a FIFO or socket, not a file; give a file, or \"-\" for standard input");
  std::ifstream in(path, std::ios::binary);
  if (!in) throw ProblemFileReadError(path + ": (file): value \"" + path + "\": cannot open the file for reading");
  std::string text;
  char buffer[1 << 16];
  while (in.read(buffer, sizeof buffer) || in.gcount() > 0) {
    text.append(buffer, static_cast<std::size_t>(in.gcount()));
    if (text.size() > kMaxFileBytes) throw std::invalid_argument(TooLargeMessage(path));
  }
  if (in.bad()) throw ProblemFileReadError(path + ": (file): value \"" + path + "\": read error");
  return ParseProblem(text, path);
}

std::string WriteProblemJson(const Problem& p) { return Writer().Document(p); }

Eigen::Matrix3d ParseOrientation(const std::string& json_text, const std::string& field,
                                 const std::string& source_name) {
  const Reader reader(source_name);
  try {
    const json root = ParseJson(json_text, reader);
    return reader.Orientation(root, field);
  } catch (const std::invalid_argument&) {
    throw;
  } catch (const json::exception& e) {
    reader.Fail(field, "(unknown)", std::string("unexpected JSON error: ") + e.what());
  }
}

}  // namespace plateball
