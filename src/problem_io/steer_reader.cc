// The "steer" section: the goal, exact arrival's impulses and the fewest-impulses options.
#include "plateball/exact_arrival.h"
#include "plateball/fewest_impulses.h"
#include "problem_io/field_archive.h"
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
  SteerTask::Fewest f;
  ReadSection(*this, j, path, &f);
  return f;
}

}  // namespace plateball::internal::problem_io
