// Python binding: execution under errors and the Monte Carlo study (error_model.h, execution.h,
// monte_carlo.h). RunMonteCarlo releases the GIL; its progress callback checks for Ctrl-C (interrupt.h).
#include <utility>

#include "bind_common.h"
#include "interrupt.h"
#include "plateball/error_model.h"
#include "plateball/execution.h"
#include "plateball/monte_carlo.h"

namespace plateball::python {
namespace {

using Scalar1 = Eigen::Matrix<double, 1, 1>;

void BindInputs(py::module_& m) {
  py::class_<ErrorModel> errors(m, "ErrorModel", "Relative error magnitudes of an execution (error_model.h).");
  WithKeywordInit(errors)
      .def_readwrite("impulse_magnitude", &ErrorModel::impulse_magnitude)
      .def_readwrite("impulse_angle", &ErrorModel::impulse_angle)
      .def_readwrite("timing", &ErrorModel::timing)
      .def_readwrite("energy_loss", &ErrorModel::energy_loss)
      .def_readwrite("lambda_", &ErrorModel::lambda)
      .def_readwrite("observation", &ErrorModel::observation)
      .def_readwrite("pulse_duration", &ErrorModel::pulse_duration)
      .def_readwrite("pulse_causal", &ErrorModel::pulse_causal)
      .def("validate",
           &ErrorModel::Validate,
           "Empty when every magnitude is finite and in [0, its maximum] and pulse_causal is 0 or 1; else names field "
           "and value.")
      .def("__str__", [](const ErrorModel& e) { return ToString(e); });
  m.def("parse_error_model",
        &ParseErrorModel,
        py::arg("text"),
        py::arg("field") = "noise",
        "'impulse_magnitude=1e-3,timing=1e-4' -> ErrorModel (the CLI's --noise)");
  py::class_<MonteCarloScenario> scenario(m,
                                          "MonteCarloScenario",
                                          "A named error model (MonteCarloScenario(name, errors=ErrorModel(...))): one "
                                          "row of a Monte Carlo study's cells.");
  WithKeywordInit(scenario)
      .def_readwrite("name", &MonteCarloScenario::name)
      .def_readwrite("errors", &MonteCarloScenario::errors);
  // The positional form MonteCarloScenario(name, errors=ErrorModel(...)) of the README.
  scenario.def(py::init([](std::string name, const ErrorModel& errors) {
                 return MonteCarloScenario{std::move(name), errors};
               }),
               py::arg("name"),
               py::arg("errors") = ErrorModel{});
  py::class_<ExecutionOptions> execution(m,
                                         "ExecutionOptions",
                                         "How the trials execute a plan: when a pass point counts as missed, and the "
                                         "window and options of the exact re-planning (strategy feedback_exact).");
  WithKeywordInit(execution)
      .def_readwrite("miss_tolerance", &ExecutionOptions::miss_tolerance)
      .def_readwrite("exact_window", &ExecutionOptions::exact_window)
      .def_readwrite("exact", &ExecutionOptions::exact)
      .def("validate",
           &ExecutionOptions::Validate,
           "Empty when the options are valid; else a message naming the field and its value.");
  py::class_<MonteCarloProblem> problem(
      m,
      "MonteCarloProblem",
      "A plan executed under errors; strategies are words: open_loop, feedback, feedback_exact.");
  WithKeywordInit(problem)
      .def_readwrite("plan", &MonteCarloProblem::plan)
      .def_property(
          "strategies",
          [](const MonteCarloProblem& p) {
            std::vector<std::string> words;
            for (ExecutionStrategy s : p.strategies) words.push_back(ToString(s));
            return words;
          },
          [](MonteCarloProblem& p, const std::vector<std::string>& words) {
            p.strategies.clear();
            for (const std::string& w : words) p.strategies.push_back(ParseExecutionStrategy(w, "strategies"));
          })
      .def_readwrite("scenarios", &MonteCarloProblem::scenarios)
      .def_readwrite("trials", &MonteCarloProblem::trials)
      .def_readwrite("seed", &MonteCarloProblem::seed)
      .def_readwrite("sweep_n", &MonteCarloProblem::sweep_n)
      .def_readwrite("main_plan",
                     &MonteCarloProblem::main_plan,
                     "the main n's plan, planned elsewhere (e.g. plan_on_rig(...).plan): executed as it is instead "
                     "of planning plan.partition; not with sweep_n (None: plan.partition is planned)");
  py::class_<MonteCarloOptions> options(m,
                                        "MonteCarloOptions",
                                        "Options of montecarlo(): the plan options, the execution, the trials of the "
                                        "sweeps, the threads and whether every trial's record is kept.");
  WithKeywordInit(options)
      .def_readwrite("plan", &MonteCarloOptions::plan)
      .def_readwrite("execution", &MonteCarloOptions::execution)
      .def_readwrite("threads", &MonteCarloOptions::threads)
      .def_readwrite("sweep_trials", &MonteCarloOptions::sweep_trials)
      .def_readwrite("keep_trials", &MonteCarloOptions::keep_trials)
      .def("validate",
           &MonteCarloOptions::Validate,
           "Empty when the options are valid; else a message naming the field and its value.");
}

void BindResults(py::module_& m) {
  py::class_<Distribution>(m,
                           "Distribution",
                           "Order statistics of one quantity over the completed trials of a cell (median and 95th "
                           "percentile by linear interpolation between order statistics, Hyndman-Fan type 7).")
      .def_readonly("median", &Distribution::median)
      .def_readonly("p95", &Distribution::p95)
      .def_readonly("max", &Distribution::max)
      .def_readonly("mean", &Distribution::mean);
  py::class_<MonteCarloCell>(
      m,
      "MonteCarloCell",
      "The trials of one (n, scenario, strategy): the distributions of the final errors over the completed trials; a "
      "cell where no trial completed has None (\"no trial completed\", never zeros).")
      .def_readonly("n", &MonteCarloCell::n)
      .def_readonly("scenario", &MonteCarloCell::scenario)
      .def_property_readonly("strategy", [](const MonteCarloCell& c) { return ToString(c.strategy); })
      .def_readonly("trials", &MonteCarloCell::trials)
      .def_readonly("completed", &MonteCarloCell::completed)
      .def_readonly("position_error", &MonteCarloCell::position_error)
      .def_readonly("orientation_error", &MonteCarloCell::orientation_error)
      .def_readonly("max_pass_miss", &MonteCarloCell::max_pass_miss)
      .def_readonly("missed_pass_points", &MonteCarloCell::missed_pass_points)
      .def_readonly("total_time", &MonteCarloCell::total_time);
  py::class_<SweepSeries>(
      m,
      "SweepSeries",
      "Median final errors of one (scenario, strategy) against n, with the plan's own error. An n whose cell has no "
      "completed trial is missing: its medians are None and the fits leave it out.")
      .def_readonly("scenario", &SweepSeries::scenario)
      .def_property_readonly("strategy", [](const SweepSeries& s) { return ToString(s.strategy); })
      .def_readonly("n", &SweepSeries::n)
      .def_readonly("median_orientation_error", &SweepSeries::median_orientation_error)
      .def_readonly("median_position_error", &SweepSeries::median_position_error)
      .def_readonly("plan_orientation_error", &SweepSeries::plan_orientation_error)
      .def_readonly("slope", &SweepSeries::slope)
      .def_readonly("local_slopes", &SweepSeries::local_slopes)
      .def_readonly("plan_slope", &SweepSeries::plan_slope);
  py::class_<NominalInfo>(m, "NominalInfo", "The nominal plan of one n.")
      .def_readonly("n", &NominalInfo::n)
      .def_property_readonly("status", [](const NominalInfo& i) { return ToString(i.status); })
      .def_readonly("message", &NominalInfo::message)
      .def_readonly("orientation_error", &NominalInfo::orientation_error)
      .def_readonly("measured_error", &NominalInfo::measured_error)
      .def_readonly("total_time", &NominalInfo::total_time);
}

void BindSummary(py::module_& m) {
  py::class_<MonteCarloSummary> summary(
      m,
      "MonteCarloSummary",
      "The result of montecarlo(): one cell per (n, scenario, strategy) with its distributions, the sweeps against n "
      "and the nominal plans; status \"not run\" until run.");
  AddSummaryShape(summary);
  summary.def_readonly("nominal", &MonteCarloSummary::nominal)
      .def_readonly("cells", &MonteCarloSummary::cells)
      .def_readonly("sweeps", &MonteCarloSummary::sweeps)
      .def_readonly("failed_trials", &MonteCarloSummary::failed_trials)
      .def_property_readonly(
          "trial_status",
          [](const MonteCarloSummary& s) {
            std::vector<std::string> words;
            for (const TrialRecord& r : s.records) words.push_back(ToString(r.status));
            return words;
          },
          "per trial (keep_trials): the execution status word")
      .def(
          "trials",
          [](const MonteCarloSummary& s, const std::string& column) {
            static const std::map<std::string, double TrialRecord::*> kColumns{
                {"position_error", &TrialRecord::position_error},
                {"orientation_error", &TrialRecord::orientation_error},
                {"max_pass_miss", &TrialRecord::max_pass_miss},
                {"total_time", &TrialRecord::total_time}};
            if (column == "n") return Stack<1>(s.records, [](const TrialRecord& r) { return Scalar1(r.n); });
            if (column == "scenario")
              return Stack<1>(s.records, [](const TrialRecord& r) { return Scalar1(r.scenario); });
            if (column == "missed_pass_points")
              return Stack<1>(s.records, [](const TrialRecord& r) { return Scalar1(r.missed_pass_points); });
            const auto it = kColumns.find(column);
            if (it == kColumns.end())
              throw std::invalid_argument("column: value '" + column + "': unknown trial column");
            return Stack<1>(s.records, [&](const TrialRecord& r) { return Scalar1(r.*(it->second)); });
          },
          py::arg("column"),
          "One column of the trial records as an array (n, scenario, position_error, ...).");
  m.def(
      "_montecarlo",
      [](const MonteCarloProblem& problem, MonteCarloOptions options) {
        const Interruptible interrupt;  // Ctrl-C abandons the run (KeyboardInterrupt)
        options.progress = [interrupt](long long, long long) { interrupt.Check(); };
        return interrupt.Run([&] { return RunMonteCarlo(problem, options); });
      },
      py::arg("problem"),
      py::arg("options"),
      py::call_guard<py::gil_scoped_release>());
}

}  // namespace

void BindMonteCarlo(py::module_& m) {
  BindInputs(m);
  BindResults(m);
  BindSummary(m);
}

}  // namespace plateball::python
