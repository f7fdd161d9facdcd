// The "isoparallel" section: start and goal (chord <= kMaxIsoparallelChord), orientations, the
// number of impulses and the solver's options.
#include "check.h"
#include "plateball/isoparallel.h"
#include "plateball/limits.h"
#include "problem_io/field_archive.h"
#include "problem_io/section_readers.h"

namespace plateball::internal::problem_io {
IsoparallelTask IsoparallelReader::Isoparallel(const json& j, const std::string& path) const {
  Object(j, path, {"start", "goal", "start_orientation", "goal_orientation", "impulses", "solver"});
  IsoparallelTask t;
  t.start = Point(Require(j, path, "start"), Join(path, "start"));
  t.goal = Point(Require(j, path, "goal"), Join(path, "goal"));
  const double chord = (t.goal - t.start).norm();
  if (!(chord <= internal::kMaxIsoparallelChord))  // the family search grows like chord^3
    Fail(Join(path, "goal"),
         j["goal"],
         "|goal - start| = " + NumberText(chord) + " must be <= " + NumberText(internal::kMaxIsoparallelChord));
  if (const json* v = Find(j, "start_orientation"))
    t.start_orientation = Orientation(*v, Join(path, "start_orientation"));
  if (const json* v = Find(j, "goal_orientation")) t.goal_orientation = Orientation(*v, Join(path, "goal_orientation"));
  if (const json* v = Find(j, "impulses"))
    t.impulses = static_cast<int>(Integer(*v, Join(path, "impulses"), 1, kMaxPartitionCount));
  if (const json* v = Find(j, "solver")) Solver(*v, Join(path, "solver"), &t.solver);
  return t;
}

// The solver's own options and ranges (IsoparallelOptions::Serialize), so that the reader and the
// solver agree.
void IsoparallelReader::Solver(const json& v, const std::string& sp, IsoparallelOptions* s) const {
  ReadSection(*this, v, sp, s);
}

}  // namespace plateball::internal::problem_io
