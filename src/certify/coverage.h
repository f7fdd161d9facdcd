// Internal: the whole certificate of a general isoparallel target up to a length cap, as a list of
// pieces of parameter space each closed by one certificate (docs/paper_notes.md,
// "General targets: the rotation problem's shortest path certified" and "General targets: the
// whole certificate in one call").
//
// Every path of the rotation trick with length L in [|x1 - x0|, cap] is an oscillating or rotating
// elastica (straight lines and circles at k = 0 or rate 0) with modulus k in [0, 1], rate a and
// phase u0 (negative oscillating rates are the positive ones mirrored). The pieces, per regime:
//   window      k in [0, 0.95], rate [0, A] (oscillating) or [-A, A] (rotating)   CertifyWindow
//   slow tail   k in [0.95, 1], |rate| <= 0.5                                     CertifySeparatrixTail
//   middle      k in [0.95, 0.99995], rate [0.5, A] (oscillating: split at k = 0.999; rotating:
//               [-A, -0.5] and [0.5, A])                                          CertifyWindow
//   loops       k in [k_t, 1), k_t = sqrt(1 - 1e-4), |rate| in [0.5, A]           CertifyLoopFamily
// A is MaxSolutionRateOver the piece's k range (certify/tails.h); rates above it are
// excluded by the averaging lemma when the straight residual delta0 exceeds the margin (else the
// plan says so and lists nothing). A piece whose rate range is empty (A <= 0.5) is not listed. The
// constants are those with which the rotation problem and T10 were certified.
#pragma once

#include <string>
#include <vector>

#include "certify/window.h"
#include "plateball/elastica.h"
#include "plateball/isoparallel.h"

namespace plateball::internal {

inline constexpr double kCoverageWindowModulus = 0.95;          // top of the windows from k = 0
inline constexpr double kCoverageMiddleSplit = 0.999;           // the oscillating middle is split here
inline constexpr double kCoverageMiddleModulus = 0.99995;       // top of the middle windows
inline constexpr double kCoverageLoopModulusComplement = 1e-2;  // k'_t of the loop family
inline constexpr double kCoverageSlowRate = 0.5;                // the slow tail's |rate| bound

enum class CoveragePieceKind { kWindow, kSlowTail, kLoops };
std::string ToString(CoveragePieceKind kind);

/// One piece: k in [k_lo, k_hi] (k_hi = 1: up to the separatrix, which the slow tail and the loop
/// family hold as a limit) and rates in [rate_lo, rate_hi]: a window's signed rate interval, the
/// slow tail's [-A, A], the loop family's |rate| range (both senses).
struct CoveragePiece {
  CoveragePieceKind kind = CoveragePieceKind::kWindow;
  PendulumRegime regime = PendulumRegime::kOscillating;
  double k_lo = 0.0, k_hi = 0.0;
  double rate_lo = 0.0, rate_hi = 0.0;
  /// "oscillating window, k [0, 0.95], rate [0, 21.0575]".
  std::string Name() const;
};

struct CoveragePlan {
  std::string message;                // empty when valid, else the invalid-value message
  double straight_residual = 0.0;     // delta0
  bool rate_tail_excluded = false;    // delta0 > margin: the pieces are the whole certificate
  std::vector<CoveragePiece> pieces;  // empty unless rate_tail_excluded
};

/// The pieces whose certificates together prove every solution of length <= cap (target.radius
/// < cap <= 1e3) found: listed from the (usually) costliest down.
CoveragePlan PlanCoverage(const CertifyTarget& target, double cap, double margin = 1e-7);

/// What one piece's certificate gave: `closed` when certified (a window: every solution in it
/// proved the only one of its box, in `found`) or excluded (slow tail, loops: none in it).
struct CoveragePieceResult {
  bool closed = false;
  std::string result;  // the certificate's status and message
  long boxes = 0;
  double resolved_volume = 0.0;
  std::vector<CertifyPoint> found;  // canonical (CanonicalSolution), windows only
  bool interrupted = false;         // stopped by the interrupt (then not closed)
};

/// Runs the piece's certificate over lengths [target.radius, cap] with the given box budget,
/// the first-order tests on and no known solution (every solution must be proved). `interrupt`
/// is asked from the piece's box loop (InterruptRequested): true stops it, not closed.
CoveragePieceResult RunCoveragePiece(const CertifyTarget& target,
                                     const CoveragePiece& piece,
                                     double cap,
                                     long max_boxes,
                                     const CertifyInterrupt& interrupt = {},
                                     double margin = 1e-7);

/// The index of the solution in `solutions` that is the path `p` (canonical, of this regime):
/// the same regime and SamePath within `tolerance` of its CanonicalSolution; -1 when none.
int MatchingSolution(const std::vector<IsoparallelSolution>& solutions,
                     PendulumRegime regime,
                     const CertifyPoint& p,
                     double tolerance);

}  // namespace plateball::internal
