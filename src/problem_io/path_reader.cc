// The path of a plan ("plan.path"): line, circle, ellipse, lemniscate, sine, samples or piecewise.
// Consecutive pieces of a piecewise path must share end points.
#include <cmath>
#include <utility>
#include <variant>

#include "plateball/limits.h"
#include "problem_io/section_readers.h"

namespace plateball::internal::problem_io {
namespace {

constexpr double kJoinTolerance = 1e-9;  // piecewise end points must match to this (relative)

// End points of a path, for the continuity check of piecewise paths.
Eigen::Vector2d Rot(double a, const Eigen::Vector2d& v) {
  return {std::cos(a) * v.x() - std::sin(a) * v.y(), std::sin(a) * v.x() + std::cos(a) * v.y()};
}
Eigen::Vector2d LemniscatePoint(const LemniscateSpec& l, double tau) {
  const double d = 1.0 + std::sin(tau) * std::sin(tau);
  return l.center + Rot(l.rotation, l.scale * Eigen::Vector2d(std::cos(tau), std::sin(tau) * std::cos(tau)) / d);
}
std::pair<Eigen::Vector2d, Eigen::Vector2d> EndPoints(const PathSpec& spec) {
  using Ends = std::pair<Eigen::Vector2d, Eigen::Vector2d>;
  struct Visitor {
    Ends operator()(const LineSpec& l) const { return {l.from, l.to}; }
    Ends operator()(const CircleSpec& c) const {
      auto at = [&](double t) -> Eigen::Vector2d {
        return c.center + c.radius * Eigen::Vector2d(std::cos(t), std::sin(t));
      };
      return {at(c.tau_begin), at(c.tau_end)};
    }
    Ends operator()(const EllipseSpec& e) const {
      auto at = [&](double t) -> Eigen::Vector2d {
        return e.center + Rot(e.rotation, {e.semi_axes.x() * std::cos(t), e.semi_axes.y() * std::sin(t)});
      };
      return {at(e.tau_begin), at(e.tau_end)};
    }
    Ends operator()(const LemniscateSpec& l) const {
      return {LemniscatePoint(l, l.tau_begin), LemniscatePoint(l, l.tau_end)};
    }
    Ends operator()(const SineSpec& w) const {
      return {w.from,
              w.from + Rot(w.rotation, {w.length, w.amplitude * std::sin(2.0 * M_PI * w.length / w.wavelength)})};
    }
    Ends operator()(const SamplesSpec& m) const { return {m.points.front(), m.points.back()}; }
    Ends operator()(const PiecewiseSpec& w) const {
      return {EndPoints(w.pieces.front()).first, EndPoints(w.pieces.back()).second};
    }
  };
  return std::visit(Visitor{}, spec.shape);
}

}  // namespace

template <class Spec>
void PathReader::TauRange(const json& j, const std::string& path, Spec* s) const {
  s->tau_begin = Number(Require(j, path, "tau_begin"), Join(path, "tau_begin"));
  s->tau_end = Number(Require(j, path, "tau_end"), Join(path, "tau_end"));
  if (s->tau_end == s->tau_begin) Fail(Join(path, "tau_end"), j["tau_end"], "must differ from tau_begin (empty path)");
}
double PathReader::OptionalRotation(const json& j, const std::string& path) const {
  const json* v = Find(j, "rotation");
  return v ? Number(*v, Join(path, "rotation")) : 0.0;
}

PathSpec PathReader::Path(const json& j, const std::string& path, int depth) const {
  if (!j.is_object()) Fail(path, j, "must be a JSON object with a \"type\"");
  const std::string type = String(Require(j, path, "type"), Join(path, "type"));
  if (type == "line") return Line(j, path);
  if (type == "circle") return Circle(j, path);
  if (type == "ellipse") return Ellipse(j, path);
  if (type == "lemniscate") return Lemniscate(j, path);
  if (type == "sine") return Sine(j, path);
  if (type == "samples") return {Samples(j, path)};
  if (type == "piecewise") return {Piecewise(j, path, depth)};
  Fail(Join(path, "type"),
       j["type"],
       "unknown path type (one of line, circle, ellipse, lemniscate, sine, samples, piecewise)");
}

PathSpec PathReader::Line(const json& j, const std::string& path) const {
  Object(j, path, {"type", "from", "to"});
  LineSpec s;
  s.from = Point(Require(j, path, "from"), Join(path, "from"));
  s.to = Point(Require(j, path, "to"), Join(path, "to"));
  if (s.from == s.to) Fail(Join(path, "to"), j["to"], "must differ from from (a line of length 0)");
  return {s};
}

PathSpec PathReader::Circle(const json& j, const std::string& path) const {
  Object(j, path, {"type", "center", "radius", "tau_begin", "tau_end"});
  CircleSpec s;
  s.center = Point(Require(j, path, "center"), Join(path, "center"));
  s.radius = PositiveLength(Require(j, path, "radius"), Join(path, "radius"));
  TauRange(j, path, &s);
  return {s};
}

PathSpec PathReader::Ellipse(const json& j, const std::string& path) const {
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

PathSpec PathReader::Lemniscate(const json& j, const std::string& path) const {
  Object(j, path, {"type", "center", "scale", "rotation", "tau_begin", "tau_end"});
  LemniscateSpec s;
  s.center = Point(Require(j, path, "center"), Join(path, "center"));
  s.scale = PositiveLength(Require(j, path, "scale"), Join(path, "scale"));
  s.rotation = OptionalRotation(j, path);
  TauRange(j, path, &s);
  return {s};
}

PathSpec PathReader::Sine(const json& j, const std::string& path) const {
  Object(j, path, {"type", "from", "rotation", "length", "amplitude", "wavelength"});
  SineSpec s;
  s.from = Point(Require(j, path, "from"), Join(path, "from"));
  s.rotation = OptionalRotation(j, path);
  s.length = PositiveLength(Require(j, path, "length"), Join(path, "length"));
  s.amplitude = Coordinate(Require(j, path, "amplitude"), Join(path, "amplitude"));
  s.wavelength = PositiveLength(Require(j, path, "wavelength"), Join(path, "wavelength"));
  return {s};
}

SamplesSpec PathReader::Samples(const json& j, const std::string& path) const {
  Object(j, path, {"type", "points"});
  SamplesSpec s;
  const std::string pp = Join(path, "points");
  s.points = Points(Require(j, path, "points"), pp, 2, limits::kMaxSamples);
  for (std::size_t i = 1; i < s.points.size(); ++i)
    if (s.points[i] == s.points[i - 1])
      Fail(Index(pp, i), j["points"][i], "repeats the previous point (consecutive samples must differ)");
  return s;
}

PiecewiseSpec PathReader::Piecewise(const json& j, const std::string& path, int depth) const {
  Object(j, path, {"type", "pieces"});
  PiecewiseSpec s;
  const std::string pp = Join(path, "pieces");
  const json& pieces = Array(Require(j, path, "pieces"), pp, 1, limits::kMaxListLength);
  if (depth >= limits::kMaxPieceDepth)
    Fail(pp, pieces, "piecewise paths nested deeper than " + std::to_string(limits::kMaxPieceDepth) + " levels");
  for (std::size_t i = 0; i < pieces.size(); ++i) {
    s.pieces.push_back(Path(pieces[i], Index(pp, i), depth + 1));
    if (i > 0) {
      const Eigen::Vector2d end = EndPoints(s.pieces[i - 1]).second;
      const Eigen::Vector2d start = EndPoints(s.pieces[i]).first;
      const double gap = (end - start).norm();
      if (!(gap <= kJoinTolerance * (1.0 + end.norm())))
        Fail(Index(pp, i),
             VectorText(start.data(), 2),
             "starts " + NumberText(gap) + " away from the end " + VectorText(end.data(), 2) +
                 " of the previous piece (consecutive pieces must share end points to 1e-9)");
    }
  }
  return s;
}

}  // namespace plateball::internal::problem_io
