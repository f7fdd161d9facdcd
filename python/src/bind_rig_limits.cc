// The rig's limits (rig_limits.h): plate shapes, the limits, what the solver did and the
// independent checks (CheckRigLimits, CheckPlanRigLimits).
#include "bind_common.h"
#include "field_binding.h"
#include "plateball/exact_arrival.h"
#include "plateball/plan_rig_check.h"
#include "plateball/rig_limits.h"
#include "plateball/rig_planner.h"
#include "plateball/rig_reference.h"

namespace plateball::python {

namespace {

ArrivalObjective ObjectiveFromWord(const std::string& word) {
  const auto o = ArrivalObjectiveFromString(word);
  if (!o)
    throw std::invalid_argument("objective: value " + word +
                                ": must be \"deviation\", \"time\", \"impulse\" or \"fewest\"");
  return *o;
}

void BindShapes(py::module_& m) {
  py::class_<DiskShape> disk(m, "DiskShape", "A disk of the plate, the points within radius of center (ball radii).");
  WithKeywordInit(disk)
      .def_readwrite("center", &DiskShape::center, "the disk's center")
      .def_readwrite("radius", &DiskShape::radius, "its radius (> 0)");
  py::class_<PolygonShape> polygon(m, "PolygonShape", "A simple polygon (>= 3 vertices, either orientation).");
  WithKeywordInit(polygon).def_readwrite("vertices", &PolygonShape::vertices, "the vertices, not repeated at the end");
  m.def(
      "signed_distance_inside",
      [](const PlateShape& s, const Eigen::Vector2d& x) { return SignedDistanceInside(s, x); },
      py::arg("shape"),
      py::arg("x"),
      "Signed distance of x to the shape's boundary, positive inside.");
}

void BindLimits(py::module_& m) {
  py::class_<RigLimits> limits(
      m, "RigLimits", "The limits of a physical rig that exact arrival honours (rig_limits.h).");
  DefFieldAttributes(WithKeywordInit(limits))
      .def_property_readonly("empty", &RigLimits::Empty, "True when no limit is set")
      .def("validate", &RigLimits::Validate, "Empty when valid; else a message naming the field.");
  py::class_<RigLimitsReport>(m, "RigLimitsReport", "What the rig's limits did in an exact arrival.")
      .def_readonly("constrained",
                    &RigLimitsReport::constrained,
                    "True when the limits cut the free optimum and the constrained solve ran")
      .def_readonly("active", &RigLimitsReport::active, "limits active at the result")
      .def_readonly("blocking",
                    &RigLimitsReport::blocking,
                    "the limits active at the closest feasible arrival (status limits_not_met)")
      .def_readonly("evaluations",
                    &RigLimitsReport::evaluations,
                    "evaluations of the constrained solve(s) (Gauss-Newton SQP steps and SLSQP)");
  py::class_<RigCheck>(m, "RigCheck", "The independent replay check of a result against the limits.")
      .def_readonly("passed", &RigCheck::passed, "every checked quantity within its limit and tolerance")
      .def_readonly("samples", &RigCheck::samples, "contact points checked")
      .def_readonly("margins", &RigCheck::margins, "the smallest margin (bound - value) of each limit")
      .def_readonly("violations", &RigCheck::violations, "one line per limit exceeded");
}

void BindReference(py::module_& m) {
  py::class_<ReferenceChoice>(
      m, "ReferenceChoice", "The isoparallel solution steered along on a rig (rig_reference.h).")
      .def_readonly("index", &ReferenceChoice::index, "the solution steered along")
      .def_readonly(
          "shortest_breaks", &ReferenceChoice::shortest_breaks, "the limits the shortest solution's path breaks")
      .def_readonly("chosen_breaks",
                    &ReferenceChoice::chosen_breaks,
                    "the limits the chosen one breaks (empty when it meets them)");
  m.def("path_limit_breaks",
        &PathLimitBreaks,
        py::arg("path"),
        py::arg("limits"),
        py::arg("x0"),
        py::arg("samples_per_piece") = 2000,
        "The plate, obstacle and stroke limits the path breaks at its samples.");
  m.def("choose_isoparallel_reference",
        &ChooseIsoparallelReference,
        py::arg("summary"),
        py::arg("limits"),
        py::arg("x0"),
        "The shortest isoparallel solution whose path meets the plate, obstacle and stroke limits, else the shortest.");
}

void BindRigPlanner(py::module_& m) {
  py::class_<RigCheckTolerances> tolerances(
      m,
      "RigCheckTolerances",
      "Tolerances of the independent check against a rig's limits (rig_limits.h): positions and impulses to these, "
      "the grid exactly.");
  DefFieldAttributes(WithKeywordInit(tolerances));
  py::class_<RigPlanOptions> options(
      m,
      "RigPlanOptions",
      "Options of plan_on_rig (rig_planner.h): the refinement and the final check's samples and tolerances.");
  DefFieldAttributes(WithKeywordInit(options))
      .def("validate", &RigPlanOptions::Validate, "Empty when valid; else a message naming the field.");
  py::class_<RigPlanSummary> summary(
      m, "RigPlanSummary", "The result of plan_on_rig(): the plan, its independent check and what the limits did.");
  AddSummaryShape(summary);
  summary.def_readonly("plan", &RigPlanSummary::plan, "the plan of the final partition (PlanSummary)")
      .def_readonly("check", &RigPlanSummary::check, "the independent check of the plan (RigCheck)")
      .def_readonly("segments_initial", &RigPlanSummary::segments_initial, "partition segments asked for")
      .def_readonly("points_added", &RigPlanSummary::points_added, "partition points the refinement added")
      .def_readonly("points_slid", &RigPlanSummary::points_slid, "partition points slid onto the tick grid")
      .def_readonly("points_removed",
                    &RigPlanSummary::points_removed,
                    "partition points removed to merge flights shorter than min_interval (or that the tick grid "
                    "could not place) with a neighbour")
      .def_readonly("rounds", &RigPlanSummary::rounds, "refinement rounds run")
      .def_readonly("active", &RigPlanSummary::active, "the limits that shaped the plan (refined against, or tick)")
      .def_readonly("blocking", &RigPlanSummary::blocking, "the limits that cannot be met");
  m.def("plan_on_rig",
        &PlanImpulsesOnRig,
        py::arg("problem"),
        py::arg("limits"),
        py::arg("physical") = py::none(),
        py::arg("options") = PlanOptions{},
        py::arg("rig_options") = RigPlanOptions{},
        py::call_guard<py::gil_scoped_release>(),
        "Plans the path under a rig's limits: refines the partition where a flight leaves the plate or the stroke "
        "box or enters an obstacle, slides the partition points onto the tick grid, and names the limits it "
        "cannot meet; the final plan is checked by check_plan_rig_limits.");
}

}  // namespace

void BindRigLimits(py::module_& m) {
  BindShapes(m);
  BindLimits(m);
  BindReference(m);
  BindRigPlanner(m);
  m.def(
      "check_plan_rig_limits",
      [](const PlanProblem& p,
         const PlanSummary& plan,
         const RigLimits& limits,
         const std::optional<PhysicalParameters>& physical,
         int samples_per_arc) { return CheckPlanRigLimits(p, plan, limits, physical, {}, samples_per_arc); },
      py::arg("problem"),
      py::arg("plan"),
      py::arg("limits"),
      py::arg("physical") = py::none(),
      py::arg("samples_per_arc") = 64,
      py::call_guard<py::gil_scoped_release>(),
      "Checks a path-following plan against a rig's limits: replays every flight with FreeMotion and checks "
      "every sampled contact point, every actuation (the impulses at one partition point together), interval "
      "and grid time; the impulse bound only with `physical`.");
}

void BindExactArrivalLimits(py::class_<ExactArrivalProblem>& problem,
                            py::class_<ExactArrivalSummary>& summary,
                            py::module_& m) {
  problem.def_readwrite("limits", &ExactArrivalProblem::limits, "the rig's limits (RigLimits)")
      .def_property(
          "objective",
          [](const ExactArrivalProblem& p) { return ToString(p.objective); },
          [](ExactArrivalProblem& p, const std::string& w) { p.objective = ObjectiveFromWord(w); },
          "what is minimised under the limits (deviation, time or impulse)")
      .def_readwrite("physical", &ExactArrivalProblem::physical, "the masses behind the impulse bounds, or None");
  summary.def_readonly("limits", &ExactArrivalSummary::limits, "what the rig's limits did (RigLimitsReport)");
  m.def(
      "check_rig_limits",
      [](const ExactArrivalProblem& p, const ExactArrivalSummary& s, int samples_per_arc) {
        return CheckRigLimits(p, s, {}, samples_per_arc);
      },
      py::arg("problem"),
      py::arg("summary"),
      py::arg("samples_per_arc") = 64,
      py::call_guard<py::gil_scoped_release>(),
      "Replays the result with FreeMotion and checks every sampled contact point, impulse, interval and grid time.");
}

}  // namespace plateball::python
