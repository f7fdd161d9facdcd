#include "common/problem_options.h"

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <sstream>
#include <stdexcept>
#include <thread>

#include "common/command_line.h"
#include "common/input_file.h"
#include "common/limits.h"
#include "common/number_format.h"
#include "plateball/problem_io.h"
#include "plateball/task_adapters.h"

namespace plateball::tools {
namespace {

[[noreturn]] void Fail(const std::string& option, const std::string& value, const std::string& what) {
  ThrowInvalidInput(CommandLineField(option), value, what);
}

std::string Quote(const std::string& s) { return "\"" + (s.size() > 80 ? s.substr(0, 80) + "..." : s) + "\""; }

// A whole string as one finite double, or nothing.
bool ParseDouble(std::string text, double* out) {
  const auto b = text.find_first_not_of(" \t");
  const auto e = text.find_last_not_of(" \t");
  if (b == std::string::npos) return false;
  text = text.substr(b, e - b + 1);
  char* end = nullptr;
  errno = 0;
  const double v = std::strtod(text.c_str(), &end);
  if (end != text.c_str() + text.size() || errno == ERANGE || !std::isfinite(v)) return false;
  *out = v;
  return true;
}

}  // namespace

double RequireFiniteOption(const std::string& option, double v) {
  if (!std::isfinite(v)) Fail(option, FormatNumber(v), "must be a finite number");
  return v;
}
double RequirePositiveOption(const std::string& option, double v) {
  if (!(std::isfinite(v) && v > 0)) Fail(option, FormatNumber(v), "must be a finite number > 0");
  return v;
}
long long RequireIntegerInRange(const std::string& option, long long v, long long lo, long long hi) {
  if (v < lo) Fail(option, std::to_string(v), "must be >= " + std::to_string(lo));
  if (v > hi) Fail(option, std::to_string(v), "must be <= " + std::to_string(hi));
  return v;
}

int ThreadsOption(long long requested) {
  if (requested == 0) return static_cast<int>(std::min(256u, std::max(1u, std::thread::hardware_concurrency())));
  return static_cast<int>(RequireIntegerInRange("--threads", requested, 1, 256));
}

void RequirePartitionSteps(const std::string& option, long long n, const Problem& p) {
  if (!p.plan) return;
  const long long pieces = static_cast<long long>(PathFromSpec(p.plan->path, p.source + ": plan.path").PieceCount());
  if (n * pieces > kMaxPartitionSteps)
    Fail(option,
         std::to_string(n),
         "must be <= " + std::to_string(kMaxPartitionSteps / pieces) + " (n x " + std::to_string(pieces) +
             (pieces == 1 ? " smooth piece" : " smooth pieces") + " = " + std::to_string(n * pieces) +
             " impulses; at most " + std::to_string(kMaxPartitionSteps) + ")");
}

void RequireCoordinatesOption(const std::string& option, const std::vector<Eigen::Vector2d>& points) {
  for (std::size_t i = 0; i < points.size(); ++i)
    if (!(points[i].cwiseAbs().maxCoeff() <= kMaxCoordinate))
      Fail(option + "[" + std::to_string(i) + "]",
           FormatNumber(points[i].x()) + "," + FormatNumber(points[i].y()),
           "|coordinate| must be <= " + FormatNumber(kMaxCoordinate) + " (precision limit)");
}

Eigen::Vector2d ParsePointOption(const std::string& option, const std::string& text) {
  const auto comma = text.find(',');
  Eigen::Vector2d p;
  if (comma == std::string::npos || !ParseDouble(text.substr(0, comma), &p.x()) ||
      !ParseDouble(text.substr(comma + 1), &p.y()))
    Fail(option, Quote(text), "must be two finite numbers X,Y");
  return p;
}

std::vector<Eigen::Vector2d> ParsePointsOption(const std::string& option,
                                               const std::string& text,
                                               std::size_t min_points) {
  // Points are separated by ';' or by white space; a point is "X,Y" without spaces.
  std::vector<Eigen::Vector2d> points;
  std::string item;
  auto flush = [&] {
    if (item.empty()) return;
    if (points.size() >= 1'000'000) Fail(option, "(more than 1e6 points)", "too many points");
    points.push_back(ParsePointOption(option + "[" + std::to_string(points.size()) + "]", item));
    item.clear();
  };
  for (const char c : text) {
    if (c == ';' || c == ' ' || c == '\t' || c == '\n')
      flush();
    else
      item += c;
  }
  flush();
  if (points.size() < min_points)
    Fail(option, Quote(text), "must give at least " + std::to_string(min_points) + " points X1,Y1;X2,Y2;...");
  return points;
}

void ProblemOptions::Add(CLI::App& app, Seed seed) {
  app.add_option("problem",
                 file_,
                 "problem file (JSON, see README \"Problem files\"; \"-\": standard input); options below override it");
  lambda_opt_ = app.add_option("--lambda", lambda_, "ball parameter lambda = (alpha+beta)/(1+beta) > 0");
  theta_opt_ = app.add_option("--theta", theta_, "initial theta (rad)");
  phi_opt_ = app.add_option("--phi", phi_, "initial phi (rad)");
  psi_opt_ = app.add_option("--psi", psi_, "initial psi (rad)");
  mu_opt_ = app.add_option("--mu", mu_, "energy mu > 0 (the period is 2 pi/sqrt(mu))");
  x0_opt_ = app.add_option("--x0", x0_, "initial contact point X,Y");
  orientation_opt_ =
      app.add_option("--orientation",
                     orientation_,
                     "initial orientation as JSON: {\"quaternion\": [w,x,y,z]}, {\"matrix\": [[..],[..],[..]]} "
                     "or {\"axis_angle\": {\"axis\": [x,y,z], \"angle\": a}}");
  atol_opt_ = app.add_option("--atol", atol_, "absolute tolerance of the integration, in (0, 1)");
  rtol_opt_ = app.add_option("--rtol", rtol_, "relative tolerance of the integration, in (0, 1)");
  max_steps_opt_ = app.add_option("--max-steps", max_steps_, "step limit of one integration (>= 1)");
  if (seed == Seed::kAccepted)
    seed_opt_ =
        app.add_option("--seed", seed_, "seed of randomised searches, 0 ... 2^64 - 1")->type_name(kSeedTypeName);
  fields_ = {{"ball.lambda", lambda_opt_},
             {"ball", lambda_opt_},
             {"lambda", lambda_opt_},
             {"initial.theta", theta_opt_},
             {"initial.phi", phi_opt_},
             {"initial.psi", psi_opt_},
             {"initial.mu", mu_opt_},
             {"initial.x0", x0_opt_},
             {"initial.orientation", orientation_opt_},
             {"integration.absolute_tolerance", atol_opt_},
             {"integration.relative_tolerance", rtol_opt_},
             {"integration.max_steps", max_steps_opt_},
             {"seed", seed_opt_}};
}

void ProblemOptions::AddIsoparallel(CLI::App& app) {
  auto add = [&](const std::string& name, auto& value, const std::string& field, const std::string& help) {
    CLI::Option* o = app.add_option(name, value, help);
    fields_.emplace_back(field, o);
    return o;
  };
  add("--start", start_, "isoparallel.start", "start point X,Y (overrides isoparallel.start)");
  add("--goal", goal_, "isoparallel.goal", "goal point X,Y (overrides isoparallel.goal)");
  add("--start-orientation",
      start_orientation_,
      "isoparallel.start_orientation",
      "start orientation as JSON (as --orientation; overrides isoparallel.start_orientation)");
  add("--goal-orientation",
      goal_orientation_,
      "isoparallel.goal_orientation",
      "goal orientation as JSON (as --orientation; overrides isoparallel.goal_orientation)");
  add("--starts",
      starts_,
      "isoparallel.solver.starts",
      "multi-start count, 1 ... 1e4 (overrides isoparallel.solver.starts)");
  add("--threads",
      threads_,
      "isoparallel.solver.threads",
      "solver threads, 1 ... 256 (overrides isoparallel.solver.threads)");
}

void ProblemOptions::SetDefault(std::string json_text, std::string source_name) {
  default_text_ = std::move(json_text);
  default_source_ = std::move(source_name);
}

namespace {

bool Given(const CLI::Option* o) { return o != nullptr && o->count() > 0; }

// A library or reader message "[SOURCE: ]FIELD[INDEX]: value ..." about a field an option gave,
// renamed "command line: OPTION[INDEX]: value ...".
std::string RenameField(const std::string& message,
                        const std::string& source,
                        const std::vector<std::pair<std::string, CLI::Option*>>& fields) {
  std::string rest = message;
  if (rest.compare(0, source.size() + 2, source + ": ") == 0) rest = rest.substr(source.size() + 2);
  const auto value = rest.find(": value ");
  if (value == std::string::npos) return message;
  const std::string field = rest.substr(0, value);
  for (const auto& [name, option] : fields) {
    if (!Given(option) || field.compare(0, name.size(), name) != 0) continue;
    const std::string tail = field.substr(name.size());  // "", "[0]" or ".matrix"
    if (!tail.empty() && tail[0] != '[' && tail[0] != '.') continue;
    return std::string(kCommandLine) + ": " + option->get_name() + tail + rest.substr(value);
  }
  return message;
}

}  // namespace

void ProblemOptions::ApplyIsoparallel(Problem* p) const {
  auto given = [&](const std::string& field) {
    for (const auto& [name, option] : fields_)
      if (name == field) return Given(option);
    return false;
  };
  const bool any = given("isoparallel.start") || given("isoparallel.goal") || given("isoparallel.start_orientation") ||
                   given("isoparallel.goal_orientation") || given("isoparallel.solver.starts") ||
                   given("isoparallel.solver.threads");
  if (!any) return;
  if (!p->isoparallel)
    ThrowInvalidInput(
        p->source + ": isoparallel",
        "(missing)",
        "the options --start, --goal, ... override the problem's isoparallel section, which it does not have");
  IsoparallelTask& t = *p->isoparallel;
  if (given("isoparallel.start")) t.start = ParsePointOption("--start", start_);
  if (given("isoparallel.goal")) t.goal = ParsePointOption("--goal", goal_);
  if (given("isoparallel.start_orientation"))
    t.start_orientation = ParseOrientation(start_orientation_, "--start-orientation", kCommandLine);
  if (given("isoparallel.goal_orientation"))
    t.goal_orientation = ParseOrientation(goal_orientation_, "--goal-orientation", kCommandLine);
  if (given("isoparallel.solver.starts"))
    t.solver.starts = static_cast<int>(RequireIntegerInRange("--starts", starts_, 1, 10'000));
  if (given("isoparallel.solver.threads"))
    t.solver.threads = static_cast<int>(RequireIntegerInRange("--threads", threads_, 1, 256));
}

Problem ProblemOptions::Load() const {
  Problem p;
  if (!file_.empty())
    p = ReadProblemInput(file_);
  else if (!default_text_.empty())
    p = ParseProblem(default_text_, default_source_), p.source = default_source_;
  else
    p.source = "(built-in defaults)";
  bool overridden = false;
  for (const auto& field : fields_) overridden = overridden || Given(field.second);
  try {
    if (Given(lambda_opt_))
      p.model = BallModel::FromLambda(RequirePositiveOption("--lambda", lambda_)), p.physical.reset();
    if (Given(theta_opt_)) p.initial.theta = RequireFiniteOption("--theta", theta_);
    if (Given(phi_opt_)) p.initial.phi = RequireFiniteOption("--phi", phi_);
    if (Given(psi_opt_)) p.initial.psi = RequireFiniteOption("--psi", psi_);
    if (Given(mu_opt_)) p.mu = RequirePositiveOption("--mu", mu_);
    if (Given(x0_opt_)) p.x0 = ParsePointOption("--x0", x0_);
    if (Given(orientation_opt_)) p.A0 = ParseOrientation(orientation_, "--orientation", kCommandLine);
    if (Given(atol_opt_)) {
      if (!(std::isfinite(atol_) && atol_ > 0 && atol_ < 1)) Fail("--atol", FormatNumber(atol_), "must be in (0, 1)");
      p.integration.absolute_tolerance = atol_;
    }
    if (Given(rtol_opt_)) {
      if (!(std::isfinite(rtol_) && rtol_ > 0 && rtol_ < 1)) Fail("--rtol", FormatNumber(rtol_), "must be in (0, 1)");
      p.integration.relative_tolerance = rtol_;
    }
    if (Given(max_steps_opt_))
      p.integration.max_steps =
          static_cast<long>(RequireIntegerInRange("--max-steps", max_steps_, 1, 1'000'000'000'000LL));
    if (Given(seed_opt_)) p.seed = ParseSeedOption("--seed", seed_);
    ApplyIsoparallel(&p);
    if (overridden) {
      // Validate the combination exactly as a file is validated (e.g. both tolerances below
      // double precision), then keep the source name for later messages.
      const std::string source = p.source;
      const std::string name = file_.empty() ? std::string(kCommandLine) : file_ + " with command-line options";
      try {
        p = ParseProblem(WriteProblemJson(p), name);
      } catch (const std::invalid_argument& e) {
        throw std::invalid_argument(RenameField(e.what(), name, fields_));
      }
      p.source = source;
    }
  } catch (const ProblemFileReadError&) {
    throw;
  } catch (const std::invalid_argument& e) {
    // The library's own range checks (BallModel::FromLambda) name its field: name the option.
    throw std::invalid_argument(RenameField(e.what(), "", fields_));
  }
  return p;
}

}  // namespace plateball::tools
