// The "isoparallel" section: start and goal (chord <= kMaxIsoparallelChord), orientations, the
// number of impulses and the solver's options.
#include "check.h"
#include "plateball/isoparallel.h"
#include "plateball/limits.h"
#include "problem_io/section_readers.h"

namespace plateball::internal::problem_io {
IsoparallelTask IsoparallelReader::Isoparallel(const json& j, const std::string& path) const {
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
  if (const json* v = Find(j, "impulses")) t.impulses = static_cast<int>(Integer(*v, Join(path, "impulses"), 1, kMaxPartitionCount));
  if (const json* v = Find(j, "solver")) Solver(*v, Join(path, "solver"), &t.solver);
  return t;
}

// The solver's own options and ranges (isoparallel.h), so that the reader and the solver agree.
void IsoparallelReader::Solver(const json& v, const std::string& sp, IsoparallelOptions* s) const {
  Object(v, sp, {"starts", "length_cap_factor", "max_iterations", "tolerance", "threads", "enumerate_families"});
  using O = IsoparallelOptions;
  if (const json* w = Find(v, "starts")) s->starts = static_cast<int>(Integer(*w, Join(sp, "starts"), 1, O::kMaxStarts));
  if (const json* w = Find(v, "length_cap_factor")) {
    s->length_cap_factor = Number(*w, Join(sp, "length_cap_factor"));
    if (!(s->length_cap_factor >= 1.0 && s->length_cap_factor <= O::kMaxLengthCapFactor))
      Fail(Join(sp, "length_cap_factor"), *w, "must be in [1, " + internal::FormatNumber(O::kMaxLengthCapFactor) + "]");
  }
  if (const json* w = Find(v, "max_iterations"))
    s->max_iterations = static_cast<int>(Integer(*w, Join(sp, "max_iterations"), 1, O::kMaxIterations));
  if (const json* w = Find(v, "tolerance")) s->tolerance = Tolerance(*w, Join(sp, "tolerance"));
  if (const json* w = Find(v, "threads")) s->threads = static_cast<int>(Integer(*w, Join(sp, "threads"), 1, O::kMaxThreads));
  if (const json* w = Find(v, "enumerate_families")) {
    if (!w->is_boolean()) Fail(Join(sp, "enumerate_families"), *w, "must be true or false");
    s->enumerate_families = w->get<bool>();
  }
}

}  // namespace plateball::internal::problem_io
