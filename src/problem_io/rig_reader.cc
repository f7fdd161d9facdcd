// The "rig" section: the limits of a physical rig (rig_limits.h).
#include "plateball/rig_limits.h"
#include "problem_io/field_archive.h"
#include "problem_io/section_readers.h"

namespace plateball::internal::problem_io {

RigLimits RigReader::Rig(const json& j,
                         const std::string& path,
                         const std::optional<PhysicalParameters>& physical) const {
  // The key set and the scalar limits by RigLimits' field list; its ByHand fields (the shapes,
  // the stroke and pulse_duration) below, as the list cannot express them.
  RigLimits l;
  ReadSection(*this, j, path, &l, {"length_unit"});
  double scale = 1.0;  // ball radii per unit of the section's lengths
  if (const json* v = Find(j, "length_unit")) {
    const std::string unit = String(*v, Join(path, "length_unit"));
    if (unit == "m") {
      if (!physical) Fail(Join(path, "length_unit"), *v, "\"m\" needs ball.physical (the radius in metres)");
      scale = 1.0 / physical->radius;
    } else if (unit != "radius") {
      Fail(Join(path, "length_unit"), *v, "must be \"radius\" or \"m\"");
    }
  }
  if (const json* v = Find(j, "plate")) l.plate = Shape(*v, Join(path, "plate"), scale);
  if (const json* v = Find(j, "obstacles")) {
    const json& a = Array(*v, Join(path, "obstacles"), 0, 1000);
    for (std::size_t i = 0; i < a.size(); ++i)
      l.obstacles.push_back(Shape(a[i], Index(Join(path, "obstacles"), i), scale));
  }
  l.clearance *= scale;
  if (const json* v = Find(j, "stroke")) {
    const Eigen::Vector2d stroke = Vector<2>(*v, Join(path, "stroke"));
    for (std::size_t i = 0; i < 2; ++i)
      if (!(stroke[static_cast<Eigen::Index>(i)] > 0)) Fail(Index(Join(path, "stroke"), i), (*v)[i], "must be > 0");
    l.stroke = scale * stroke;
  }
  if (Find(j, "max_force"))
    l.pulse_duration = Positive(Require(j, path, "pulse_duration"), Join(path, "pulse_duration"));
  else if (const json* d = Find(j, "pulse_duration"))
    Fail(Join(path, "pulse_duration"), *d, "is used only with max_force (the mean force is |J| / pulse_duration)");
  if (l.NeedsPhysical() && !physical)
    Fail(Join(path, Find(j, "max_plate_impulse") ? "max_plate_impulse" : "max_force"),
         *Find(j, Find(j, "max_plate_impulse") ? "max_plate_impulse" : "max_force"),
         "needs ball.physical (a bare lambda fixes no masses)");
  const std::string e = l.Validate();
  if (!e.empty()) throw std::invalid_argument(source() + ": " + e);
  return l;
}

PlateShape RigReader::Shape(const json& j, const std::string& path, double scale) const {
  if (!j.is_object()) Fail(path, j, "must be an object with \"type\": \"disk\", \"rectangle\" or \"polygon\"");
  const std::string type = String(Require(j, path, "type"), Join(path, "type"));
  if (type == "disk") {
    Object(j, path, {"type", "center", "radius"});
    return DiskShape{scale * Point(Require(j, path, "center"), Join(path, "center")),
                     scale * Positive(Require(j, path, "radius"), Join(path, "radius"))};
  }
  if (type == "rectangle") {
    Object(j, path, {"type", "min", "max"});
    const Eigen::Vector2d lo = scale * Point(Require(j, path, "min"), Join(path, "min"));
    const Eigen::Vector2d hi = scale * Point(Require(j, path, "max"), Join(path, "max"));
    if (!(hi.x() > lo.x() && hi.y() > lo.y())) Fail(Join(path, "max"), j["max"], "must exceed min in both coordinates");
    return PolygonShape{{lo, Eigen::Vector2d(hi.x(), lo.y()), hi, Eigen::Vector2d(lo.x(), hi.y())}};
  }
  if (type == "polygon") {
    Object(j, path, {"type", "vertices"});
    PolygonShape p{Points(Require(j, path, "vertices"), Join(path, "vertices"), 3, 1000)};
    for (Eigen::Vector2d& v : p.vertices) v *= scale;
    return p;
  }
  Fail(Join(path, "type"), j["type"], "must be \"disk\", \"rectangle\" or \"polygon\"");
}

}  // namespace plateball::internal::problem_io
