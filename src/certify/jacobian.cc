#include "certify/jacobian.h"

#include <Eigen/LU>
#include <algorithm>
#include <boost/math/special_functions/ellint_2.hpp>
#include <cmath>
#include <vector>

#include "elastica_closed_rolling.h"
#include "elastica_rolling.h"
#include "jacobi_elliptic.h"
#include "plateball/so3.h"
#include "rotation_trick.h"

namespace plateball::internal {

namespace {

// 4-point Gauss-Legendre on [-1, 1].
constexpr double kNodes[4] = {-0.8611363115940526, -0.3399810435848563, 0.3399810435848563, 0.8611363115940526};
constexpr double kWeights[4] = {0.3478548451374538, 0.6521451548625461, 0.6521451548625461, 0.3478548451374538};

double JrInvCoefficient(double a);

// Inverse right Jacobian of SO(3): for M = Exp(phi), dM = M hat(eta) gives dphi = JrInv(phi) eta.
Eigen::Matrix3d InverseRightJacobian(const Eigen::Vector3d& phi) {
  const double a = phi.norm();
  const Eigen::Matrix3d h = Hat(phi);
  return Eigen::Matrix3d::Identity() + 0.5 * h + JrInvCoefficient(a) * h * h;
}

// Variation of the path and of its rolling with one parameter: d chord and xi, dQ(L) = Q(L) hat(xi).
struct PathVariation {
  Eigen::Vector2d chord = Eigen::Vector2d::Zero();
  Eigen::Vector3d xi = Eigen::Vector3d::Zero();
};

// The rate, modulus and phase columns of the path's variation (quadrature along [0, L]).
void IntegrateVariations(PendulumRegime regime,
                         const CertifyPoint& x,
                         const Elastica& e,
                         const ElasticaRollingTable& table,
                         double max_step,
                         PathVariation* var) {
  const CertifyQuadrature quad = CertifyQuadratureAlong(x[kCertifyLength], max_step);
  const std::vector<HeadingDerivatives> heading =
      HeadingDerivativesAtNodes(regime, x[kCertifyModulus], x[kCertifyRate], x[kCertifyPhase], quad);
  for (size_t i = 0; i < quad.nodes.size(); ++i) {
    const double s = quad.nodes[i], w = quad.weights[i];
    const HeadingDerivatives& d = heading[i];
    const Eigen::Vector2d t = e.Tangent(s);
    const Eigen::Vector2d n(-t.y(), t.x());
    const Eigen::Vector3d qt = table.Rolling(s).transpose() * Eigen::Vector3d(t.x(), t.y(), 0.0);
    const double dtheta[3] = {s * d.dv, d.dk, d.dv};  // rate, modulus, phase
    for (int p = 0; p < 3; ++p) {
      var[p].chord += w * dtheta[p] * n;  // d t = d theta n
      var[p].xi -= w * dtheta[p] * qt;    // d w = e3 x d t = -d theta t
    }
  }
}

// sn, cn, dn at v and the unwrapped amplitude am v (reduced modulo 2K: sn, cn change sign).
struct JacobiPoint {
  double sn = 0.0, cn = 1.0, dn = 1.0, amp = 0.0;
};

JacobiPoint JacobiUnwrapped(const JacobiAgm& agm, double kk, double v) {
  const double m = std::round(v / (2.0 * kk));
  const double r = v - 2.0 * kk * m;  // |r| <= K; sn, cn change sign with each 2K, dn does not
  JacobiPoint j;
  JacobiSnCnDn(r, agm, &j.sn, &j.cn, &j.dn);
  j.amp = m * M_PI + std::atan2(j.sn, j.cn);
  const double sign = std::fmod(m, 2.0) == 0.0 ? 1.0 : -1.0;
  j.sn *= sign;
  j.cn *= sign;
  return j;
}

// The heading and its derivatives from sn, cn, dn, am at v and Jacobi's epsilon E(am v) (used
// for k >= 1e-3; below, int_0^v cn^2 takes its k = 0 value v/2 + sin(2 am)/4).
HeadingDerivatives HeadingFrom(PendulumRegime regime, double k, double v, const JacobiPoint& j, double epsilon) {
  const double kp2 = (1.0 - k) * (1.0 + k);
  // int_0^v cn^2 = (E(am v) - k'^2 v) / k^2.
  const double cn2 = k < 1e-3 ? 0.5 * v + 0.25 * std::sin(2.0 * j.amp) : (epsilon - kp2 * v) / (k * k);
  const double am_k = k * (j.sn * j.cn - j.dn * cn2) / kp2;
  HeadingDerivatives out;
  if (regime == PendulumRegime::kRotating) {
    out.theta = 2.0 * j.amp;
    out.dv = 2.0 * j.dn;
    out.dk = 2.0 * am_k;
  } else {
    out.theta = 2.0 * std::asin(std::clamp(k * j.sn, -1.0, 1.0));
    out.dv = 2.0 * k * j.cn;
    out.dk = 2.0 * (j.sn + k * j.cn * am_k) / j.dn;
  }
  return out;
}

double EpsilonAt(double k, const JacobiPoint& j) { return k < 1e-3 ? 0.0 : boost::math::ellint_2(k, j.amp); }

// c(a) of JrInv = I + hat/2 + c hat^2: c = (1 - (a/2) cot(a/2)) / a^2 = 1/12 + a^2/720 + ..., a
// series with positive coefficients: c and c' increase on [0, pi).
double JrInvCoefficient(double a) {
  return a < 1e-4 ? 1.0 / 12.0 + a * a / 720.0 : 1.0 / (a * a) - (1.0 + std::cos(a)) / (2.0 * a * std::sin(a));
}

// ||JrInv(phi)||_2 = (a/2) / sin(a/2), a = |phi| (1 along phi, the same on its normal plane).
double JrInvNorm(double a) { return a < 1e-8 ? 1.0 : 0.5 * a / std::sin(0.5 * a); }

// Sums over [0, L_max] (each piece at the sup of its bounds over the piece: upper bounds of the
// integrals) for the rate, modulus and phase columns.
struct ColumnSums {
  double sup[3] = {};        // >= int |theta_p|: sup |d chord_p|, sup |xi_p|
  double chord[3] = {};      // >= |d chord_p(x) - d chord_p(c)| over [0, L_c]
  double xi[3] = {};         // >= |xi_p(x) - xi_p(c)| over [0, L_c]
  double tail[3] = {};       // sup |theta_p| over [L_lo, L_max] (times the length half-width: the ends)
  double rolling = 0.0;      // >= int min(dg, 2): rotation and chord deviation at fixed length
  double heading_end = 0.0;  // >= min(dg(s), 2) over s in [L_lo, L_max]
};

// min(dg, 2), dg >= |theta(s; x) - theta(s; c)| by the mean value theorem from c to x: |d theta/dk|
// <= mk, |d theta/dv| <= mv, |v_x - v_c| <= s h_rate + h_phase. 2 also bounds |t_x - t_c|.
double HeadingDeviation(const CertifyBox& box, double s, double mk, double mv) {
  const double lin = s * box.HalfWidth(kCertifyRate) + box.HalfWidth(kCertifyPhase);
  return std::min(box.HalfWidth(kCertifyModulus) * mk + lin * mv, 2.0);
}

ColumnSums SumColumnBounds(PendulumRegime regime, const CertifyBox& box) {
  const double k_max = box.hi[kCertifyModulus], l_max = box.hi[kCertifyLength];
  const double hr = box.HalfWidth(kCertifyRate), hk = box.HalfWidth(kCertifyModulus);
  const double hu = box.HalfWidth(kCertifyPhase);
  const double mv = HeadingRateBound(regime, k_max);
  const int pieces = 64;
  const double ds = l_max / pieces;
  ColumnSums out;
  for (int j = 1; j <= pieces; ++j) {
    // The heading bounds grow with |v|: taken at the box's largest |v| over the piece [s - ds, s]
    // (not at s alone: where the phase opposes the rate, |v| falls along the piece).
    const double s = j * ds, v_max = ArgumentBoundOver(box, s - ds, s), lin = s * hr + hu;
    const double mk = HeadingModulusBound(regime, k_max, v_max);
    const HeadingSecondBounds b = HeadingSecondDerivativeBounds(regime, k_max, v_max);
    const double dg = HeadingDeviation(box, s, mk, mv);  // |theta(s; x) - theta(s; c)|, |t_x - t_c|
    const double rolled = out.rolling + dg * ds;         // |Q_x(s) - Q_c(s)|
    const double theta_p[3] = {s * mv, mk, mv};
    const double delta_p[3] = {s * (lin * b.vv + hk * b.vk), lin * b.vk + hk * b.kk, lin * b.vv + hk * b.vk};
    for (int p = 0; p < 3; ++p) {
      out.sup[p] += theta_p[p] * ds;
      out.chord[p] += (delta_p[p] + theta_p[p] * dg) * ds;
      out.xi[p] += (delta_p[p] + theta_p[p] * (rolled + dg)) * ds;
    }
    out.rolling = rolled;
  }
  const EndHeadingBounds ends = EndHeadingBoundsOf(regime, box);
  out.tail[0] = l_max * mv;
  out.tail[1] = ends.dk;
  out.tail[2] = mv;
  out.heading_end = ends.deviation;
  return out;
}

// How far the chord and the rolling move over a box, and what that leaves of the chord and of the
// rotation residual's distance from pi (the enclosure's two requirements).
struct EnclosureGeometry {
  double deviation = 0.0, chord_lo = 0.0, turn = 0.0, chord_min = 0.0, rho = 0.0, r_c = 0.0, r_max = 0.0;
};

bool EnclosureGeometryOf(
    double rolling, double hl, double chord_norm, double rotation, double margin, EnclosureGeometry* g) {
  g->deviation = rolling + hl;  // chord and rolling at the end, lengths included
  g->chord_lo = chord_norm - margin;
  if (!(g->deviation < g->chord_lo)) return false;
  g->turn = std::asin(g->deviation / g->chord_lo);
  g->chord_min = g->chord_lo - g->deviation;
  g->rho = g->deviation + 2.0 * g->turn;  // angle(P_x, P_c), P = B Q B^T; the same for M
  g->r_c = rotation + margin;
  g->r_max = g->r_c + g->rho;
  return g->r_max <= 2.5;
}

bool AdmissibleForEnclosure(const CertifyBox& box) {
  return box.hi[kCertifyModulus] < 1.0 && box.lo[kCertifyModulus] >= 0.0 && box.lo[kCertifyLength] > 0.0;
}

}  // namespace

EndHeadingBounds EndHeadingBoundsOf(PendulumRegime regime, const CertifyBox& box) {
  // The box's lengths [L_lo, L_max] can be wider than a piece of the sums, and |v| can fall along
  // them: the sup over the whole range, at one of its ends (ArgumentBoundOver).
  const double k_max = box.hi[kCertifyModulus], l_max = box.hi[kCertifyLength];
  const double v_end = ArgumentBoundOver(box, std::max(0.0, box.lo[kCertifyLength]), l_max);
  EndHeadingBounds ends;
  ends.dk = HeadingModulusBound(regime, k_max, v_end);
  ends.deviation = HeadingDeviation(box, l_max, ends.dk, HeadingRateBound(regime, k_max));
  return ends;
}

bool CertifyEnclosureAvailable(
    PendulumRegime regime, const CertifyBox& box, double chord_norm, double rotation, double margin) {
  if (!AdmissibleForEnclosure(box)) return false;
  EnclosureGeometry g;
  return EnclosureGeometryOf(
      SumColumnBounds(regime, box).rolling, box.HalfWidth(kCertifyLength), chord_norm, rotation, margin - 1e-9, &g);
}

HeadingDerivatives HeadingDerivativesAt(PendulumRegime regime, double k, double v) {
  const JacobiPoint j = JacobiUnwrapped(JacobiAgm(k), CompleteEllipticK(k), v);
  return HeadingFrom(regime, k, v, j, EpsilonAt(k, j));
}

CertifyQuadrature CertifyQuadratureAlong(double length, double max_step) {
  CertifyQuadrature q;
  q.steps = std::max(1, static_cast<int>(std::ceil(length / max_step)));
  q.step = length / q.steps;
  for (int i = 0; i < q.steps; ++i)
    for (int j = 0; j < 4; ++j) {
      q.nodes.push_back(q.step * (i + 0.5 * (1.0 + kNodes[j])));
      q.weights.push_back(0.5 * q.step * kWeights[j]);
    }
  return q;
}

std::vector<HeadingDerivatives> HeadingDerivativesAtNodes(
    PendulumRegime regime, double k, double rate, double phase, const CertifyQuadrature& quad) {
  const JacobiAgm agm(k);
  const double kk = CompleteEllipticK(k);
  // The four gaps between consecutive nodes (the first across a step's end), their sn and E(am).
  JacobiPoint gap[4];
  double gap_epsilon[4];
  for (int j = 0; j < 4; ++j) {
    const double ds =
        j == 0 ? quad.step * (1.0 + 0.5 * (kNodes[0] - kNodes[3])) : 0.5 * quad.step * (kNodes[j] - kNodes[j - 1]);
    gap[j] = JacobiUnwrapped(agm, kk, rate * ds);
    gap_epsilon[j] = EpsilonAt(k, gap[j]);
  }
  std::vector<HeadingDerivatives> out;
  out.reserve(quad.nodes.size());
  JacobiPoint previous;
  double epsilon = 0.0;
  for (size_t i = 0; i < quad.nodes.size(); ++i) {
    const double v = rate * quad.nodes[i] + phase;
    const JacobiPoint j = JacobiUnwrapped(agm, kk, v);
    const int g = static_cast<int>(i % 4);
    // Addition theorem E(u + w) = E(u) + E(w) - k^2 sn u sn w sn(u + w) (E = E(am .)); restarted
    // from Boost's integral every 64 nodes so that rounding cannot accumulate along long paths.
    epsilon = i % 64 == 0 ? EpsilonAt(k, j) : epsilon + gap_epsilon[g] - k * k * previous.sn * gap[g].sn * j.sn;
    out.push_back(HeadingFrom(regime, k, v, j, epsilon));
    previous = j;
  }
  return out;
}

bool EvaluateCertifyJacobian(
    const CertifyTarget& target, PendulumRegime regime, const CertifyPoint& x, double max_step, CertifyJacobian* out) {
  const double length = x[kCertifyLength];
  for (double c : x)
    if (!std::isfinite(c)) return false;
  if (!(x[kCertifyModulus] >= 0.0 && x[kCertifyModulus] < 1.0) || !(length > 0.0) || !(max_step > 0.0)) return false;
  const Elastica e = CertifyElastica(regime, x);
  const double step = CertifyJacobianStep(max_step, x[kCertifyRate]);
  const ElasticaRollingTable table(e, length, 32, step);
  if (!table.Valid()) return false;
  const Eigen::Vector2d chord = e.Position(length);
  const double norm = chord.norm();
  if (!(norm > 1e-12)) return false;
  const Eigen::Matrix3d q = ElasticaClosedRolling(e).Rolling(length);  // CertifyResidualError
  const double beta = ChordTurn(target.goal_angle, chord);
  const Eigen::Matrix3d b = RotationZ(beta);
  const Eigen::Matrix3d p = b * q * b.transpose();
  const Eigen::Vector3d r = RotationTrickResidual(target.target, beta, q);
  if (!(r.allFinite() && r.norm() < M_PI - 1e-6)) return false;
  PathVariation var[4];
  IntegrateVariations(regime, x, e, table, step, var);
  const Eigen::Vector2d t = e.Tangent(length);
  var[kCertifyLength].chord = t;
  var[kCertifyLength].xi = q.transpose() * Eigen::Vector3d(-t.y(), t.x(), 0.0);  // w(L) = e3 x t(L)
  const Eigen::Matrix3d jr_inv = InverseRightJacobian(r);
  const Eigen::Vector3d e3 = Eigen::Vector3d::UnitZ();
  const Eigen::Vector3d tilt = p.transpose() * e3 - e3;
  out->residual << norm - target.radius, r;
  out->chord_norm = norm;
  for (int c = 0; c < 4; ++c) {
    const Eigen::Vector2d& dc = var[c].chord;
    const double dbeta = -(chord.x() * dc.y() - chord.y() * dc.x()) / (norm * norm);
    // d(B Q B^T) = P hat(B xi + dbeta (P^T e3 - e3)); d Log(M) = JrInv(r) eta for dM = M hat(eta).
    out->jacobian(0, c) = chord.dot(dc) / norm;
    out->jacobian.block<3, 1>(1, c) = jr_inv * (b * var[c].xi + dbeta * tilt);
  }
  return out->residual.allFinite() && out->jacobian.allFinite();
}

double CertifyResidualError(const CertifyBox& box) {
  const double rate_max = std::max(std::abs(box.lo[kCertifyRate]), std::abs(box.hi[kCertifyRate]));
  return 1e-13 * (1.0 + box.hi[kCertifyLength] * (1.0 + rate_max));
}

double CertifyJacobianStep(double max_step, double rate) {
  return std::min(max_step, kJacobianArcStep / std::abs(rate));
}

bool NewtonRefineCertify(const CertifyTarget& target,
                         PendulumRegime regime,
                         double max_step,
                         double tolerance,
                         int max_iterations,
                         CertifyPoint* x) {
  CertifyJacobian f;
  for (int it = 0; it <= max_iterations; ++it) {
    if (!EvaluateCertifyJacobian(target, regime, *x, max_step, &f)) return false;
    if (f.residual.lpNorm<Eigen::Infinity>() < tolerance) return true;
    if (it == max_iterations) break;
    const Eigen::FullPivLU<Eigen::Matrix4d> lu(f.jacobian);
    if (!lu.isInvertible()) return false;
    const Eigen::Vector4d step = lu.solve(f.residual);
    for (int i = 0; i < 4; ++i) (*x)[i] -= step[i];
    (*x)[kCertifyModulus] = std::abs((*x)[kCertifyModulus]);
  }
  return false;
}

HeadingSecondBounds HeadingSecondDerivativeBounds(PendulumRegime regime, double k_max, double v_max) {
  const double k = k_max, v = v_max;
  const double kp2 = (1.0 - k) * (1.0 + k), kp = std::sqrt(kp2);
  const double am_k = k * (0.5 + v) / kp2;                                       // |d am/dk|
  const double dn_k = (k + k * k * am_k) / kp;                                   // |d dn/dk|
  const double g_k = am_k + dn_k * v + k * (v + v * v) / kp2;                    // |d/dk (sn cn - dn I)|
  const double am_kk = (1.0 + k * k) / (kp2 * kp2) * (0.5 + v) + k / kp2 * g_k;  // |d2 am/dk2|
  HeadingSecondBounds b;
  if (regime == PendulumRegime::kRotating) {  // theta = 2 am, d theta/dv = 2 dn
    b.vv = k * k;
    b.vk = 2.0 * dn_k;
    b.kk = 2.0 * am_kk;
  } else {  // d theta/dv = 2 k cn, d theta/dk = 2 (sn + k cn am_k) / dn, dn >= k'
    b.vv = 2.0 * k;
    b.vk = 2.0 + 2.0 * k * am_k;
    b.kk = 2.0 * ((2.0 * am_k + k * am_k * am_k + k * am_kk) / kp + (1.0 + k * am_k) * dn_k / kp2);
  }
  return b;
}

bool CertifyJacobianEnclosure(PendulumRegime regime,
                              const CertifyBox& box,
                              const CertifyJacobian& centre,
                              double margin,
                              Eigen::Matrix4d* radius) {
  if (!AdmissibleForEnclosure(box)) return false;
  const ColumnSums sums = SumColumnBounds(regime, box);
  const double hl = box.HalfWidth(kCertifyLength);
  EnclosureGeometry g;
  if (!EnclosureGeometryOf(sums.rolling, hl, centre.chord_norm, centre.residual.tail<3>().norm(), margin, &g))
    return false;
  const double deviation = g.deviation, chord_lo = g.chord_lo, turn = g.turn, chord_min = g.chord_min;
  const double rho = g.rho, r_c = g.r_c, r_max = g.r_max;
  // JrInv is Lipschitz on |phi| <= r_max: 1/2 + c'(r) r^2 + 2 c(r) r, c' <= its slope to r + 0.01.
  const double slope = (JrInvCoefficient(r_max + 0.01) - JrInvCoefficient(r_max)) / 0.01;
  const double lipschitz = 0.5 + slope * r_max * r_max + 2.0 * JrInvCoefficient(r_max) * r_max;
  const double kappa = std::max(std::abs(box.lo[kCertifyRate]), std::abs(box.hi[kCertifyRate])) *
                       HeadingRateBound(regime, box.hi[kCertifyModulus]);  // sup |curvature|
  for (int c = 0; c < 4; ++c) {
    double sup = 1.0, d_chord, d_xi;  // sup |d chord| (= sup |xi|), and their variations
    if (c == kCertifyLength) {        // d chord = t(L), xi = Q(L)^T n(L)
      d_chord = std::min(sums.heading_end + kappa * hl, 2.0);
      d_xi = deviation + d_chord;
    } else {
      const int p = c == kCertifyRate ? 0 : c == kCertifyModulus ? 1 : 2;
      sup = sums.sup[p];
      d_chord = sums.chord[p] + sums.tail[p] * hl;
      d_xi = sums.xi[p] + sums.tail[p] * hl;
    }
    const double beta_sup = sup / chord_min;  // |d beta| = |u x d chord| / |chord|
    const double d_beta = (turn * sup + d_chord) / chord_min + sup * deviation / (chord_min * chord_lo);
    const double d_eta = turn * sup + d_xi + 2.0 * d_beta + beta_sup * rho;  // eta = B xi + d beta (P^T e3 - e3)
    const double eta_sup = sup + 2.0 * beta_sup;
    const double d_row = lipschitz * rho * JrInvNorm(r_max) * eta_sup + JrInvNorm(r_c) * d_eta;
    const double fp = kJacobianMargin * (1.0 + centre.jacobian.col(c).lpNorm<Eigen::Infinity>());
    (*radius)(0, c) = turn * sup + d_chord + fp;
    for (int i = 1; i < 4; ++i) (*radius)(i, c) = d_row + fp;
  }
  return radius->allFinite();
}

std::string ToString(FirstOrderVerdict verdict) {
  switch (verdict) {
    case FirstOrderVerdict::kNotRun:
      return "not run";
    case FirstOrderVerdict::kExcluded:
      return "excluded";
    case FirstOrderVerdict::kUnique:
      return "unique";
    case FirstOrderVerdict::kUndecided:
      return "undecided";
  }
  return "unknown";
}

FirstOrderVerdict FirstOrderTest(const CertifyBox& box,
                                 const CertifyJacobian& centre,
                                 const Eigen::Matrix4d& radius,
                                 double margin) {
  const CertifyPoint c = box.Centre();
  Eigen::Vector4d h;
  for (int i = 0; i < 4; ++i) h[i] = box.HalfWidth(i);
  const Eigen::Matrix4d jac_abs = centre.jacobian.cwiseAbs() + radius;
  // Mean value form: F(x) in F(c) + J(X)(x - c).
  const Eigen::Vector4d spread = jac_abs * h + Eigen::Vector4d::Constant(margin);
  for (int i = 0; i < 4; ++i)
    if (std::abs(centre.residual[i]) > spread[i] * (1.0 + 1e-12)) return FirstOrderVerdict::kExcluded;
  const Eigen::FullPivLU<Eigen::Matrix4d> lu(centre.jacobian);
  if (!lu.isInvertible()) return FirstOrderVerdict::kUndecided;
  const Eigen::Matrix4d a = lu.inverse();
  const Eigen::Vector4d newton = a * centre.residual;
  const Eigen::Matrix4d contraction =
      (Eigen::Matrix4d::Identity() - a * centre.jacobian).cwiseAbs() + a.cwiseAbs() * radius;
  const Eigen::Vector4d k_radius = a.cwiseAbs() * Eigen::Vector4d::Constant(margin) + contraction * h;
  bool inside = true;
  for (int i = 0; i < 4; ++i) {
    const double mid = c[i] - newton[i];
    const double rad = k_radius[i] + 1e-12 * (std::abs(c[i]) + std::abs(newton[i]) + k_radius[i]) + 1e-300;
    if (mid - rad > box.hi[i] || mid + rad < box.lo[i]) return FirstOrderVerdict::kExcluded;  // K(X) and X disjoint
    inside = inside && mid - rad > box.lo[i] && mid + rad < box.hi[i];
  }
  return inside ? FirstOrderVerdict::kUnique : FirstOrderVerdict::kUndecided;
}

bool ProveAroundNewtonPoint(const CertifyTarget& target,
                            PendulumRegime regime,
                            const CertifyBox& box,
                            const CertifyJacobian& centre,
                            double max_step,
                            double margin,
                            CertifyBox* proved,
                            CertifyPoint* solution) {
  const Eigen::FullPivLU<Eigen::Matrix4d> lu(centre.jacobian);
  if (!lu.isInvertible()) return false;
  const Eigen::Vector4d step = lu.solve(centre.residual);
  const CertifyPoint c = box.Centre();
  CertifyPoint x = c;
  // Near the box: within twice its half-widths of its centre (Newton may stop just outside a face).
  const auto near = [&](const CertifyPoint& y) {
    for (int i = 0; i < 4; ++i)
      if (!(std::abs(y[i] - c[i]) <= 2.0 * box.HalfWidth(i))) return false;
    return true;
  };
  CertifyPoint newton;
  for (int i = 0; i < 4; ++i) newton[i] = c[i] - step[i];
  if (!near(newton) || !NewtonRefineCertify(target, regime, max_step, 1e-11, 8, &x) || !near(x)) return false;
  for (int i = 0; i < 4; ++i) {
    proved->lo[i] = x[i] - box.HalfWidth(i);
    proved->hi[i] = x[i] + box.HalfWidth(i);
  }
  CertifyJacobian at;
  Eigen::Matrix4d radius;
  if (!EvaluateCertifyJacobian(target, regime, proved->Centre(), max_step, &at) ||
      !CertifyJacobianEnclosure(regime, *proved, at, margin, &radius) ||
      FirstOrderTest(*proved, at, radius, margin) != FirstOrderVerdict::kUnique)
    return false;
  *solution = x;
  return true;
}

}  // namespace plateball::internal
