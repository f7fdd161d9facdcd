// Error bounds of the impulsive approximation (section 2.3): Lemmas 2.3-2.4, Theorems 2.5 and
// 2.6, Corollaries 2 and 3, with the constants estimated from the path and the dynamics.
//
// Per segment (docs/paper_notes.md, "Error bound constants"): Lemma 2.2 gives
//   ||R_1(b) - R_0(b)|| <= int_0^1 int_a^b |d p_nu/d nu| |d p_nu/d tau| dtau dnu
// for the deformation p_nu = p + nu (chord - p). With |chord - p| <= (tau - a)(b - tau)/2 max|p''|
// and |d p_nu/d tau| <= max|p'| this is <= max|p'| max|p''| h^3 / 12 (the a-posteriori term), and
// the paper's looser constant is Kbar_p = K_p M'_p with K_p = max|p''|, M'_p = max|p'|. The same
// lemma on each free arc x(t), t in [t_k, t_k+1], against its chord gives
// ||S_k - Rtilde_k|| <= max|x'| max|x''| (t_k+1 - t_k)^3 / 12, and the paper's Ktilde = max|x''| max|x'|.
#pragma once

#include <string>
#include <vector>

#include "plateball/export.h"
#include "plateball/path.h"

namespace plateball PLATEBALL_EXPORT {

/// The constants of Lemmas 2.1-2.4 and Theorems 2.5-2.6, estimated over one plan.
struct ErrorBoundConstants {
  double K_p = 0.0;        ///< max |p''| (Lemma 2.3: |p - p_ab| <= K_p |b - a|^2)
  double M_prime_p = 0.0;  ///< max |d p_nu / d tau| <= max |p'| (Lemma 2.4)
  double K_bar_p = 0.0;    ///< K_p M'_p (Lemma 2.4, Theorem 2.5)
  double C_p = 0.0;        ///< max (tau_k+1 - tau_k) / |p(tau_k+1) - p(tau_k)| (Corollary 1)
  double M_prime = 0.0;    ///< max |x'| over the free arcs
  double K_10 = 0.0;       ///< max |x''| / 2 over the free arcs (bound of the Taylor remainder c(t, s))
  double K_tilde = 0.0;    ///< 2 K_(1,0) M' = max|x''| max|x'| (Theorem 2.6)
  double K1 = 0.0;         ///< max t_k / |p(tau_k+1) - p(tau_k)| over the plan (Lemma 2.1)
  double D_p = 0.0;        ///< max |p'|: |p(tau_k) - p(tau_k+1)| <= D_p |tau_k - tau_k+1|
  /// Ktilde (K1 D_p)^3. The paper writes Ktilde K1 D_p; the cube is right (docs/paper_notes.md).
  double K_tilde_p = 0.0;
};

/// Bounds on ||A(T) - A_n|| reported by a plan (initial error 0).
struct ErrorBounds {
  ErrorBoundConstants constants;
  double sum_dtau_cubed = 0.0;     ///< sum_k |tau_k+1 - tau_k|^3
  double parameter_norm = 0.0;     ///< ||P||_[0,T] (max over pieces)
  int segments = 0;                ///< n (all pieces)
  double theorem_2_5 = 0.0;        ///< Kbar_p sum dtau^3: polyline vs planned path
  double corollary_2 = 0.0;        ///< Kbar_p n ||P||^3
  double theorem_2_6 = 0.0;        ///< (Kbar_p + Ktilde_p) sum dtau^3: impulsive vs planned
  double corollary_3 = 0.0;        ///< (Kbar_p + Ktilde_p) n ||P||^3
  double a_posteriori_path = 0.0;  ///< sum_k max|p'| max|p''| h_k^3 / 12 (polyline vs path)
  double a_posteriori_arcs = 0.0;  ///< sum_k max|x'| max|x''| dt_k^3 / 12 (arcs vs polyline)
  double a_posteriori = 0.0;       ///< the sum of both: the bound the planner reports

  /// One line: the status, the message and the main numbers.
  std::string BriefReport() const;
};

/// max |p'| and max |p''| of a curve over [a, b]: on lines (|v|, 0) and circles (rho, rho) the
/// constants themselves; on the other curves from `samples` >= 2 equally spaced values plus the
/// largest difference between neighbouring samples (so that a maximum between samples is covered
/// for smooth data).
struct CurveDerivativeBounds {
  double max_speed = 0.0;
  double max_acceleration = 0.0;
};
/// The bounds of CurveDerivativeBounds for `curve` on [a, b] (see above).
CurveDerivativeBounds EstimateCurveDerivativeBounds(const SmoothCurve& curve, double a, double b, int samples = 9);

/// Lemma 2.4 per segment: ||R - S|| <= max|p'| max|p''| h^3 / 12.
inline double SegmentBound(double max_speed, double max_acceleration, double h) {
  return max_speed * max_acceleration * h * h * h / 12.0;
}

/// The paper's bound formulas, as pure functions of the constants (section 2.3).
/// Lemma 2.4 / Theorem 2.5 constant: Kbar_p = K_p M'_p.
double KBarP(double K_p, double M_prime_p);
/// Theorem 2.6 constant: Ktilde = 2 K_(1,0) M' (= max|x''| max|x'|).
double KTilde(double K_10, double M_prime);
/// Theorem 2.6 constant Ktilde_p = Ktilde (K^1 D_p)^3 (the paper prints Ktilde K^1 D_p; the cube is
/// right, docs/paper_notes.md).
double KTildeP(double K_tilde, double K1, double D_p);
/// Theorem 2.5: ||A(T) - A_n(polyline)|| <= Kbar_p sum_k |tau_k+1 - tau_k|^3.
double Theorem25Bound(double K_bar_p, double sum_dtau_cubed);
/// Corollary 2: ||A(T) - A_n(polyline)|| <= Kbar_p n ||P||^3.
double Corollary2Bound(double K_bar_p, int n, double parameter_norm);
/// Theorem 2.6: ||A(T) - A_n(impulsive)|| <= (Kbar_p + Ktilde_p) sum_k |tau_k+1 - tau_k|^3.
double Theorem26Bound(double K_bar_p, double K_tilde_p, double sum_dtau_cubed);
/// Corollary 3: ||A(T) - A_n(impulsive)|| <= (Kbar_p + Ktilde_p) n ||P||^3.
double Corollary3Bound(double K_bar_p, double K_tilde_p, int n, double parameter_norm);

/// What one segment of a plan contributes to the bounds: the parameter step h = tau_k+1 - tau_k,
/// the chord |p(tau_k+1) - p(tau_k)|, the path's derivative maxima over the segment, and the
/// free arc's duration and derivative maxima.
struct SegmentMeasures {
  double h = 0.0;
  double chord = 0.0;
  CurveDerivativeBounds path;
  double arc_time = 0.0;
  double arc_max_speed = 0.0;
  double arc_max_acceleration = 0.0;
};
/// Adds one segment to the sums (sum h^3, the a-posteriori terms of Corollaries 2/3's
/// per-segment form) and to the maxima (K_p, M'_p, C_p, M', K_(1,0), K^1, ||P||).
void AccumulateSegment(const SegmentMeasures& m, ErrorBounds* b);
/// The derived constants (Kbar_p, D_p = M'_p, Ktilde, Ktilde_p) and every bound of a plan of n
/// segments from the accumulated sums and maxima.
void CompleteBounds(int n, ErrorBounds* b);

}  // namespace PLATEBALL_EXPORT
