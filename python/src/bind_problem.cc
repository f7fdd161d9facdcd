// Python binding: problem files (problem.h, problem_io.h) and the task adapters (task_adapters.h),
// so that Python runs exactly what the tools run for a file.
#include "bind_common.h"
#include "field_binding.h"
#include "plateball/limits.h"
#include "plateball/problem.h"
#include "plateball/problem_io.h"
#include "plateball/task_adapters.h"

namespace plateball::python {
namespace {

void BindTasks(py::module_& m) {
  py::class_<SimulateTask> simulate(m, "SimulateTask", "`plateball simulate`: sample the free motion on [0, t_end].");
  DefFieldAttributes(WithKeywordInit(simulate));
  py::class_<ReachTask> reach(
      m, "ReachTask", "`plateball join` / `plateball reach`: reach target points from the initial state.");
  WithKeywordInit(reach)
      .def_readwrite("targets", &ReachTask::targets)
      .def_readwrite("horizon_periods", &ReachTask::horizon_periods);
  py::class_<PathSpec>(m, "PathSpec", "A path of a problem file (JSON \"path\"); PathSpec.to_path() builds it.")
      .def_property_readonly("type", [](const PathSpec& s) { return ToString(s); })
      .def(
          "to_path",
          [](const PathSpec& s) { return PathFromSpec(s); },
          "The Path this specification describes (what the solvers follow).");
  py::class_<PlanTask> plan(
      m, "PlanTask", "`plateball plan` / `plateball converge`: follow a planned path with impulses.");
  WithKeywordInit(plan)
      .def_readwrite("path", &PlanTask::path)
      .def_readwrite("partition", &PlanTask::partition)
      .def_readwrite("energy_changes", &PlanTask::energy_changes)
      .def_readwrite("converge_n", &PlanTask::converge_n);
  py::class_<IsoparallelTask> iso(
      m,
      "IsoparallelTask",
      "The isoparallel problem (section 2.2): shortest path from (start, A_start) to (goal, A_goal).");
  WithKeywordInit(iso)
      .def_readwrite("start", &IsoparallelTask::start)
      .def_readwrite("goal", &IsoparallelTask::goal)
      .def_readwrite("start_orientation", &IsoparallelTask::start_orientation)
      .def_readwrite("goal_orientation", &IsoparallelTask::goal_orientation)
      .def_readwrite("impulses", &IsoparallelTask::impulses)
      .def_readwrite("solver", &IsoparallelTask::solver);
  py::class_<SteerTask> steer(
      m,
      "SteerTask",
      "`plateball steer` / `isoparallel_solve --exact`: exact arrival at (goal, goal_orientation) with `impulses` "
      "impulses along a reference: the plan section's path when the file has one, else the shortest isoparallel path.");
  WithKeywordInit(steer)
      .def_readwrite("goal", &SteerTask::goal)
      .def_readwrite("goal_orientation", &SteerTask::goal_orientation)
      .def_readwrite("impulses", &SteerTask::impulses)
      .def_property(
          "objective",
          [](const SteerTask& t) { return ToString(t.objective); },
          [](SteerTask& t, const std::string& w) {
            const auto o = ArrivalObjectiveFromString(w);
            if (!o)
              throw std::invalid_argument("steer.objective: value " + w +
                                          ": must be \"deviation\", \"time\", \"impulse\" or \"fewest\"");
            t.objective = *o;
          },
          "what the exact arrival minimises under the rig's limits (deviation, time or impulse)");
  py::class_<ExpectedValue>(
      m,
      "ExpectedValue",
      "Golden values a problem file may carry (\"expected\"): name -> value, with a tolerance each.")
      .def_readonly("value", &ExpectedValue::value)
      .def_readonly("tolerance", &ExpectedValue::tolerance);
}

void BindProblemValue(py::module_& m) {
  py::class_<Problem, StartState> problem(m, "Problem", "A problem file's content (README: \"Problem files\").");
  WithKeywordInit(problem)
      .def_readwrite("source", &Problem::source)
      .def_readwrite("name", &Problem::name)
      .def_readwrite("description", &Problem::description)
      .def_readwrite("physical", &Problem::physical)
      .def_readwrite("initial_angles", &Problem::initial, "an alias of `initial`, the former name of the start angles")
      .def_readwrite("seed", &Problem::seed)
      .def_readwrite("integration", &Problem::integration)
      .def_readwrite("simulate", &Problem::simulate)
      .def_readwrite("reach", &Problem::reach)
      .def_readwrite("plan", &Problem::plan)
      .def_readwrite("isoparallel", &Problem::isoparallel)
      .def_readwrite("steer", &Problem::steer)
      .def_readwrite("rig", &Problem::rig, "the rig's limits (RigLimits), honoured by steer")
      .def_readwrite("expected", &Problem::expected)
      .def("__repr__",
           [](const Problem& p) { return "<plateball.Problem " + (p.name.empty() ? p.source : p.name) + ">"; });
  // plateball.MAX_...: the sizes of plateball/limits.h, the same numbers as the reader and the tools.
  m.attr("MAX_PROBLEM_FILE_BYTES") = limits::kMaxProblemFileBytes;
  m.attr("MAX_RESULT_FILE_BYTES") = limits::kMaxResultFileBytes;
  m.attr("MAX_JSON_DEPTH") = limits::kMaxJsonDepth;
  m.attr("MAX_SAMPLES") = limits::kMaxSamples;
  m.attr("MAX_POINTS") = limits::kMaxPoints;
  m.attr("MAX_PARTITION_STEPS") = limits::kMaxPartitionSteps;
  m.attr("MAX_LIST_LENGTH") = limits::kMaxListLength;
  m.attr("MAX_HORIZON_PERIODS") = limits::kMaxHorizonPeriods;
  m.attr("MAX_PIECE_DEPTH") = limits::kMaxPieceDepth;
  m.def("read_problem_file",
        &ReadProblemFile,
        py::arg("path"),
        "Read a problem file (ValueError naming the field and value; ProblemFileReadError when unreadable).");
  m.def("parse_problem",
        &ParseProblem,
        py::arg("json_text"),
        py::arg("source_name") = "<memory>",
        "A problem from JSON text, with the same checks and messages as the tools' reader (at most "
        "MAX_PROBLEM_FILE_BYTES).");
  m.def("write_problem_json", &WriteProblemJson, py::arg("problem"), "The canonical JSON form of a problem.");
  m.def("parse_orientation",
        &ParseOrientation,
        py::arg("json_text"),
        py::arg("field") = "orientation",
        py::arg("source_name") = "<python>",
        "An orientation from its JSON text in any of the problem file's three forms (3x3).");
}

// One setup per task: problem and options, ready for the solver call (what the tools run).
template <typename Setup>
void BindSetup(py::module_& m, const char* name) {
  py::class_<Setup>(
      m, name, "A solver's (problem, options) made from a problem file by a task adapter; unpacks as a pair.")
      .def_readwrite("problem", &Setup::problem)
      .def_readwrite("options", &Setup::options)
      .def("__iter__", [](const Setup& s) { return py::iter(py::make_tuple(s.problem, s.options)); });
}

void BindAdapters(py::module_& m) {
  BindSetup<JoinSetup>(m, "JoinSetup");
  BindSetup<ReachSetup>(m, "ReachSetup");
  BindSetup<PlanSetup>(m, "PlanSetup");
  BindSetup<ConvergenceSetup>(m, "ConvergenceSetup");
  BindSetup<IsoparallelSetup>(m, "IsoparallelSetup");
  BindSetup<IsoparallelPlanSetup>(m, "IsoparallelPlanSetup");
  BindSetup<ExactArrivalSetup>(m, "ExactArrivalSetup");
  BindSetup<FewestImpulsesSetup>(m, "FewestImpulsesSetup");
  m.def("path_from_spec",
        &PathFromSpec,
        py::arg("spec"),
        py::arg("field") = "path",
        "The Path of a problem file's path section (`field` names it in errors).");
  m.def("free_motion_for",
        &FreeMotionFor,
        py::arg("problem"),
        py::call_guard<py::gil_scoped_release>(),
        "The FreeMotion of a problem file's ball and initial state (what `plateball simulate` integrates).");
  m.def("join_setup_for",
        &JoinSetupFor,
        py::arg("problem"),
        py::arg("target"),
        "The (problem, options) of a join from the file's initial state to `target`.");
  m.def("reach_setup_for",
        &ReachSetupFor,
        py::arg("problem"),
        py::arg("target"),
        "The (problem, options) of `plateball reach` for a problem file and one target.");
  m.def("plan_setup_for",
        &PlanSetupFor,
        py::arg("problem"),
        py::arg("n") = 0,
        py::arg("n_field") = "n",
        "The (problem, options) of `plateball plan` for a problem file; n > 0 replaces a uniform partition's n.");
  m.def("convergence_setup_for",
        &ConvergenceSetupFor,
        py::arg("problem"),
        py::arg("ns") = std::vector<int>{},
        py::arg("ns_field") = "ns",
        py::arg("timings") = false,
        "The (problem, options) of `plateball converge` for a problem file, for the partition sizes ns (empty: the "
        "file's).");
  m.def("isoparallel_setup_for",
        &IsoparallelSetupFor,
        py::arg("problem"),
        "The (problem, options) of `isoparallel_solve` for a problem file.");
  m.def("isoparallel_plan_setup_for",
        &IsoparallelPlanSetupFor,
        py::arg("problem"),
        py::arg("solution"),
        py::arg("impulses") = 0,
        "The (problem, options) that follow an isoparallel solution with the file's impulses (Figure 7).");
  m.def("exact_arrival_setup_for",
        py::overload_cast<const Problem&, int, const std::string&>(&ExactArrivalSetupFor),
        py::arg("problem"),
        py::arg("impulses") = 0,
        py::arg("n_field") = "impulses",
        "The (problem, options) of `plateball steer` for a problem file.");
  m.def("exact_arrival_setup_for",
        py::overload_cast<const Problem&, const IsoparallelSolution&, int, const std::string&>(&ExactArrivalSetupFor),
        py::arg("problem"),
        py::arg("solution"),
        py::arg("impulses") = 0,
        py::arg("n_field") = "impulses",
        "The (problem, options) of `plateball steer` for a problem file.");
  m.def("fewest_impulses_setup_for",
        &FewestImpulsesSetupFor,
        py::arg("problem"),
        "What `plateball steer` runs on a file whose steer section asks for the fewest impulses.");
}

}  // namespace

void BindProblem(py::module_& m) {
  BindTasks(m);
  BindProblemValue(m);
  BindAdapters(m);
}

}  // namespace plateball::python
