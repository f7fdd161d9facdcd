// The certificate of a general isoparallel target: every solution of length up to a
// cap, each proved (Krawczyk) the only solution of a box of parameter space, and a proof that the
// rest of parameter space holds none. SolveIsoparallel's shooting is a deterministic sample
// (`complete` false for general targets); this is the offline check that turns its list into a
// complete one, or finds what it missed.
//
// Parameter space (the elastica's regime, modulus k in [0, 1], rate, phase, length in
// [|x1 - x0|, cap]) is cut into pieces (docs/paper_notes.md, "General targets: the whole
// certificate in one call"): windows over k in [0, 0.95] and up to 0.99995 (branch and bound with
// interval bounds on the rolling, first-order tests, Krawczyk), the slow separatrix tail and the
// fast one loop by loop (exclusion), rates above an averaging-lemma bound (excluded). The result
// is rigorous up to the floating-point margin 1e-7 on the centre residuals. It costs minutes: on
// problems/isoparallel_rotation.json at 1.0001 x the shortest, 209M boxes and 22.5 CPU minutes.
#pragma once

#include <functional>
#include <string>
#include <vector>

#include "plateball/elastica.h"
#include "plateball/export.h"
#include "plateball/isoparallel.h"

namespace plateball PLATEBALL_EXPORT {

/// One piece of parameter space and what its certificate gave.
struct IsoparallelCertificatePiece {
  std::string name;              ///< e.g. "rotating window, k [0, 0.95], rate [-11.595842, 11.595842]"
  bool closed = false;           ///< certified (every solution in it proved) or excluded (none in it)
  std::string result;            ///< the piece certificate's status and message
  long boxes = 0;                ///< boxes examined
  double resolved_volume = 0.0;  ///< fraction of the piece decided, in [0, 1]
  int proved = 0;                ///< solutions proved in it (windows only)
  double cpu_seconds = 0.0;
};

/// Options of CertifyIsoparallel.
struct IsoparallelCertificateOptions {
  static constexpr long kMaxBoxes = 10000000000L;
  static constexpr int kMaxThreads = 256;
  /// Certify every solution of length <= cap_factor x (1 + 1e-4) x the solver's shortest (the
  /// 1e-4 puts a solution at the cap, the shortest at 1.0, inside the pieces), in [1, 10].
  double cap_factor = 1.0;
  /// If > 0: this length cap instead (then no solution is needed: a cap below the shortest
  /// proves a lower bound on the length of every solution). Must exceed |x1 - x0|, <= 1000.
  double length_cap = 0.0;
  long max_boxes = 250000000;  ///< budget of boxes per piece, in [1, kMaxBoxes]
  int threads = 1;             ///< pieces certified in parallel, [1, kMaxThreads]
  /// Called (serialised) as each piece ends: (piece, pieces ended, pieces in all).
  std::function<void(const IsoparallelCertificatePiece&, int, int)> progress;
  /// A request to stop (Ctrl-C; Python sets it): asked before each piece starts and about every
  /// thousand boxes of each running piece (milliseconds), from the threads that run them, so it
  /// must be thread-safe and cheap. Once it returns true every piece stops at its next question,
  /// pieces not started are not run, and the certificate is kInterrupted. Empty: never asked.
  std::function<bool()> interrupted;
  /// Empty when valid, else a message naming the field, the value and the bound.
  std::string Validate() const;
};

enum class IsoparallelCertificateStatus {
  kNotRun,         ///< default
  kComplete,       ///< every piece closed: `solutions` is every solution up to the cap
  kIncomplete,     ///< some piece did not close (budget, or an undecided box): see `pieces`
  kNotApplicable,  ///< identity target (the family enumeration is complete already), no solution
                   ///< to set the cap from, or a target the straight rolling reaches within the margin
  kInterrupted,    ///< stopped by `interrupted` before every piece ended: nothing is claimed
};
/// The value's word as the tools write it in their JSON output and messages.
std::string ToString(IsoparallelCertificateStatus status);

/// A solution proved the only one of a box, in canonical parameters (k >= 0; the phase of the
/// Jacobi argument in [0, one period); an oscillating path written with a positive rate).
struct CertifiedSolution {
  PendulumRegime regime = PendulumRegime::kOscillating;
  double rate = 0.0, modulus = 0.0, phase = 0.0, length = 0.0;
  int solver_index = -1;  ///< the solver's solution that is this path, or -1 (the solver missed it)
};

struct IsoparallelCertificate {
  IsoparallelCertificateStatus status = IsoparallelCertificateStatus::kNotRun;
  std::string message = "not run";           ///< why, when not kComplete (empty when complete)
  double length_cap = 0.0;                   ///< every solution of length <= this is certified
  double straight_residual = 0.0;            ///< delta0: the straight rolling's distance to the target (rad)
  std::vector<CertifiedSolution> solutions;  ///< proved solutions, sorted by length
  /// Indices of the solver's solutions of length <= length_cap that no piece proved. Empty when
  /// complete (a solver's solution outside the proved list would contradict the certificate,
  /// reported as kIncomplete with the reason).
  std::vector<int> solver_unproved;
  std::vector<IsoparallelCertificatePiece> pieces;
  long boxes = 0;
  double cpu_seconds = 0.0;   ///< summed over the pieces
  double time_seconds = 0.0;  ///< wall clock

  /// True when the certificate closed: every solution up to the cap is proved.
  bool IsComplete() const { return status == IsoparallelCertificateStatus::kComplete; }
  bool IsSolutionUsable() const { return IsComplete(); }  ///< the shape every summary shares

  /// How many proved solutions the solver missed (solver_index -1); meaningful when complete.
  int MissedBySolver() const;
  /// One line: the status, the cap, the solutions proved and missed, boxes and time.
  std::string BriefReport() const;
  /// BriefReport, then the message, every proved solution (with its solver index) and every piece.
  std::string FullReport() const;
};

/// Certifies the solver's answer: every solution of length <= the cap is found and proved, or
/// the status says which piece did not close. `solved` is SolveIsoparallel's summary (its problem
/// and solutions). Throws std::invalid_argument (naming the field and value) for invalid options.
IsoparallelCertificate CertifyIsoparallel(const IsoparallelSummary& solved,
                                          const IsoparallelCertificateOptions& options = {});

}  // namespace PLATEBALL_EXPORT
