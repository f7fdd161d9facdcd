// The problem a subcommand works on: an optional PROBLEM.json (problem_io.h) plus command-line
// overrides of the ball, the initial state and the integration, validated like the file.
//
//   ProblemOptions problem;            // in the subcommand's setup
//   problem.Add(sub);
//   ... Problem p = problem.Load();    // in its run function
#pragma once

#include <CLI/CLI.hpp>
#include <Eigen/Core>
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "common/invalid_input.h"
#include "plateball/problem.h"

namespace plateball::tools {

class ProblemOptions {
 public:
  /// Whether the subcommand draws random numbers (the isoparallel multi-start, also as steer's
  /// reference; the Monte Carlo errors) and so takes --seed; join, reach, plan, converge and
  /// simulate are deterministic and do not accept it (their header still names the problem's seed).
  enum class Seed { kAccepted, kNone };
  /// Adds the positional PROBLEM.json ("-": standard input) and --lambda --theta --phi --psi --mu
  /// --x0 X,Y --orientation JSON --atol --rtol --max-steps (and --seed unless Seed::kNone) to `app`.
  void Add(CLI::App& app, Seed seed = Seed::kAccepted);

  /// Adds the overrides of the problem's isoparallel section: --start X,Y, --goal X,Y,
  /// --start-orientation JSON, --goal-orientation JSON, --starts N, --threads N.
  void AddIsoparallel(CLI::App& app);

  /// The problem used without a file (a problem file's text, e.g. the built-in Figure 7 problem)
  /// and its name in messages, instead of problem.h's defaults.
  void SetDefault(std::string json_text, std::string source_name);

  /// The problem file (or, without one, the defaults of problem.h: lambda = 1,
  /// (theta, phi, psi) = (pi/3, 0.4, 0.1), mu = 1, x0 = 0, identity orientation) with the given
  /// options applied. Throws ProblemFileReadError for an unreadable file and std::invalid_argument
  /// ("command line: --OPTION: value V: reason", or the reader's message) for bad values: a value
  /// the reader rejects is named by the option that gave it.
  Problem Load() const;

  /// The file given, or empty.
  const std::string& file() const { return file_; }

 private:
  std::string file_;
  std::string default_text_, default_source_;
  std::string start_, goal_, start_orientation_, goal_orientation_;
  long long starts_ = 0, threads_ = 0;
  std::vector<std::pair<std::string, CLI::Option*>> fields_;  ///< problem-file field -> option
  void ApplyIsoparallel(Problem* p) const;
  double lambda_ = 0, theta_ = 0, phi_ = 0, psi_ = 0, mu_ = 0, atol_ = 0, rtol_ = 0;
  long max_steps_ = 0;
  std::string seed_, x0_, orientation_;
  CLI::Option *lambda_opt_ = nullptr, *theta_opt_ = nullptr, *phi_opt_ = nullptr, *psi_opt_ = nullptr,
              *mu_opt_ = nullptr, *atol_opt_ = nullptr, *rtol_opt_ = nullptr, *max_steps_opt_ = nullptr,
              *seed_opt_ = nullptr, *x0_opt_ = nullptr, *orientation_opt_ = nullptr;
};

/// Checks of single command-line values; each throws std::invalid_argument
/// "command line: OPTION: value V: reason".
double RequireFiniteOption(const std::string& option, double v);
double RequirePositiveOption(const std::string& option, double v);
long long RequireIntegerInRange(const std::string& option, long long v, long long lo, long long hi);
/// A --threads value: 0 for the hardware's threads (at most 256), else checked in [1, 256].
int ThreadsOption(long long requested);
/// A number n of impulses per smooth piece of the problem's plan.path (--impulses of plan and
/// converge): n x pieces must be <= 10^4, the reader's limit (README, "Limits"). Nothing is checked
/// without a plan section (the task adapter names it).
void RequirePartitionSteps(const std::string& option, long long n, const Problem& p);
/// Targets of a command-line option: |x|, |y| <= kMaxCoordinate (limits.h), each named OPTION[i].
void RequireCoordinatesOption(const std::string& option, const std::vector<Eigen::Vector2d>& points);
/// "X,Y" (two finite numbers separated by a comma).
Eigen::Vector2d ParsePointOption(const std::string& option, const std::string& text);
/// "X1,Y1;X2,Y2;..." or "X1,Y1 X2,Y2 ..." (separated by ';' or white space; at least
/// `min_points` points).
std::vector<Eigen::Vector2d> ParsePointsOption(const std::string& option,
                                               const std::string& text,
                                               std::size_t min_points = 1);

}  // namespace plateball::tools
