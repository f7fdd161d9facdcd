#include "isoparallel_certify_jacobian.h"

#include <boost/math/special_functions/ellint_1.hpp>
#include <boost/math/special_functions/ellint_2.hpp>
#include <Eigen/LU>
#include <algorithm>
#include <cmath>

#include "elastica_rolling.h"
#include "jacobi_elliptic.h"
#include "plateball/so3.h"
#include "rotation_trick.h"

namespace plateball::internal {

namespace {

// 4-point Gauss-Legendre on [-1, 1].
constexpr double kNodes[4] = {-0.8611363115940526, -0.3399810435848563, 0.3399810435848563, 0.8611363115940526};
constexpr double kWeights[4] = {0.3478548451374538, 0.6521451548625461, 0.6521451548625461, 0.3478548451374538};

// Inverse right Jacobian of SO(3): for M = Exp(phi), dM = M hat(eta) gives dphi = JrInv(phi) eta.
Eigen::Matrix3d InverseRightJacobian(const Eigen::Vector3d& phi) {
  const double a = phi.norm();
  const Eigen::Matrix3d h = Hat(phi);
  const double c = a < 1e-4 ? 1.0 / 12.0 + a * a / 720.0
                            : 1.0 / (a * a) - (1.0 + std::cos(a)) / (2.0 * a * std::sin(a));
  return Eigen::Matrix3d::Identity() + 0.5 * h + c * h * h;
}

// Variation of the path and of its rolling with one parameter: d chord and xi, dQ(L) = Q(L) hat(xi).
struct PathVariation {
  Eigen::Vector2d chord = Eigen::Vector2d::Zero();
  Eigen::Vector3d xi = Eigen::Vector3d::Zero();
};

// The rate, modulus and phase columns of the path's variation (quadrature along [0, L]).
void IntegrateVariations(PendulumRegime regime, const CertifyPoint& x, const Elastica& e,
                         const ElasticaRollingTable& table, double max_step, PathVariation* var) {
  const double length = x[kCertifyLength];
  const int steps = std::max(1, static_cast<int>(std::ceil(length / max_step)));
  const double h = length / steps;
  for (int i = 0; i < steps; ++i) {
    for (int j = 0; j < 4; ++j) {
      const double s = h * (i + 0.5 * (1.0 + kNodes[j])), w = 0.5 * h * kWeights[j];
      const HeadingDerivatives d =
          HeadingDerivativesAt(regime, x[kCertifyModulus], x[kCertifyRate] * s + x[kCertifyPhase]);
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
}

}  // namespace

HeadingDerivatives HeadingDerivativesAt(PendulumRegime regime, double k, double v) {
  const double kk = boost::math::ellint_1(k);
  const double m = std::round(v / (2.0 * kk));
  const double r = v - 2.0 * kk * m;  // |r| <= K; sn, cn change sign with each 2K, dn does not
  double sn = 0, cn = 0, dn = 0;
  JacobiSnCnDn(r, k, &sn, &cn, &dn);
  const double amp = m * M_PI + std::atan2(sn, cn);
  const double sign = std::fmod(m, 2.0) == 0.0 ? 1.0 : -1.0;
  sn *= sign;
  cn *= sign;
  const double kp2 = (1.0 - k) * (1.0 + k);
  // int_0^v cn^2 = (E(am v) - k'^2 v) / k^2; below k = 1e-3 its k = 0 value v/2 + sin(2 am)/4.
  const double cn2 = k < 1e-3 ? 0.5 * v + 0.25 * std::sin(2.0 * amp)
                              : (boost::math::ellint_2(k, amp) - kp2 * v) / (k * k);
  const double am_k = k * (sn * cn - dn * cn2) / kp2;
  HeadingDerivatives out;
  if (regime == PendulumRegime::kRotating) {
    out.theta = 2.0 * amp;
    out.dv = 2.0 * dn;
    out.dk = 2.0 * am_k;
  } else {
    out.theta = 2.0 * std::asin(std::clamp(k * sn, -1.0, 1.0));
    out.dv = 2.0 * k * cn;
    out.dk = 2.0 * (sn + k * cn * am_k) / dn;
  }
  return out;
}

bool EvaluateCertifyJacobian(const CertifyTarget& target, PendulumRegime regime, const CertifyPoint& x,
                             double max_step, CertifyJacobian* out) {
  const double length = x[kCertifyLength];
  for (double c : x)
    if (!std::isfinite(c)) return false;
  if (!(x[kCertifyModulus] >= 0.0 && x[kCertifyModulus] < 1.0) || !(length > 0.0) || !(max_step > 0.0)) return false;
  const Elastica e = CertifyElastica(regime, x);
  const ElasticaRollingTable table(e, length, 32, max_step);
  if (!table.Valid()) return false;
  const Eigen::Vector2d chord = e.Position(length);
  const double norm = chord.norm();
  if (!(norm > 1e-12)) return false;
  const Eigen::Matrix3d q = table.Rolling(length);
  const double beta = ChordTurn(target.goal_angle, chord);
  const Eigen::Matrix3d b = RotationZ(beta);
  const Eigen::Matrix3d p = b * q * b.transpose();
  const Eigen::Vector3d r = RotationTrickResidual(target.target, beta, q);
  if (!(r.allFinite() && r.norm() < M_PI - 1e-6)) return false;
  PathVariation var[4];
  IntegrateVariations(regime, x, e, table, max_step, var);
  const Eigen::Vector2d t = e.Tangent(length);
  var[kCertifyLength].chord = t;
  var[kCertifyLength].xi = q.transpose() * Eigen::Vector3d(-t.y(), t.x(), 0.0);  // w(L) = e3 x t(L)
  const Eigen::Matrix3d jr_inv = InverseRightJacobian(r);
  const Eigen::Vector3d e3 = Eigen::Vector3d::UnitZ();
  const Eigen::Vector3d tilt = p.transpose() * e3 - e3;
  out->residual << norm - target.radius, r;
  for (int c = 0; c < 4; ++c) {
    const Eigen::Vector2d& dc = var[c].chord;
    const double dbeta = -(chord.x() * dc.y() - chord.y() * dc.x()) / (norm * norm);
    // d(B Q B^T) = P hat(B xi + dbeta (P^T e3 - e3)); d Log(M) = JrInv(r) eta for dM = M hat(eta).
    out->jacobian(0, c) = chord.dot(dc) / norm;
    out->jacobian.block<3, 1>(1, c) = jr_inv * (b * var[c].xi + dbeta * tilt);
  }
  return out->residual.allFinite() && out->jacobian.allFinite();
}

bool NewtonRefineCertify(const CertifyTarget& target, PendulumRegime regime, double max_step, double tolerance,
                         int max_iterations, CertifyPoint* x) {
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

}  // namespace plateball::internal
