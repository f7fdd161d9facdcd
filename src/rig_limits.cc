#include "plateball/rig_limits.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>

#include "check.h"

namespace plateball {

namespace {

// Distance from x to the segment [a, b] and the nearest point on it.
double SegmentDistance(const Eigen::Vector2d& x,
                       const Eigen::Vector2d& a,
                       const Eigen::Vector2d& b,
                       Eigen::Vector2d* nearest) {
  const Eigen::Vector2d ab = b - a;
  const double len2 = ab.squaredNorm();
  const double t = len2 > 0 ? std::clamp((x - a).dot(ab) / len2, 0.0, 1.0) : 0.0;
  *nearest = a + t * ab;
  return (x - *nearest).norm();
}

// Even-odd rule: true when x is inside the polygon.
bool InsidePolygon(const std::vector<Eigen::Vector2d>& v, const Eigen::Vector2d& x) {
  bool inside = false;
  for (std::size_t i = 0, j = v.size() - 1; i < v.size(); j = i++) {
    if ((v[i].y() > x.y()) != (v[j].y() > x.y()) &&
        x.x() < (v[j].x() - v[i].x()) * (x.y() - v[i].y()) / (v[j].y() - v[i].y()) + v[i].x())
      inside = !inside;
  }
  return inside;
}

double PolygonSignedDistance(const PolygonShape& p, const Eigen::Vector2d& x, Eigen::Vector2d* gradient) {
  double best = std::numeric_limits<double>::infinity();
  Eigen::Vector2d best_point = p.vertices.front();
  for (std::size_t i = 0; i < p.vertices.size(); ++i) {
    Eigen::Vector2d q;
    const double d = SegmentDistance(x, p.vertices[i], p.vertices[(i + 1) % p.vertices.size()], &q);
    if (d < best) best = d, best_point = q;
  }
  const double sign = InsidePolygon(p.vertices, x) ? 1.0 : -1.0;
  if (gradient) {
    const Eigen::Vector2d away = x - best_point;
    *gradient = best > 0 ? Eigen::Vector2d(sign * away / best) : Eigen::Vector2d::Zero();
  }
  return sign * best;
}

double DiskSignedDistance(const DiskShape& d, const Eigen::Vector2d& x, Eigen::Vector2d* gradient) {
  const Eigen::Vector2d r = x - d.center;
  const double len = r.norm();
  // At the center every direction is a normal: any unit vector is a valid (sub)gradient.
  if (gradient) *gradient = len > 0 ? Eigen::Vector2d(-r / len) : Eigen::Vector2d(-1.0, 0.0);
  return d.radius - len;
}

// Twice the signed area: zero for a degenerate polygon.
double TwiceArea(const std::vector<Eigen::Vector2d>& v) {
  double a = 0.0;
  for (std::size_t i = 0; i < v.size(); ++i) {
    const Eigen::Vector2d& p = v[i];
    const Eigen::Vector2d& q = v[(i + 1) % v.size()];
    a += p.x() * q.y() - q.x() * p.y();
  }
  return a;
}

std::string ValidateShape(const std::string& field, const PlateShape& shape) {
  using internal::InvalidValueMessage;
  if (const auto* d = std::get_if<DiskShape>(&shape)) {
    if (!(std::isfinite(d->center.x()) && std::isfinite(d->center.y())))
      return InvalidValueMessage(field + ".center", "(non-finite)", "must be finite");
    if (!(std::isfinite(d->radius) && d->radius > 0))
      return InvalidValueMessage(field + ".radius", d->radius, "must be finite and > 0");
    return "";
  }
  const auto& p = std::get<PolygonShape>(shape);
  if (p.vertices.size() < 3 || p.vertices.size() > 1000)
    return InvalidValueMessage(field + ".vertices", p.vertices.size(), "must hold 3 to 1000 points");
  for (std::size_t i = 0; i < p.vertices.size(); ++i)
    if (!p.vertices[i].allFinite())
      return InvalidValueMessage(field + ".vertices[" + std::to_string(i) + "]", "(non-finite)", "must be finite");
  if (!(std::abs(TwiceArea(p.vertices)) > 0))
    return InvalidValueMessage(field + ".vertices", "(zero area)", "the polygon encloses no area");
  return "";
}

}  // namespace

std::string ToString(ArrivalObjective objective) {
  switch (objective) {
    case ArrivalObjective::kDeviation:
      return "deviation";
    case ArrivalObjective::kTotalTime:
      return "time";
    case ArrivalObjective::kTotalImpulse:
      return "impulse";
    case ArrivalObjective::kFewest:
      return "fewest";
  }
  return "unknown";
}

std::optional<ArrivalObjective> ArrivalObjectiveFromString(const std::string& word) {
  for (ArrivalObjective o : {ArrivalObjective::kDeviation,
                             ArrivalObjective::kTotalTime,
                             ArrivalObjective::kTotalImpulse,
                             ArrivalObjective::kFewest})
    if (ToString(o) == word) return o;
  return std::nullopt;
}

double SignedDistanceInside(const PlateShape& shape, const Eigen::Vector2d& x, Eigen::Vector2d* gradient) {
  if (const auto* d = std::get_if<DiskShape>(&shape)) return DiskSignedDistance(*d, x, gradient);
  return PolygonSignedDistance(std::get<PolygonShape>(shape), x, gradient);
}

bool RigLimits::Empty() const {
  return !plate && obstacles.empty() && !stroke && std::isinf(max_plate_velocity_change) &&
         std::isinf(ImpulseBound()) && min_interval == 0.0 && tick == 0.0;
}

double RigLimits::ImpulseBound() const {
  const double force_bound = std::isinf(max_force) ? max_force : max_force * pulse_duration;
  return std::min(max_plate_impulse, force_bound);
}

bool RigLimits::NeedsPhysical() const { return !std::isinf(max_plate_impulse) || !std::isinf(max_force); }

std::string RigLimits::Validate() const {
  using internal::InvalidValueMessage;
  if (plate) {
    const std::string e = ValidateShape("rig.plate", *plate);
    if (!e.empty()) return e;
  }
  for (std::size_t i = 0; i < obstacles.size(); ++i) {
    const std::string e = ValidateShape("rig.obstacles[" + std::to_string(i) + "]", obstacles[i]);
    if (!e.empty()) return e;
  }
  if (!(std::isfinite(clearance) && clearance >= 0))
    return InvalidValueMessage("rig.clearance", clearance, "must be finite and >= 0");
  if (stroke && !(std::isfinite(stroke->x()) && std::isfinite(stroke->y()) && stroke->minCoeff() > 0))
    return InvalidValueMessage(
        "rig.stroke",
        "(" + internal::FormatNumber(stroke->x()) + ", " + internal::FormatNumber(stroke->y()) + ")",
        "both half-ranges must be finite and > 0");
  const auto positive_or_inf = [](double v) { return v > 0 && !std::isnan(v); };
  if (!positive_or_inf(max_plate_velocity_change))
    return InvalidValueMessage("rig.max_plate_velocity_change", max_plate_velocity_change, "must be > 0");
  if (!positive_or_inf(max_plate_impulse))
    return InvalidValueMessage("rig.max_plate_impulse", max_plate_impulse, "must be > 0");
  if (!positive_or_inf(max_force)) return InvalidValueMessage("rig.max_force", max_force, "must be > 0");
  if (!(std::isfinite(pulse_duration) && pulse_duration >= 0))
    return InvalidValueMessage("rig.pulse_duration", pulse_duration, "must be finite and >= 0");
  if (!std::isinf(max_force) && pulse_duration == 0)
    return InvalidValueMessage("rig.pulse_duration",
                               pulse_duration,
                               "must be > 0 with rig.max_force (the mean force is |J| / pulse_duration)");
  if (!(std::isfinite(min_interval) && min_interval >= 0))
    return InvalidValueMessage("rig.min_interval", min_interval, "must be finite and >= 0");
  if (!(std::isfinite(tick) && tick >= 0)) return InvalidValueMessage("rig.tick", tick, "must be finite and >= 0");
  return "";
}

}  // namespace plateball
