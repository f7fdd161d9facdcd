// Internal: the first-order part of the window certificate (docs/paper_notes.md,
// "General targets: the residual's Jacobian for a first-order certificate"): the free-length
// residual as a smooth 4-vector
//   F(rate, k, phase, L) = ( |chord| - |x1 - x0|,  Log(target^T B Q(0, L) B^T) ),
// B = RotationZ(goal_angle - arg chord) the chord turn of rotation_trick.h, its Jacobian at a
// point from the variation of the rolling (closed-form heading derivatives, one quadrature along
// the path), and a Newton refinement. The residual's NORM is the one of certify/vocabulary.h.
#pragma once

#include <Eigen/Core>
#include <string>
#include <vector>

#include "certify/vocabulary.h"

namespace plateball::internal {

/// The pendulum angle theta (= the heading at heading_w = pi/2) and its derivatives in
/// v = rate s + u0 and in the modulus k at fixed v: oscillating sin(theta / 2) = k sn(v),
/// d theta/dv = 2 k cn, d theta/dk = 2 (sn + k cn d am/dk) / dn; rotating theta = 2 am(v),
/// d theta/dv = 2 dn, d theta/dk = 2 d am/dk; d am/dk = k (sn cn - dn int_0^v cn^2) / k'^2.
struct HeadingDerivatives {
  double theta = 0.0, dv = 0.0, dk = 0.0;
};
/// For 0 <= k < 1 and finite v. Accurate to ~1e-13 (1 + |v|) / k'^3 (below k = 1e-3 a series
/// for int cn^2 adds k^3 |v|).
HeadingDerivatives HeadingDerivativesAt(PendulumRegime regime, double k, double v);

/// The quadrature of the Jacobian's path integrals: 4-point Gauss-Legendre on `steps` equal
/// steps <= max_step of [0, length]; nodes in increasing order.
struct CertifyQuadrature {
  int steps = 0;
  double step = 0.0;
  std::vector<double> nodes, weights;
};
CertifyQuadrature CertifyQuadratureAlong(double length, double max_step);

/// HeadingDerivativesAt at v = rate s + phase for every node s of `quad`, with Jacobi's epsilon
/// E(am v) carried from node to node by the addition theorem
/// E(u + w) = E(u) + E(w) - k^2 sn(u) sn(w) sn(u + w): one incomplete integral per gap length
/// (four in all) and a restart every 64 nodes, instead of one per node. Agrees with
/// HeadingDerivativesAt to ~1e-13 (1 + |v|) / k'^3.
std::vector<HeadingDerivatives> HeadingDerivativesAtNodes(
    PendulumRegime regime, double k, double rate, double phase, const CertifyQuadrature& quad);

/// F and dF/dx at one parameter point x = (rate, k, phase, L) (columns in CertifyAxis order).
struct CertifyJacobian {
  Eigen::Vector4d residual = Eigen::Vector4d::Zero();  // (chord miss, rotation vector)
  Eigen::Matrix4d jacobian = Eigen::Matrix4d::Zero();
  double chord_norm = 0.0;  // |chord| at the point
};

/// The residual from the closed-form rolling (as EvaluateCertifyResidual; CertifyResidualError) and
/// its Jacobian: the length column in closed form (dQ/dL = hat(w(L)) Q), the rate, modulus and
/// phase columns from dQ(L) = Q(L) hat(-int_0^L theta_p(s) Q(s)^T t(s) ds) and
/// d chord = int theta_p(s) n(s) ds by 4-point Gauss-Legendre on steps <= CertifyJacobianStep
/// (the rolling inside them by a sixth-order Magnus table on the same steps); the Log map
/// by the inverse right Jacobian of SO(3). False for an inadmissible point (k outside [0, 1),
/// L <= 0, a degenerate chord, non-finite values, a rotation residual within 1e-6 of pi).
bool EvaluateCertifyJacobian(
    const CertifyTarget& target, PendulumRegime regime, const CertifyPoint& x, double max_step, CertifyJacobian* out);

/// The arc of the pendulum argument v = rate s + u0 that one quadrature or Magnus step of
/// EvaluateCertifyJacobian may cover: the heading's derivatives in s scale with |rate|, so a step
/// of fixed length loses its accuracy at high rates (max_step 0.05 alone: residual error 5e-8 at
/// rate 10, Jacobian error 8e-4 of its column at rate 26).
inline constexpr double kJacobianArcStep = 0.1;
/// min(max_step, kJacobianArcStep / |rate|): the step EvaluateCertifyJacobian takes.
double CertifyJacobianStep(double max_step, double rate);

/// A bound on the floating-point error of each component of EvaluateCertifyJacobian's residual
/// (the closed-form chord and rolling) at any point of `box`:
/// 1e-13 (1 + L_max (1 + |rate|_max)). Measured errors against Magnus tables at steps of 0.005 /
/// |rate| reach 0.10 of it up to rate 80 and length 60, k' down to 4e-5 (tests; mostly the
/// tables' own rounding).
double CertifyResidualError(const CertifyBox& box);

/// Newton's method on F from x (at most max_iterations steps, k kept >= 0); true when |F| (max
/// norm) drops below tolerance. x receives the last iterate.
bool NewtonRefineCertify(const CertifyTarget& target,
                         PendulumRegime regime,
                         double max_step,
                         double tolerance,
                         int max_iterations,
                         CertifyPoint* x);

/// Bounds on |d2 theta/dv2|, |d2 theta/dv dk|, |d2 theta/dk2| (k at fixed v) over moduli in
/// [0, k_max] and |v| <= v_max (k_max < 1); each increasing in k_max and v_max (derived in the
/// notes from d am/dk = k (sn cn - dn int cn^2) / k'^2).
struct HeadingSecondBounds {
  double vv = 0.0, vk = 0.0, kk = 0.0;
};
HeadingSecondBounds HeadingSecondDerivativeBounds(PendulumRegime regime, double k_max, double v_max);

/// The enclosure's end terms, over the box's parameters x and its lengths s in [L_lo, L_max]
/// (0 <= k_max < 1): dk >= |d theta/dk (s; x)| at fixed v = rate s + u0, and deviation >=
/// min(|theta(s; x) - theta(s; c)|, 2), c = box.Centre() (the heading's change over the box at
/// the path's end; 2 also bounds the tangent's).
struct EndHeadingBounds {
  double dk = 0.0, deviation = 0.0;
};
EndHeadingBounds EndHeadingBoundsOf(PendulumRegime regime, const CertifyBox& box);

/// Relative floating-point error allowed on a column of the centre's Jacobian: the enclosure adds
/// kJacobianMargin (1 + |column|_max) to every entry (tests: measured error ~3e-9).
inline constexpr double kJacobianMargin = 1e-6;

/// Entrywise radius E with |J(x) - J_centre| <= E for every x of the box, J_centre the Jacobian
/// EvaluateCertifyJacobian computed at box.Centre() (its floating-point error included). False
/// when no enclosure is available: the chord may vanish in the box, the rotation residual may
/// exceed 2.5 rad, or k_max >= 1.
bool CertifyJacobianEnclosure(PendulumRegime regime,
                              const CertifyBox& box,
                              const CertifyJacobian& centre,
                              double margin,
                              Eigen::Matrix4d* radius);

/// Whether CertifyJacobianEnclosure can succeed over `box` for a centre with this chord length
/// and rotation residual angle (its requirements Dev < |chord| - margin and r_max <= 2.5, with
/// 1e-9 of slack so that it never refuses a box the enclosure accepts): a cheap check before the
/// centre's Jacobian is computed (the zeroth-order residual gives both numbers).
bool CertifyEnclosureAvailable(
    PendulumRegime regime, const CertifyBox& box, double chord_norm, double rotation, double margin);

enum class FirstOrderVerdict { kNotRun, kExcluded, kUnique, kUndecided };
std::string ToString(FirstOrderVerdict verdict);

/// First-order tests of a box from its centre's residual and Jacobian (residual error <= margin
/// per component) and the enclosure `radius`: kExcluded when 0 is outside F(c) + J(X)(X - c)
/// componentwise or the Krawczyk image K(X) = c - A F(c) + (I - A J(X))(X - c) (A = J_c^-1) is
/// disjoint from X; kUnique when K(X) lies inside the interior of X (exactly one solution in X).
FirstOrderVerdict FirstOrderTest(const CertifyBox& box,
                                 const CertifyJacobian& centre,
                                 const Eigen::Matrix4d& radius,
                                 double margin);

/// The standard remedy for a solution on a face shared by two boxes of a subdivision (it lies in
/// the interior of neither, so Krawczyk proves it in neither): when the Newton step from the
/// centre lands near `box` (within twice its half-widths of its centre), Newton's method (at most 8
/// steps, |F| < 1e-11); if it converges to a point near the box, the first-order tests on the box of the same
/// half-widths centred at that point (the solution now in its interior). True when that box is proved to hold exactly
/// one solution: *proved receives the box, *solution the Newton point.
bool ProveAroundNewtonPoint(const CertifyTarget& target,
                            PendulumRegime regime,
                            const CertifyBox& box,
                            const CertifyJacobian& centre,
                            double max_step,
                            double margin,
                            CertifyBox* proved,
                            CertifyPoint* solution);

}  // namespace plateball::internal
