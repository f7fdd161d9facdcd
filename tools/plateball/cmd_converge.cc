// `plateball converge PROBLEM.json`: plan the problem for a sequence of partition sizes n and
// report the table (n, time, measured error, bound) as JSON or CSV, the fitted log-log slope, and
// the log-log chart as SVG (convergence.h).
#include <cmath>
#include <memory>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include "common/command_registry.h"
#include "common/exit_codes.h"
#include "common/json_output.h"
#include "common/number_format.h"
#include "common/output_file.h"
#include "common/problem_options.h"
#include "common/progress.h"
#include "common/svg.h"
#include "plateball/convergence.h"
#include "plateball/task_adapters.h"

namespace plateball::tools {
namespace {

struct ConvergeCliOptions {
  ProblemOptions problem;
  std::vector<long long> ns;
  std::string format = "json";
  std::string out;
  std::string svg;
  bool timings = false;
};

// plan_seconds only with --timings: without it the output is a deterministic function of the input.
std::string Csv(const ConvergenceStudy& s, bool timings) {
  std::ostringstream os;
  // The JSON row's keys, nested ones joined by '.' (docs/output_contract.md).
  os << "n,segments," << (timings ? "plan_seconds," : "")
     << "measured_error,polyline_error,bounds.a_posteriori,bounds.theorem_2_6,bounds.corollary_3,max_pass_miss,"
        "status\n";
  for (const auto& r : s.rows) {
    os << r.n << "," << r.segments << ",";
    if (timings) os << FormatNumber(r.plan_seconds) << ",";
    os << FormatNumber(r.measured_error) << "," << FormatNumber(r.polyline_error) << "," << FormatNumber(r.bound) << ","
       << FormatNumber(r.theorem_2_6) << "," << FormatNumber(r.corollary_3) << "," << FormatNumber(r.max_pass_miss)
       << "," << ToString(r.status) << "\n";
  }
  return os.str();
}

// Least-squares line through (log n, log e): returns the intercept for the chart's fitted line.
double Intercept(const std::vector<double>& x, const std::vector<double>& y, double slope) {
  double sx = 0, sy = 0;
  int m = 0;
  for (std::size_t i = 0; i < x.size(); ++i)
    if (x[i] > 0 && y[i] > 0) sx += std::log(x[i]), sy += std::log(y[i]), ++m;
  return m > 0 ? (sy - slope * sx) / m : 0.0;
}

void DrawStudy(const Problem& p, const ConvergenceStudy& s, const std::string& file) {
  LogLogSeries err{"measured error ||A(T) - A_n||", {}, {}, {"#c0392b", 1.8, "", "none"}, true};
  LogLogSeries poly{"polyline error ||A(T) - Abar_n||", {}, {}, {"#7f8c8d", 1.2, "3,3", "none"}, true};
  LogLogSeries bound{"reported bound (a-posteriori)", {}, {}, {"#1f5fbf", 1.6, "7,5", "none"}, true};
  // The a-priori bounds (Theorem 2.6 and its n^-2 form, Corollary 3): the paper's guarantee.
  LogLogSeries theorem{"a-priori bound, Theorem 2.6", {}, {}, {"#8e44ad", 1.4, "10,3,2,3", "none"}, true};
  LogLogSeries corollary{"a-priori bound, Corollary 3 (~ n^-2)", {}, {}, {"#d35400", 1.4, "2,3", "none"}, true};
  for (const auto& r : s.rows) {
    if (r.status != PlanStatus::kSuccess) continue;
    err.x.push_back(r.n), err.y.push_back(r.measured_error);
    poly.x.push_back(r.n), poly.y.push_back(r.polyline_error);
    bound.x.push_back(r.n), bound.y.push_back(r.bound);
    theorem.x.push_back(r.n), theorem.y.push_back(r.theorem_2_6);
    corollary.x.push_back(r.n), corollary.y.push_back(r.corollary_3);
  }
  std::vector<LogLogSeries> series{err, poly, bound, theorem, corollary};
  // Uniform partitions: Corollary 3 is Theorem 2.6 evaluated (equal to rounding): one curve.
  bool same = theorem.y.size() == corollary.y.size();
  for (std::size_t i = 0; same && i < theorem.y.size(); ++i)
    same = std::abs(theorem.y[i] - corollary.y[i]) <= 1e-9 * std::abs(theorem.y[i]);
  if (same) {
    series.pop_back();
    series.back().label = "a-priori bound, Theorem 2.6 = Corollary 3 (~ n^-2)";
  }
  std::ostringstream title;
  title.precision(3);
  title << (p.name.empty() ? std::string("convergence") : p.name);
  if (s.error_slope) {  // a fitted line needs two successful n
    const double slope = *s.error_slope;
    std::ostringstream label;
    label.precision(3);
    label << "fit: slope " << slope;
    LogLogSeries fit{label.str(), {}, {}, {"black", 1.0, "2,4", "none"}, false};
    const double c = Intercept(err.x, err.y, slope);
    for (double n : err.x) fit.x.push_back(n), fit.y.push_back(std::exp(c) * std::pow(n, slope));
    series.push_back(fit);
    title << ": error ~ n^" << slope;
  } else {
    title << ": no slope (fewer than 2 successful n)";
  }
  WriteOutput(file, RenderLogLogChart(title.str(), "impulses per piece n", "orientation error", series));
}

int RunConverge(const ConvergeCliOptions& o) {
  CheckOutputPaths({{"--out", o.out.empty() ? "-" : o.out}, {"--svg", o.svg}}, {{"PROBLEM.json", o.problem.file()}});
  const Problem p = o.problem.Load();
  if (o.format != "json" && o.format != "csv")
    ThrowInvalidInput(CommandLineField("--format"), o.format, "must be json or csv");
  std::vector<int> ns;
  for (long long n : o.ns) ns.push_back(static_cast<int>(RequireIntegerInRange("--impulses", n, 1, 1'000'000)));
  for (int n : ns) RequirePartitionSteps("--impulses", n, p);
  ConvergenceSetup setup = ConvergenceSetupFor(p, ns, std::string(kCommandLine) + ": --impulses", o.timings);
  // A plan's cost grows like n: the progress counts impulses, so the ETA weighs the large n.
  std::vector<double> work{0.0};
  for (int n : setup.problem.ns) work.push_back(work.back() + n);
  Progress progress("plateball converge", work.back());
  setup.options.progress = [&](int done, int) { progress.Update(work[static_cast<std::size_t>(done)]); };
  const ConvergenceStudy s = RunConvergenceStudy(setup.problem, setup.options);
  if (o.format == "csv") {
    WriteOutput(o.out, Csv(s, o.timings));
  } else {
    Json doc = HeaderJson("plateball", "converge", p, o.problem.file());
    Append(doc, Json{{"status", ToString(s.status)}, {"usable", s.IsSolutionUsable()}, {"message", s.message}});
    const Path& path = setup.problem.plan.path;
    doc["path"] = Json{{"type", ToString(p.plan->path)}, {"pieces", path.PieceCount()}, {"length", path.Length()}};
    doc["partition"] = Json{{"type", ToString(p.plan->partition)}};
    Json rows = Json::array();
    for (const auto& r : s.rows) {
      Json j{{"n", r.n}, {"segments", r.segments}};
      if (o.timings) j["plan_seconds"] = r.plan_seconds;
      Append(j,
             Json{{"status", ToString(r.status)},
                  {"usable", r.status == PlanStatus::kSuccess},
                  {"message", r.message},
                  {"measured_error", r.measured_error},
                  {"polyline_error", r.polyline_error},
                  {"bounds",
                   Json{{"a_posteriori", r.bound}, {"theorem_2_6", r.theorem_2_6}, {"corollary_3", r.corollary_3}}},
                  {"max_pass_miss", r.max_pass_miss}});
      rows.push_back(std::move(j));
    }
    doc["rows"] = std::move(rows);
    auto slope_or_null = [](const std::optional<double>& v) { return v ? Json(*v) : Json(nullptr); };
    doc["error_slope"] = slope_or_null(s.error_slope);
    doc["bound_slope"] = slope_or_null(s.bound_slope);
    if (o.timings) doc["time_slope"] = slope_or_null(s.time_slope);
    doc["bound_holds"] = s.bound_holds;
    doc["failed_rows"] = s.failed_rows;
    doc["report"] = s.BriefReport();
    WriteJson(doc, o.out);
  }
  if (!o.svg.empty()) DrawStudy(p, s, o.svg);
  return s.failed_rows == 0 ? kExitSuccess : kExitNoSolution;
}

std::function<int()> SetupConverge(CLI::App& sub) {
  auto o = std::make_shared<ConvergeCliOptions>();
  o->problem.Add(sub, ProblemOptions::Seed::kNone);  // deterministic: no --seed
  sub.add_option("--impulses,--n",
                 o->ns,
                 "distinct numbers of impulses per smooth piece (partition sizes n), e.g. --impulses 16,32,64 "
                 "(default: plan.converge_n, else 16 ... 1024; a uniform partition only; --n: deprecated alias)")
      ->delimiter(',');
  sub.add_option("--format", o->format, "json (default) or csv");
  sub.add_option("--out", o->out, "write the table to this file instead of standard output (\"-\": standard output)");
  sub.add_option(
      "--svg",
      o->svg,
      "draw the log-log chart (error, bound, fitted slope) to this SVG file (\"-\": standard output, with --out FILE)");
  AddFigureSizeOption(sub);
  sub.add_flag("--timings",
               o->timings,
               "also report the wall time of every plan (plan_seconds, time_slope); without it the output is "
               "reproducible byte for byte");
  sub.footer(
      "Plans plan.path for each n and reports n, plan time, measured error ||A(T) - A_n||, the polyline's\n"
      "error, the reported bound and Theorem 2.6 / Corollary 3, with the least-squares log-log slopes\n"
      "(Corollary 3: error ~ n^-2).\n"
      "Example: plateball converge problems/circle.json --impulses 16,32,64,128 --svg circle_convergence.svg\n"
      "Exit codes: 0 ok, 2 usage, 3 invalid input, 4 some plan failed, 5 unreadable file.");
  return [o] { return RunConverge(*o); };
}

const CommandRegistrar kRegistrar{
    {"converge",
     "convergence study: plan for several n, fit the log-log slope of the error (JSON/CSV, SVG)",
     SetupConverge}};

}  // namespace
}  // namespace plateball::tools
