// Internal: the fast separatrix tail of the certified exclusion for general isoparallel targets,
// loop by loop (docs/paper_notes.md, "General targets: the separatrix tail loop by
// loop"). The composition lemma (b) of "the tails of the certificate window", point 7.
//
// For every modulus k in [k_t, 1), in the cell |v - 2jK| <= K (v = a s + u0) the heading is
// within G_t = SeparatrixHeadingGapSup(regime, k_t) of the separatrix piece
// (+-)2 gd(v - 2jK) (mod 2 pi; rotating the same sense in every cell, oscillating mirrored in every
// other cell). Replacing the separatrix beyond |v - 2jK| > W2 by its limit direction (the run's
// direction) costs 2 asin(sech W2) more. So every tail path is within
//   eps = G_t + 2 asin(sech W2)
// in heading, hence (rolling comparison) within eps L in rotation and chord, of a LOOP MODEL path:
//   - cores: the separatrix heading sigma_j 2 gd(b (s - c_j)) on |s - c_j| <= W2 / b (b = |a|),
//   - centred at c_j = t0 + j P, P = r + 2 W2 / b, j in Z (sigma_j = sigma_0 rotating,
//     sigma_0 (-1)^j oscillating),
//   - joined by exact straight runs of length r = (2K - 2 W2) / b, direction pi.
// Its coordinates (LoopAxis): rate b in [a_lo, A], run length r in [2 (K_t - W2) / A, cap] (a run
// longer than the path meets at most one core: r = cap stands for every longer run), phase t0 (arc
// length from the path start to core 0's centre) in [-W2 / a_lo, cap + W2 / a_lo], length L.
// The model's rolling: exact exponentials on the runs, and on the cores the closed-form rolling of
// the rotating elastica at kLoopCoreModulus (within SeparatrixHeadingGapSup(kRotating,
// kLoopCoreModulus) of the separatrix in heading: added to the box bound).
#pragma once

#include <Eigen/Core>
#include <string>
#include <vector>

#include "certify/bisection.h"
#include "certify/vocabulary.h"
#include "plateball/elastica.h"

namespace plateball::internal {

/// Coordinates of a loop model point (stored in a CertifyPoint / CertifyBox): rate b > 0, run
/// length r >= 0, phase t0 (arc length from the start to the centre of core 0), length L.
enum LoopAxis { kLoopRate = 0, kLoopRun = 1, kLoopPhase = 2, kLoopLength = 3 };

/// The modulus whose rotating elastica stands for the separatrix core (1 - 1e-12: heading within
/// SeparatrixHeadingGapSup(kRotating, kLoopCoreModulus) ~ 2e-6 of 2 gd).
inline constexpr double kLoopCoreModulus = 1.0 - 1e-12;

/// int_0^inf (pi - 2 gd y) dy = int_0^inf 4 atan(e^-y) dy = 4 Catalan: a rate change at a fixed
/// core centre moves the core's heading by at most 2 |d(1/b)| times this in L1 (both halves).
inline constexpr double kLoopCoreRateIntegral = 4.0 * 0.91596559417721901505;

/// The loop family's heading error eps = SeparatrixHeadingGapSup(regime, k_t) + 2 asin(sech W2)
/// (the separatrix piece's distance to its limit direction beyond W2, in both regimes).
double LoopModelHeadingError(PendulumRegime regime, double k_t, double core_half_width);

/// The heading error per unit length of the real paths of a box against their model (same regime):
/// D gets ForBox(box) * L_max. In general the family's eps plus the model core's own gap (Family).
/// When every path of the box stays within one core, |v| <= V = b_max max(|t0|, |L - t0|) from
/// core 0's centre with V <= min(W2, K(k_t)), no run replaces the separatrix and the elastica is
/// far closer to it than at the cell's edge: then min(the growing side of the gap at V, G_t) plus
/// the core's gap (a slow path is a short piece of one loop).
class LoopHeadingError {
 public:
  LoopHeadingError(PendulumRegime regime, double k_t, double core_half_width);
  double Family() const { return family_; }
  double ForBox(const CertifyBox& box) const;

 private:
  PendulumRegime regime_;
  double k_t_, v_one_core_, gap_sup_, core_gap_, family_;
};

/// The half-width W2 (in v) that makes 2 asin(sech W2) equal to the gap G_t, capped at K(k_t)
/// (the cores must lie inside their cells).
double LoopCoreHalfWidthFor(PendulumRegime regime, double k_t);

/// The model's rolling Q(0, L) and chord in the model frame (run direction pi): sense = sigma_0 of
/// core 0 (+1 or -1). Requires b > 0, r >= 0, L > 0.
struct LoopModelRolling {
  Eigen::Matrix3d rolling = Eigen::Matrix3d::Identity();
  Eigen::Vector2d chord = Eigen::Vector2d::Zero();
};
LoopModelRolling RollLoopModel(PendulumRegime regime, int sense, double core_half_width, const CertifyPoint& x);

/// The free-length residual of a model point (the definition of EvaluateCertifyResidual: the
/// rotation trick on the model's rolling and chord). False for an inadmissible point.
bool EvaluateLoopModelResidual(const CertifyTarget& target,
                               PendulumRegime regime,
                               int sense,
                               double core_half_width,
                               const CertifyPoint& x,
                               CertifyResidual* out);

/// Bound D on the rotation distance of Q(0, L) and on the chord distance between any model point
/// of the box (same regime and sense) and the box centre: 2 |dt0| (a shift along the path) +
/// sum over the cores that can meet [0, L] of (8 Catalan |d(1/b)| + 2 pi |dc_j|) with
/// c_j - c_m moving by (j - m) dP, dP = dr + 2 W2 d(1/b) (m the anchor core), capped at 2 L, + |dL|.
/// `shares` (optional) receives each axis's part (for choosing the axis to split).
double LoopModelDeviationBound(double core_half_width, const CertifyBox& box, CertifyPoint* shares = nullptr);

/// The model point of a real elastica path of length L (k < 1): b = |rate|, r = (2K - 2 W2) / b,
/// t0 the first core centre with t0 >= -W2 / b, and its sense. For the tests and the notes.
struct LoopModelPoint {
  int sense = 1;
  CertifyPoint x{};
};
LoopModelPoint LoopModelOf(const Elastica& e, double length, double core_half_width);

/// A model point with a run longer than run_cap (>= its length L) written with run_cap: at most one
/// core meets [0, L], kept in place (t0 <= L + W2/b) or moved to t0 = L + W2/b (none meets it).
LoopModelPoint CapLoopRun(const LoopModelPoint& point, double run_cap, double core_half_width);

/// True when no path needs the box: every path's capped model point (CapLoopRun) has t0 in
/// [-W2/b, r + W2/b] and r >= min(run_min_k / b, run_cap), run_min_k = 2 (K(k_t) - W2); a box
/// entirely outside that set is dropped.
bool LoopBoxOutsideDomain(double core_half_width, double run_min_k, double run_cap, const CertifyBox& box);

struct LoopFamilyOptions {
  PendulumRegime regime = PendulumRegime::kRotating;
  double k_t = 1.0 - 1e-4;       // the family covers k in [k_t, 1)
  double core_half_width = 0.0;  // W2 in v; 0: LoopCoreHalfWidthFor(regime, k_t)
  double rate_lo = 0.5;          // a_lo: |rate| in [rate_lo, rate_max]
  double rate_max = 30.0;        // A
  double length_lo = 0.0;        // L in [length_lo, cap]
  double cap = 1.0;
  long max_boxes = 1000000;        // over both senses
  double accept_deviation = 1e-3;  // a box whose model part of D is below this is undecided, not split
  int keep_undecided = 16;
  double margin = 1e-7;          // on the centre residual
  CertifyInterrupt interrupted;  // if set: asked every kInterruptPollBoxes boxes (kInterrupted)
  std::string Validate() const;
};

using LoopFamilyStatus = ExclusionStatus;  // ToString in certify/bisection.h

struct LoopFamilyResult {
  LoopFamilyStatus status = LoopFamilyStatus::kNotRun;
  double core_half_width = 0.0;  // W2
  double heading_error = 0.0;    // eps (+ the core's own gap): D gets (this) * L (LoopHeadingError::Family)
  CertifyBox window;             // (rate, run, phase, length), searched once per sense
  long boxes = 0;
  long excluded_by_chord = 0, excluded_by_rotation = 0;
  long outside_domain = 0;  // boxes no path needs (LoopBoxOutsideDomain)
  long undecided = 0;
  std::vector<CertifyBox> undecided_boxes;  // the first keep_undecided
  std::vector<int> undecided_senses;        // their senses
  double resolved_volume = 0.0;             // fraction of the two windows excluded
  std::string message;
  bool Excluded() const { return status == LoopFamilyStatus::kExcluded; }
};

/// kExcluded: no solution with k in [k_t, 1), rate_lo <= |rate| <= rate_max and length in
/// [length_lo, cap] (rigorous up to `margin` on the centre residuals).
LoopFamilyResult CertifyLoopFamily(const CertifyTarget& target, const LoopFamilyOptions& options);

}  // namespace plateball::internal
