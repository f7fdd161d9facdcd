#include "common/problem_options.h"

#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <sstream>
#include <stdexcept>

#include "common/command_line.h"
#include "common/number_format.h"
#include "plateball/problem_io.h"

namespace plateball::tools {
namespace {

[[noreturn]] void Fail(const std::string& option, const std::string& value, const std::string& what) {
  throw std::invalid_argument(std::string(kCommandLine) + ": " + option + ": value " + value + ": " + what);
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

Eigen::Vector2d ParsePointOption(const std::string& option, const std::string& text) {
  const auto comma = text.find(',');
  Eigen::Vector2d p;
  if (comma == std::string::npos || !ParseDouble(text.substr(0, comma), &p.x()) ||
      !ParseDouble(text.substr(comma + 1), &p.y()))
    Fail(option, Quote(text), "must be two finite numbers X,Y");
  return p;
}

std::vector<Eigen::Vector2d> ParsePointsOption(const std::string& option, const std::string& text,
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
  app.add_option("problem", file_, "problem file (JSON, see README \"Problem files\"); options below override it");
  lambda_opt_ = app.add_option("--lambda", lambda_, "ball parameter lambda = (alpha+beta)/(1+beta) > 0");
  theta_opt_ = app.add_option("--theta", theta_, "initial theta (rad)");
  phi_opt_ = app.add_option("--phi", phi_, "initial phi (rad)");
  psi_opt_ = app.add_option("--psi", psi_, "initial psi (rad)");
  mu_opt_ = app.add_option("--mu", mu_, "energy mu > 0 (the period is 2 pi/sqrt(mu))");
  x0_opt_ = app.add_option("--x0", x0_, "initial contact point X,Y");
  orientation_opt_ = app.add_option("--orientation", orientation_,
                                    "initial orientation as JSON: {\"quaternion\": [w,x,y,z]}, {\"matrix\": [[..],[..],[..]]} "
                                    "or {\"axis_angle\": {\"axis\": [x,y,z], \"angle\": a}}");
  atol_opt_ = app.add_option("--atol", atol_, "absolute tolerance of the integration, in (0, 1)");
  rtol_opt_ = app.add_option("--rtol", rtol_, "relative tolerance of the integration, in (0, 1)");
  max_steps_opt_ = app.add_option("--max-steps", max_steps_, "step limit of one integration (>= 1)");
  if (seed == Seed::kAccepted)
    seed_opt_ = app.add_option("--seed", seed_, "seed of randomised searches, 0 ... 2^64 - 1")->type_name(kSeedTypeName);
}

Problem ProblemOptions::Load() const {
  Problem p = file_.empty() ? Problem{} : ReadProblemFile(file_);
  if (file_.empty()) p.source = "(built-in defaults)";
  bool overridden = false;
  auto given = [&](const CLI::Option* o) {
    const bool g = o != nullptr && o->count() > 0;
    overridden = overridden || g;
    return g;
  };
  if (given(lambda_opt_)) p.model = BallModel::FromLambda(RequirePositiveOption("--lambda", lambda_)), p.physical.reset();
  if (given(theta_opt_)) p.initial_angles.theta = RequireFiniteOption("--theta", theta_);
  if (given(phi_opt_)) p.initial_angles.phi = RequireFiniteOption("--phi", phi_);
  if (given(psi_opt_)) p.initial_angles.psi = RequireFiniteOption("--psi", psi_);
  if (given(mu_opt_)) p.mu = RequirePositiveOption("--mu", mu_);
  if (given(x0_opt_)) p.x0 = ParsePointOption("--x0", x0_);
  if (given(orientation_opt_)) p.A0 = ParseOrientation(orientation_, "--orientation", kCommandLine);
  if (given(atol_opt_)) {
    if (!(std::isfinite(atol_) && atol_ > 0 && atol_ < 1)) Fail("--atol", FormatNumber(atol_), "must be in (0, 1)");
    p.integration.absolute_tolerance = atol_;
  }
  if (given(rtol_opt_)) {
    if (!(std::isfinite(rtol_) && rtol_ > 0 && rtol_ < 1)) Fail("--rtol", FormatNumber(rtol_), "must be in (0, 1)");
    p.integration.relative_tolerance = rtol_;
  }
  if (given(max_steps_opt_)) p.integration.max_steps = static_cast<long>(RequireIntegerInRange("--max-steps", max_steps_, 1, 1'000'000'000'000LL));
  if (given(seed_opt_)) p.seed = ParseSeedOption("--seed", seed_);
  if (overridden) {
    // Validate the combination exactly as a file is validated (e.g. both tolerances below
    // double precision), then keep the source name for later messages.
    const std::string source = p.source;
    p = ParseProblem(WriteProblemJson(p), (file_.empty() ? std::string(kCommandLine) : file_ + " with command-line options"));
    p.source = source;
  }
  return p;
}

}  // namespace plateball::tools
