// The "simulate", "reach" and "expected" sections.
#include "plateball/limits.h"
#include "problem_io/field_archive.h"
#include "problem_io/section_readers.h"

namespace plateball::internal::problem_io {

SimulateTask RunSectionsReader::Simulate(const json& j, const std::string& path) const {
  SimulateTask t;
  ReadSection(*this, j, path, &t);
  return t;
}

ReachTask RunSectionsReader::Reach(const json& j, const std::string& path) const {
  Object(j, path, {"targets", "horizon_periods"});
  ReachTask t;
  t.targets = Points(Require(j, path, "targets"), Join(path, "targets"), 1, limits::kMaxListLength);
  if (const json* v = Find(j, "horizon_periods"))
    t.horizon_periods = InRange(*v, Join(path, "horizon_periods"), 0.0, limits::kMaxHorizonPeriods);
  return t;
}

std::map<std::string, ExpectedValue> RunSectionsReader::Expected(const json& j, const std::string& path) const {
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

}  // namespace plateball::internal::problem_io
