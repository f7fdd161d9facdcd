// The isoparallel problem (section 2.2): the shortest smooth path on the plate from (x0, A0) to
// (x1, A1), where rolling along the path takes the orientation A0 to A1.
//
// Optimal paths are elastica (elastica.h): the heading is a pendulum with three parameters
// (G, energy, phase). The solver shoots over exactly these with Ceres (TinySolver,
// Levenberg-Marquardt, 3 residuals in 3 unknowns) using the paper's rotation trick: a candidate
// from x0 runs until its n-th crossing of the circle |x - x0| = |x1 - x0| (n = 1, 2, ...: paths
// that leave and re-enter the circle count), the plane is rotated by the B about e3 taking the
// crossing point to x1, and B A B^-1 is compared with A1 A0^-1 (residual: LogSO3 of the mismatch).
// The search stage frees the length: 4 unknowns (G, energy, phase, L), 4 residuals
// (|x(L) - x0| - |x1 - x0| and the mismatch with B taken from the direction of x(L)), smooth where
// the crossing number jumps (a tangency adds or removes a pair of crossings, and solutions often
// lie near one). The polish (to the tolerance) runs on the same four unknowns with exact
// Jacobians; a reported path's n is counted on it with a proof (every root of |x(s) - x0| =
// |x1 - x0| before its end, also a pair between two of the search's nodes).
// General targets, two stages: the shapes (rate, modulus) are the first `starts` Halton points
// (no seed); for each shape ONE rolling table over [0, T + s_max] serves the whole (phase,
// length) plane (Q(s0, s0 + L) = Q(0, s0 + L) Q(0, s0)^-1, every start node s0 of one period,
// every crossing or near-tangency of the chord along L), and only the local minima of the
// rotation residual there below 1 rad start the 4-unknown search. From each new solution the curve
// on which three of the four residuals vanish is followed both ways, and where the fourth changes
// sign a search starts (the twin across a fold, found from either member of the pair). Every
// distinct solution up to length_cap_factor times the shortest is reported, sorted by length.
// Each reported solution is verified independently of the solver by VerifyRolling (a second
// integrator along the path).
//
// Completeness. General targets: the shapes are a sample of the (rate, modulus) plane and the
// (phase, length) scan is at node resolution, so the method is NOT complete (`complete` stays
// false). On problems/isoparallel_rotation.json it finds 31 solutions up to 3x the shortest (the
// 8192-start shooting it replaces found 29), and on ten test targets nothing that a 16,384-start
// shooting finds is missed (docs/paper_notes.md, "General targets").
//
// Identity targets (A1 = A0, Figure 7) are solved by direct enumeration instead
// (isoparallel_families.h): there every solution covers a whole number of curvature periods and
// is a one-parameter family, the families are the roots of one scalar function of the modulus per
// period count, and a certificate ends the enumeration. Set enumerate_families = false to shoot.
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <functional>
#include <limits>
#include <string>
#include <vector>

#include "plateball/elastica.h"
#include "plateball/export.h"
#include "plateball/field_list.h"
#include "plateball/integration_options.h"

namespace plateball PLATEBALL_EXPORT {

/// Options of SolveIsoparallel. The problem reader fills them from the JSON "isoparallel.solver"
/// section (plus the file's seed and integration section) with the same ranges as Validate().
struct IsoparallelOptions {
  // Work limits (README, "Limits"): 10^6 starts took 13 minutes, a length cap of 1000 past a minute.
  static constexpr int kMaxStarts = 10000;
  static constexpr int kMaxIterations = 100000;
  static constexpr int kMaxThreads = 256;
  static constexpr double kMaxLengthCapFactor = 10.0;
  /// General targets: the shapes (rate, modulus; the first `starts` Halton points) whose
  /// (phase, length) plane is scanned on one rolling table each; identity target with
  /// enumerate_families = false: the multi-start points of the comparison shooting. 2048 shapes
  /// miss one of the solutions a 16,384-start shooting finds on ten test targets, 4096 none
  /// (docs/paper_notes.md, "General targets").
  int starts = 4096;
  double length_cap_factor = 3.0;  ///< report solutions up to this times the shortest length (>= 1)
  int max_iterations = 100;        ///< Levenberg-Marquardt iterations per local solve
  double tolerance = 1e-12;        ///< accepted |LogSO3| orientation residual (radians)
  int threads = 1;                 ///< worker threads in [1, kMaxThreads] (results do not depend on it)
  /// Scrambles the start sequence of the shooting at an identity target only (a comparison with
  /// the enumeration); general targets use the unshifted sequence, the same for every seed.
  std::uint64_t seed = 1;
  /// Longest path searched before a shortest one is known; 0 = automatic (see README).
  double max_length = 0.0;
  /// Identity targets (|LogSO3(A1 A0^-1)| <= tolerance): enumerate the families directly
  /// (complete up to the length cap; isoparallel_families.h). false: multi-start shooting.
  bool enumerate_families = true;
  /// Tolerances and step bound of the independent verification by rolling (VerifyRolling);
  /// exceeding the step bound ends the solve with kIntegrationFailure.
  IntegrationOptions integration;
  /// Called (from a worker thread, serialised) after each start with (starts done, starts in
  /// this pass), or by the family enumeration after each period count m with (m, 0); for a
  /// tool's progress line. The library never prints.
  std::function<void(int, int)> progress;
  /// Empty when valid, else a message naming the field, the value and the bound.
  std::string Validate() const;

  /// The field list (field_list.h): the problem file's "isoparallel.solver" section (seed,
  /// max_length and integration come from elsewhere in a file).
  template <class Archive>
  void Serialize(Archive* a) {
    a->Visit(
        PLATEBALL_FIELD(starts, "shapes scanned (general targets) or shooting starts (identity targets)")
            .Counts(1, kMaxStarts),
        PLATEBALL_FIELD(length_cap_factor, "report solutions up to this times the shortest length")
            .Closed(1.0, kMaxLengthCapFactor),
        PLATEBALL_FIELD(max_iterations, "Levenberg-Marquardt iterations per local solve").Counts(1, kMaxIterations),
        PLATEBALL_FIELD(tolerance, "accepted |LogSO3| orientation residual (radians)").Tolerance(),
        PLATEBALL_FIELD(threads, "worker threads (results do not depend on it)").Counts(1, kMaxThreads),
        PLATEBALL_FIELD(seed, "scrambles the shooting's start sequence at an identity target").NotInFile(),
        PLATEBALL_FIELD(max_length, "longest path searched before a shortest one is known; 0: automatic").NotInFile(),
        PLATEBALL_FIELD(enumerate_families, "identity targets: enumerate the families (false: multi-start shooting)"),
        PLATEBALL_FIELD(integration, "tolerances and step bound of the verification by rolling").NotInFile());
  }
};

/// Boundary data: x0 = start, x1 = goal, A0 = start_orientation, A1 = goal_orientation.
struct IsoparallelProblem {
  Eigen::Vector2d start = Eigen::Vector2d::Zero();
  Eigen::Vector2d goal = Eigen::Vector2d::Zero();
  Eigen::Matrix3d start_orientation = Eigen::Matrix3d::Identity();
  Eigen::Matrix3d goal_orientation = Eigen::Matrix3d::Identity();
};

/// One optimal path: x(s) = start + elastica.Position(s), s in [0, length].
struct IsoparallelSolution {
  ElasticaParameters parameters;  ///< in the plate's frame (heading_w includes the rotation B)
  Eigen::Vector2d start = Eigen::Vector2d::Zero();
  double length = 0.0;
  /// Which crossing of the circle |x - x0| = |x1 - x0| ends the path: 1 + the roots before the end.
  int crossing = 1;
  double G = 0.0;        ///< pendulum "gravity" |W| (1/length^2); R ~ 1/sqrt(G)
  double energy = 0.0;   ///< pendulum energy E = theta'^2/2 - G cos(theta)
  double periods = 0.0;  ///< length / curvature period
  /// A one-parameter family: the path covers a whole number of curvature periods and stays a
  /// solution for every starting phase (e.g. identity target). Counted once; the phase
  /// reported is the canonical one, parameters.phase = 0.
  bool family = false;
  double shooting_residual = 0.0;     ///< |LogSO3| in the shooting's own integrator
  double orientation_residual = 0.0;  ///< |LogSO3(A1 A0^-1)^-1 R)|, R by VerifyRolling
  double orientation_error = 0.0;     ///< operator 2-norm ||A1 - R A0|| (verification)
  double endpoint_error = 0.0;        ///< |x(length) - x1|
  /// The first conjugate time along the extremal in (0, kConjugateSearchFactor x length]: where
  /// the Jacobian of the end state (x, y, log R) with respect to the initial costate and the length
  /// (the exponential map) changes sign; +infinity when it does not there (docs/paper_notes.md,
  /// "Conjugate points of the isoparallel extremals"). A family's end is conjugate (its members at
  /// other phases reach the same state), so its conjugate time is at most its length.
  double conjugate_time = std::numeric_limits<double>::infinity();
  /// No conjugate point strictly before the end (conjugate_time >= length to kConjugateEndTolerance
  /// relative): Jacobi's condition. The path is then a local minimiser of length among nearby paths
  /// with the same ends; it says nothing of other, distant paths (global optimality is what the
  /// branch-and-bound certificate, isoparallel_certificate.h, proves).
  bool locally_optimal = false;

  /// The optimal path as an Elastica (arc length from the start).
  Elastica Path() const { return Elastica(parameters); }
  /// The contact point at arc length s along the path.
  Eigen::Vector2d PositionAt(double s) const { return start + Elastica(parameters).Position(s); }
};

/// The conjugate-point search runs to this multiple of the solution's length.
constexpr double kConjugateSearchFactor = 2.0;
/// A conjugate time within this relative distance of the end is the end (a family's end point).
constexpr double kConjugateEndTolerance = 1e-7;

/// Two distinct reported solutions of equal length (to kMaxwellLengthTolerance relative): both reach
/// the goal, so the goal is a Maxwell point of each, and neither stays optimal past it.
struct MaxwellPair {
  int first = 0;   ///< index into IsoparallelSummary::solutions
  int second = 0;  ///< a larger index
};
constexpr double kMaxwellLengthTolerance = 1e-9;

enum class IsoparallelStatus {
  kNotRun,              ///< default: no solve was run
  kSolved,              ///< at least one verified solution
  kNoSolution,          ///< no start converged to a verified solution
  kIntegrationFailure,  ///< the verification by rolling failed (step bound); message says where
};
/// The value's word as the tools write it in their JSON output and messages.
std::string ToString(IsoparallelStatus status);

enum class IsoparallelMethod {
  kShooting,           ///< seeded multi-start shooting (general targets)
  kFamilyEnumeration,  ///< identity target: families enumerated directly
};
/// The value's word as the tools write it in their JSON output and messages.
std::string ToString(IsoparallelMethod method);

struct IsoparallelSummary {
  IsoparallelProblem problem;
  IsoparallelOptions options;
  IsoparallelStatus status = IsoparallelStatus::kNotRun;
  std::string message = "not run";  ///< why, when not kSolved (empty when solved)
  IsoparallelMethod method = IsoparallelMethod::kShooting;
  /// Family enumeration: the certificate ended the search (every solution up to the cap is
  /// reported), and the largest period count examined. Shooting: false and 0.
  bool complete = false;
  int periods_searched = 0;
  /// Shooting: the starts were shifted by options.seed (identity target with
  /// enumerate_families = false only). General targets: false, the starts and the solution list
  /// do not depend on the seed.
  bool seeded = false;
  std::vector<IsoparallelSolution> solutions;  ///< distinct, sorted by length (shortest first)
  /// Pairs of solutions of equal length (Maxwell points at the goal); a family is besides a whole
  /// continuum of equal-length solutions (its other phases).
  std::vector<MaxwellPair> maxwell_pairs;
  int local_solves = 0;        ///< Levenberg-Marquardt runs (start, crossing)
  int converged_solves = 0;    ///< runs that reached the tolerance
  long evaluations = 0;        ///< candidate paths evaluated (residuals and Jacobians)
  double searched_length = 0;  ///< longest path considered
  double time_seconds = 0.0;
  /// True when the status gives a result that may be used.
  bool IsSolutionUsable() const { return status == IsoparallelStatus::kSolved; }
  /// Shortest solution. Throws std::logic_error when there is none.
  const IsoparallelSolution& Shortest() const;
  /// One line: the status, the message and the main numbers.
  std::string BriefReport() const;
  /// The brief report and one line per solution.
  std::string FullReport() const;
};

/// Solves the isoparallel problem. Throws std::invalid_argument (naming the field and value)
/// for non-finite points, start == goal (the rotation trick needs a circle of positive radius),
/// non-rotation orientations or invalid options. Non-convergence is a status.
IsoparallelSummary SolveIsoparallel(const IsoparallelProblem& problem, const IsoparallelOptions& options = {});

/// Reorientation R = A(length) A(0)^-1 of rolling along the path: A' = hat(e3 x x') A with the
/// closed-form tangent, integrated by the Runge-Kutta-Fehlberg 7(8) pair (Boost.Odeint) at a
/// tenth of the integration tolerances (clamped to 1e-15), independent of the solver's Magnus
/// tables. An enumerated family of m >= 2 periods (length m T to round-off) is integrated over
/// one period P and reported as P^m (the tangent is T-periodic). SolveIsoparallel checks a
/// rotating family's mirror image through its partner (the rolling along a path reflected in a
/// vertical plane S is S R S^-1: same residual). Throws std::runtime_error when the integration
/// exceeds integration.max_steps.
Eigen::Matrix3d VerifyRolling(const IsoparallelSolution& solution, const IntegrationOptions& integration = {});

}  // namespace PLATEBALL_EXPORT
