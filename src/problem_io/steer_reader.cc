// The "steer" section: the goal, exact arrival's impulses and the fewest-impulses options.
#include "plateball/exact_arrival.h"
#include "plateball/fewest_impulses.h"
#include "problem_io/section_readers.h"

namespace plateball::internal::problem_io {

SteerTask SteerReader::Steer(const json& j, const std::string& path) const {
  Object(j, path, {"goal", "goal_orientation", "impulses", "start_at_rest", "stop_at_goal", "objective", "fewest"});
  SteerTask t;
  t.goal = Point(Require(j, path, "goal"), Join(path, "goal"));
  if (const json* v = Find(j, "goal_orientation")) t.goal_orientation = Orientation(*v, Join(path, "goal_orientation"));
  if (const json* v = Find(j, "impulses"))
    t.impulses = static_cast<int>(Integer(*v, Join(path, "impulses"), 3, kMaxExactImpulses));
  if (const json* v = Find(j, "start_at_rest")) t.start_at_rest = Boolean(*v, Join(path, "start_at_rest"));
  if (const json* v = Find(j, "stop_at_goal")) t.stop_at_goal = Boolean(*v, Join(path, "stop_at_goal"));
  if (const json* v = Find(j, "objective")) {
    const auto o = ArrivalObjectiveFromString(String(*v, Join(path, "objective")));
    if (!o) Fail(Join(path, "objective"), *v, "must be \"deviation\", \"time\", \"impulse\" or \"fewest\"");
    t.objective = *o;
  }
  if (const json* v = Find(j, "fewest")) t.fewest = Fewest(*v, Join(path, "fewest"));
  return t;
}

SteerTask::Fewest SteerReader::Fewest(const json& j, const std::string& path) const {
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

}  // namespace plateball::internal::problem_io
