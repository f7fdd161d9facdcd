#include "certify/coverage.h"

#include <array>
#include <cmath>
#include <sstream>

#include "certify/loops.h"
#include "certify/separatrix.h"
#include "certify/tails.h"
#include "check.h"
#include "jacobi_elliptic.h"

namespace plateball::internal {

namespace {

// k_t of the loop family: k'_t = kCoverageLoopModulusComplement.
double LoopModulus() {
  const double kp = kCoverageLoopModulusComplement;
  return std::sqrt((1.0 - kp) * (1.0 + kp));
}

// The middle windows (|rate| in [0.5, A] for k in [k_lo, k_hi]) and the loop family of a regime,
// those with a non-empty rate range.
void AddFastTail(
    const CertifyTarget& target, PendulumRegime regime, double cap, double margin, std::vector<CoveragePiece>* pieces) {
  const double slow = kCoverageSlowRate;
  std::vector<std::array<double, 2>> middles = {{kCoverageWindowModulus, kCoverageMiddleModulus}};
  if (regime == PendulumRegime::kOscillating)
    middles = {{kCoverageMiddleSplit, kCoverageMiddleModulus}, {kCoverageWindowModulus, kCoverageMiddleSplit}};
  for (const std::array<double, 2>& k : middles) {
    const double a = MaxSolutionRateOver(target, regime, k[0], k[1], cap, margin);
    if (!(a > slow)) continue;
    if (regime == PendulumRegime::kRotating)
      pieces->push_back(CoveragePiece{CoveragePieceKind::kWindow, regime, k[0], k[1], -a, -slow});
    pieces->push_back(CoveragePiece{CoveragePieceKind::kWindow, regime, k[0], k[1], slow, a});
  }
  const double k_t = LoopModulus(), a = MaxSolutionRateOver(target, regime, k_t, 1.0, cap, margin);
  if (a > slow) pieces->push_back(CoveragePiece{CoveragePieceKind::kLoops, regime, k_t, 1.0, slow, a});
}

std::string Interval(double lo, double hi) {
  std::ostringstream s;
  s.precision(11);
  s << "[" << lo << ", " << hi << "]";
  return s.str();
}

CoveragePieceResult RunWindow(const CertifyTarget& target,
                              const CoveragePiece& piece,
                              double cap,
                              long max_boxes,
                              double margin,
                              const CertifyInterrupt& interrupt) {
  CertifyWindowOptions o;
  o.interrupted = interrupt;
  o.regime = piece.regime;
  o.max_boxes = max_boxes;
  o.margin = margin;
  o.first_order = true;
  // One period of the phase at k_hi (>= the period at every smaller k), centred on 0.
  const double period = PhasePeriod(piece.regime, piece.k_hi);
  o.window.lo = {piece.rate_lo, piece.k_lo, -0.5 * period, target.radius};
  o.window.hi = {piece.rate_hi, piece.k_hi, 0.5 * period, cap};
  const CertifyWindowResult w = CertifyWindow(target, {}, o);
  CoveragePieceResult r;
  r.closed = w.Certified();
  r.result = w.message.empty() ? ToString(w.status) : w.message;
  r.boxes = w.boxes;
  r.resolved_volume = w.resolved_volume;
  r.found = w.found;
  r.interrupted = w.status == CertifyStatus::kInterrupted;
  return r;
}

template <class Result>
CoveragePieceResult FromExclusion(const Result& e) {
  CoveragePieceResult r;
  r.closed = e.Excluded();
  r.result = ToString(e.status) + (e.message.empty() ? "" : ": " + e.message);
  r.boxes = e.boxes;
  r.resolved_volume = e.resolved_volume;
  r.interrupted = e.status == ExclusionStatus::kInterrupted;
  return r;
}

// The fields the tail certificates share: regime, L in [|x1 - x0|, cap], budget and margin.
template <class Options>
Options ExclusionOptions(const CertifyTarget& target,
                         const CoveragePiece& piece,
                         double cap,
                         long max_boxes,
                         double margin,
                         const CertifyInterrupt& interrupt) {
  Options o;
  o.interrupted = interrupt;
  o.regime = piece.regime;
  o.length_lo = target.radius;
  o.cap = cap;
  o.max_boxes = max_boxes;
  o.margin = margin;
  return o;
}

CoveragePieceResult RunSlowTail(const CertifyTarget& target,
                                const CoveragePiece& piece,
                                double cap,
                                long max_boxes,
                                double margin,
                                const CertifyInterrupt& interrupt) {
  auto o = ExclusionOptions<SeparatrixTailOptions>(target, piece, cap, max_boxes, margin, interrupt);
  o.k_lo = piece.k_lo;
  o.rate_max = piece.rate_hi;
  return FromExclusion(CertifySeparatrixTail(target, o));
}

CoveragePieceResult RunLoops(const CertifyTarget& target,
                             const CoveragePiece& piece,
                             double cap,
                             long max_boxes,
                             double margin,
                             const CertifyInterrupt& interrupt) {
  auto o = ExclusionOptions<LoopFamilyOptions>(target, piece, cap, max_boxes, margin, interrupt);
  o.k_t = piece.k_lo;
  // The heading error eps decreases in W2: oscillating (larger gap G_t), cores as wide as their
  // cells (W2 = K(k_t), no run at k = k_t); rotating, the automatic W2 (2 asin(sech W2) = G_t).
  // Those of the rotation problem's and T10's certificates.
  o.core_half_width = piece.regime == PendulumRegime::kOscillating ? CompleteEllipticK(piece.k_lo) : 0.0;
  o.rate_lo = piece.rate_lo;
  o.rate_max = piece.rate_hi;
  return FromExclusion(CertifyLoopFamily(target, o));
}

}  // namespace

std::string ToString(CoveragePieceKind kind) {
  switch (kind) {
    case CoveragePieceKind::kWindow:
      return "window";
    case CoveragePieceKind::kSlowTail:
      return "slow tail";
    case CoveragePieceKind::kLoops:
      return "loops";
  }
  return "unknown";
}

std::string CoveragePiece::Name() const {
  const std::string rate = kind == CoveragePieceKind::kLoops ? "|rate| " : "rate ";
  return ToString(regime) + " " + ToString(kind) + ", k " + Interval(k_lo, k_hi) + ", " + rate +
         Interval(rate_lo, rate_hi);
}

CoveragePlan PlanCoverage(const CertifyTarget& target, double cap, double margin) {
  CoveragePlan plan;
  if (!(target.radius > 0.0 && target.radius <= 1e3))
    plan.message = InvalidValueMessage("target.radius", target.radius, "must be in (0, 1e3]");
  else if (!(cap > target.radius && cap <= 1e3))
    plan.message = InvalidValueMessage("cap", cap, "must lie in (|x1 - x0|, 1e3]");
  else if (!(margin >= 0.0 && margin <= 1e-2))
    plan.message = InvalidValueMessage("margin", margin, "must be in [0, 1e-2]");
  if (!plan.message.empty()) return plan;
  plan.straight_residual = StraightResidual(target);
  plan.rate_tail_excluded = plan.straight_residual > margin;
  if (!plan.rate_tail_excluded) return plan;
  std::vector<CoveragePiece>& pieces = plan.pieces;
  AddFastTail(target, PendulumRegime::kOscillating, cap, margin, &pieces);
  const double k0 = kCoverageWindowModulus;
  const double a_osc = MaxSolutionRateOver(target, PendulumRegime::kOscillating, 0.0, k0, cap, margin);
  pieces.push_back(CoveragePiece{CoveragePieceKind::kWindow, PendulumRegime::kOscillating, 0.0, k0, 0.0, a_osc});
  AddFastTail(target, PendulumRegime::kRotating, cap, margin, &pieces);
  const double a_rot = MaxSolutionRateOver(target, PendulumRegime::kRotating, 0.0, k0, cap, margin);
  pieces.push_back(CoveragePiece{CoveragePieceKind::kWindow, PendulumRegime::kRotating, 0.0, k0, -a_rot, a_rot});
  for (PendulumRegime regime : {PendulumRegime::kOscillating, PendulumRegime::kRotating})
    pieces.push_back(
        CoveragePiece{CoveragePieceKind::kSlowTail, regime, k0, 1.0, -kCoverageSlowRate, kCoverageSlowRate});
  return plan;
}

CoveragePieceResult RunCoveragePiece(const CertifyTarget& target,
                                     const CoveragePiece& piece,
                                     double cap,
                                     long max_boxes,
                                     const CertifyInterrupt& interrupt,
                                     double margin) {
  switch (piece.kind) {
    case CoveragePieceKind::kWindow:
      return RunWindow(target, piece, cap, max_boxes, margin, interrupt);
    case CoveragePieceKind::kSlowTail:
      return RunSlowTail(target, piece, cap, max_boxes, margin, interrupt);
    case CoveragePieceKind::kLoops:
      return RunLoops(target, piece, cap, max_boxes, margin, interrupt);
  }
  return {};
}

int MatchingSolution(const std::vector<IsoparallelSolution>& solutions,
                     PendulumRegime regime,
                     const CertifyPoint& p,
                     double tolerance) {
  for (std::size_t i = 0; i < solutions.size(); ++i) {
    const IsoparallelSolution& s = solutions[i];
    if (s.parameters.regime == regime && SamePath(regime, CanonicalSolution(s.parameters, s.length), p, tolerance))
      return static_cast<int>(i);
  }
  return -1;
}

}  // namespace plateball::internal
