// One reader per section of a problem file (schemas/input/problem.schema.json). Each is a
// FieldReader (same source name, same message format) that reads its section into the
// library's struct; DocumentReader reads the top level and calls the others.
#pragma once

#include <map>
#include <string>

#include "plateball/limits.h"
#include "plateball/problem.h"
#include "problem_io/field_reader.h"

namespace plateball::internal::problem_io {

/// The largest count a section accepts: partition n, impulse counts and indices.
inline constexpr long long kMaxPartitionCount = limits::kMaxPartitionSteps;

/// "integration", "ball" and "initial": the model and the start state.
class StartStateReader : public FieldReader {
 public:
  explicit StartStateReader(const FieldReader& r) : FieldReader(r) {}
  void Integration(const json& j, const std::string& path, IntegrationOptions* o) const;
  void Ball(const json& j, const std::string& path, Problem* p) const;
  void Initial(const json& j, const std::string& path, Problem* p) const;

 private:
  void PhysicalBall(const json& ph, const std::string& pp, Problem* p) const;
  // lambda = (alpha + beta) / (1 + beta) in [1e-3, 1e3] (check.h), named by the given field.
  void RequireLambdaOf(double alpha, double beta, const std::string& path, const json& v) const;
  double Angle(const json& j, const std::string& path, const char* key) const;
};

/// A path of "plan.path": one of seven shapes, piecewise paths nested at most kMaxPieceDepth deep.
class PathReader : public FieldReader {
 public:
  explicit PathReader(const FieldReader& r) : FieldReader(r) {}
  PathSpec Path(const json& j, const std::string& path, int depth) const;

 private:
  PathSpec Line(const json& j, const std::string& path) const;
  PathSpec Circle(const json& j, const std::string& path) const;
  PathSpec Ellipse(const json& j, const std::string& path) const;
  PathSpec Lemniscate(const json& j, const std::string& path) const;
  PathSpec Sine(const json& j, const std::string& path) const;
  SamplesSpec Samples(const json& j, const std::string& path) const;
  PiecewiseSpec Piecewise(const json& j, const std::string& path, int depth) const;
  template <class Spec>
  void TauRange(const json& j, const std::string& path, Spec* s) const;
  double OptionalRotation(const json& j, const std::string& path) const;
};

/// "plan": the path, its partition, energy changes and the convergence study's n.
class PlanReader : public FieldReader {
 public:
  explicit PlanReader(const FieldReader& r) : FieldReader(r) {}
  PlanTask Plan(const json& j, const std::string& path) const;

 private:
  PartitionSpec Partition(const json& j, const std::string& path) const;
  std::vector<EnergyChangeSpec> EnergyChanges(const json& v, const std::string& path) const;
};

/// "simulate", "reach" and "expected" (golden values).
class RunSectionsReader : public FieldReader {
 public:
  explicit RunSectionsReader(const FieldReader& r) : FieldReader(r) {}
  SimulateTask Simulate(const json& j, const std::string& path) const;
  ReachTask Reach(const json& j, const std::string& path) const;
  std::map<std::string, ExpectedValue> Expected(const json& j, const std::string& path) const;
};

/// "isoparallel" with its "solver" options.
class IsoparallelReader : public FieldReader {
 public:
  explicit IsoparallelReader(const FieldReader& r) : FieldReader(r) {}
  IsoparallelTask Isoparallel(const json& j, const std::string& path) const;

 private:
  void Solver(const json& v, const std::string& sp, IsoparallelOptions* s) const;
};

/// "steer" with its "fewest" options.
class SteerReader : public FieldReader {
 public:
  explicit SteerReader(const FieldReader& r) : FieldReader(r) {}
  SteerTask Steer(const json& j, const std::string& path) const;

 private:
  SteerTask::Fewest Fewest(const json& j, const std::string& path) const;
};

/// "rig": the plate region, obstacles, stroke, actuator bounds and timing (rig_limits.h), lengths
/// in ball radii or, with "length_unit": "m" and ball.physical, in metres.
class RigReader : public FieldReader {
 public:
  explicit RigReader(const FieldReader& r) : FieldReader(r) {}
  RigLimits Rig(const json& j, const std::string& path, const std::optional<PhysicalParameters>& physical) const;

 private:
  PlateShape Shape(const json& j, const std::string& path, double scale) const;
};

/// The whole document: its top-level keys, each section by its reader.
class DocumentReader : public FieldReader {
 public:
  explicit DocumentReader(const FieldReader& r) : FieldReader(r) {}
  Problem Document(const json& root) const;
};

}  // namespace plateball::internal::problem_io
