#include "elastica_closed_rolling.h"

#include <Eigen/Geometry>
#include <cmath>

#include "carlson.h"  // Pi by Carlson's R_F and R_J (ThirdKind)
#include "check.h"
#include "plateball/so3.h"

namespace plateball::internal {

ElasticaClosedRolling::ElasticaClosedRolling(const Elastica& e)
    : regime_(e.parameters().regime),
      rate_(e.parameters().rate),
      modulus_(e.parameters().modulus),
      phase_(e.parameters().phase),
      big_g_(e.G()),
      cos_w_(e.cos_w_),  // the Elastica's rotation sin(g_W), -cos(g_W), K (its period) and AGM
      sin_w_(e.sin_w_),  // sequence, computed once
      complete_k_(e.kk_),
      agm_(*e.agm_) {
  if (!(std::abs(rate_) <= kMaxRate))
    ThrowInvalid(
        "rate", rate_, "|rate| must be <= " + FormatNumber(kMaxRate) + " for the closed-form rolling (G, V^2 finite)");
  const bool oscillating = regime_ == PendulumRegime::kOscillating;
  const double k = std::abs(modulus_);
  // G = b^2 (oscillating) or (a k)^2 (rotating); 1 - G as a product, exact near G = 1.
  one_minus_g_ = OneMinusSquare(oscillating ? rate_ : rate_ * k);
  // V^2 = 1 + G^2 + 2E = (1 - G)^2 + 4 b^2 k^2 (oscillating), (1 - G)^2 + 4 a^2 (rotating).
  const double curvature_scale = oscillating ? 2.0 * rate_ * k : 2.0 * rate_;
  norm_v_ = std::hypot(one_minus_g_, curvature_scale);
  straight_ = rate_ == 0.0 || (oscillating && k == 0.0);
  unit_chart_ = std::abs(one_minus_g_) < kUnitChart;
  straight_omega_ = Eigen::Vector3d::Zero();
  if (straight_) {
    const Eigen::Vector2d t = e.Tangent(0.0);
    straight_omega_ = Eigen::Vector3d(-t.y(), t.x(), 0.0);
  }
  // k'^2 = (1 - k)(1 + k), accurate near the separatrix (jacobi_elliptic.h), as the Elastica's.
  const double kc2 = e.kc2_;
  kc2_ = kc2;
  integral_sn2_origin_ = e.i0_;
  if (!straight_ && !unit_chart_) {
    const double kappa2 = oscillating ? k * k : 1.0;
    n_ = -4.0 * big_g_ * kappa2 / (one_minus_g_ * one_minus_g_);
    if (n_ != 0.0) SetUpThirdKind(k * k, kc2);
    twist_factor_ = (1.0 + big_g_) / (one_minus_g_ * rate_);
  }
  CacheOrigin(e);
}

// A&S 17.7.15 (Boost's form of it): for n < 0, N = (k^2 - n)/(1 - n) in (k^2, 1) and
//   Pi(n; phi) = c1 Pi(N; phi) + c2 F(phi) + c3 atan(p2 sin(phi) cos(phi) / Delta(phi)),
//   c1 = (-n/(1 - n)) (k'^2/(k^2 - n)), c2 = k^2/(k^2 - n), c3 = sqrt(-n/((k^2 - n)(1 - n))),
//   p2 = sqrt(-n N): every term >= 0 on [0, pi/2], no cancellation however large -n is.
void ElasticaClosedRolling::SetUpThirdKind(double k2, double kc2) {
  third_.one_minus_n_big = kc2 / (1.0 - n_);
  third_.n_big = 1.0 - third_.one_minus_n_big;
  third_.c1 = (-n_ / (1.0 - n_)) * (kc2 / (k2 - n_));
  third_.c2 = k2 / (k2 - n_);
  third_.c3 = std::sqrt(-n_ / (k2 - n_)) * std::sqrt(1.0 / (1.0 - n_));
  third_.p2 = std::sqrt(-n_) * std::sqrt(third_.n_big);
  // At phi = pi/2: F = K, the atan term vanishes, Pi(N) = K + (N/3) R_J(0, k'^2, 1, 1 - N).
  const double pi_big = complete_k_ + (third_.n_big / 3.0) * CarlsonRJ(0.0, kc2, 1.0, third_.one_minus_n_big);
  complete_pi_ = third_.c1 * pi_big + third_.c2 * complete_k_;
}

// Pi(n; phi, k) from sin(phi), cos(phi) >= 0 and Delta = sqrt(1 - k^2 sin^2 phi) (the Jacobi
// sn, cn, dn of the reduced argument: no 1 - k^2 sin^2 formed), by Carlson's R_F and R_J:
// F = sn R_F(cn^2, dn^2, 1), Pi(N) = F + (N/3) sn^3 R_J(cn^2, dn^2, 1, cn^2 + (1 - N) sn^2).
// R_F and R_J share one duplication loop; p lies in [x, y], so R_J's R_C(1, 1 + e_n) have e_n >= 0.
double ElasticaClosedRolling::ThirdKind(double sn, double cn, double dn) const {
  const double x = cn * cn, y = dn * dn, sn2 = sn * sn;
  const CarlsonFJ fj = CarlsonRFRJ(x, y, 1.0, x + third_.one_minus_n_big * sn2);
  const double f = sn * fj.rf;
  const double pi_big = f + (third_.n_big / 3.0) * sn * sn2 * fj.rj;
  return third_.c1 * pi_big + third_.c2 * f + third_.c3 * std::atan(third_.p2 * sn * cn / dn);
}

// At s = 0 (w = phase) the Elastica has the Jacobi functions already, from the same reduction
// modulo 2K with the same K (its j0_, signs flipped for odd m): unflipped, they give the node.
void ElasticaClosedRolling::CacheOrigin(const Elastica& e) {
  const double m = std::round(phase_ / (2.0 * complete_k_));
  const double sign = IsOddInteger(m) ? -1.0 : 1.0;
  origin_ = NodeFrom(m, sign * e.j0_.sn, sign * e.j0_.cn, e.j0_.dn, true);
  if (!straight_) origin_frame_t_ = FrameAt(origin_).transpose();
}

ElasticaClosedRolling::Node ElasticaClosedRolling::At(double s, const char* field, bool with_pi) const {
  RequireFinite(field, s);
  const double w = rate_ * s + phase_;
  if (!std::isfinite(w)) ThrowInvalid(field, s, "rate * s + phase must be finite");
  const double m = std::round(w / (2.0 * complete_k_));
  const double r = w - 2.0 * complete_k_ * m;  // |r| <= K: cn(r) >= 0
  double sn = 0.0, cn = 1.0, dn = 1.0;
  JacobiSnCnDn(r, agm_, &sn, &cn, &dn);  // finite for every r (sn = r, cn = dn = 1 when tiny)
  return NodeFrom(m, sn, cn, dn, with_pi);
}

ElasticaClosedRolling::Node ElasticaClosedRolling::NodeFrom(
    double m, double sn, double cn, double dn, bool with_pi) const {
  Node j;
  j.m = m;
  j.sn = sn;
  j.cn = cn;
  j.dn = dn;
  // Pi(n; am(r), k), am(r) in [-pi/2, pi/2], needed by the twist when n != 0.
  if (with_pi && n_ != 0.0 && j.sn != 0.0) j.pi = ThirdKind(j.sn, j.cn, j.dn);
  if (IsOddInteger(j.m)) {  // sn(r + 2K) = -sn(r), cn(r + 2K) = -cn(r)
    j.sn = -j.sn;
    j.cn = -j.cn;
  }
  return j;
}

// v = (sin theta, G - cos theta, theta') in the pendulum frame (W along its second axis).
Eigen::Vector3d ElasticaClosedRolling::PendulumCostate(const Node& j) const {
  if (regime_ == PendulumRegime::kOscillating) {  // sin(theta/2) = k sn, cos(theta/2) = dn
    const double h = modulus_ * j.sn;
    return {2.0 * h * j.dn, 2.0 * h * h - one_minus_g_, 2.0 * modulus_ * rate_ * j.cn};
  }
  // theta / 2 = am: sin(theta/2) = sn, cos(theta/2) = cn.
  return {2.0 * j.sn * j.cn, 2.0 * j.sn * j.sn - one_minus_g_, 2.0 * rate_ * j.dn};
}

Eigen::Vector3d ElasticaClosedRolling::Costate(double s) const {
  const Eigen::Vector3d v = PendulumCostate(At(s, "s", false));
  return {cos_w_ * v.x() - sin_w_ * v.y(), sin_w_ * v.x() + cos_w_ * v.y(), v.z()};
}

Eigen::Matrix3d ElasticaClosedRolling::FrameAt(const Node& j) const {
  const Eigen::Vector3d v = PendulumCostate(j);
  const double norm = v.stableNorm();  // no overflow for |rate| up to kMaxRate
  if (!(norm > 0.0)) ThrowInvalid("rate", rate_, "the costate vanishes (straight line with G = 1): no costate frame");
  const Eigen::Vector3d u = v / norm;
  Eigen::Vector2d f;  // f1, horizontal
  if (unit_chart_) {
    // v_h = 2 sin(theta/2) (cos(theta/2), sin(theta/2)): f1 follows theta/2 through v_h = 0.
    f = regime_ == PendulumRegime::kOscillating ? Eigen::Vector2d(-modulus_ * j.sn, j.dn)
                                                : Eigen::Vector2d(-j.sn, j.cn);
  } else {
    f = Eigen::Vector2d(-v.y(), v.x());
  }
  f.stableNormalize();
  const Eigen::Vector3d f1(cos_w_ * f.x() - sin_w_ * f.y(), sin_w_ * f.x() + cos_w_ * f.y(), 0.0);
  const Eigen::Vector3d up(cos_w_ * u.x() - sin_w_ * u.y(), sin_w_ * u.x() + cos_w_ * u.y(), u.z());
  Eigen::Matrix3d frame;
  frame << f1, up.cross(f1), up;
  return frame;
}

Eigen::Matrix3d ElasticaClosedRolling::Frame(double s) const { return FrameAt(At(s, "s", false)); }

double ElasticaClosedRolling::TwistBetween(const Node& a, const Node& b, double ds) const {
  if (norm_v_ == 0.0) ThrowInvalid("rate", rate_, "the costate vanishes (straight line with G = 1): no twist");
  // (1 - G^2) J: zero on the G = 1 chart; (1 + G) / (1 - G) ds when n = 0 (Pi(0; am w) = w).
  double weighted_j = 0.0;
  if (!unit_chart_) {
    if (n_ == 0.0 || straight_) {
      weighted_j = (1.0 + big_g_) / one_minus_g_ * ds;
    } else {
      weighted_j = twist_factor_ * (2.0 * (b.m - a.m) * complete_pi_ + (b.pi - a.pi));
    }
  }
  return -0.5 * norm_v_ * (ds + weighted_j);
}

double ElasticaClosedRolling::Twist(double s) const { return TwistBetween(origin_, At(s, "s", true), s); }

Eigen::Matrix3d ElasticaClosedRolling::Rolling(double s0, double s1) const {
  const Node a = At(s0, "s0", true), b = At(s1, "s1", true);
  if (straight_) return ExpSO3((s1 - s0) * straight_omega_);
  return FrameAt(b) * RotationZ(TwistBetween(a, b, s1 - s0)) * FrameAt(a).transpose();
}

Eigen::Matrix3d ElasticaClosedRolling::Rolling(double s) const { return RollingTo(At(s, "s", true), s); }

Eigen::Matrix3d ElasticaClosedRolling::RollingTo(const Node& b, double s) const {
  if (straight_) return ExpSO3(s * straight_omega_);
  return FrameAt(b) * RotationZ(TwistBetween(origin_, b, s)) * origin_frame_t_;
}

ElasticaClosedRolling::PathEnd ElasticaClosedRolling::Path(const Elastica& e, double s) const {
  RequireFinite("s", s);
  const double w = rate_ * s + phase_;
  if (!std::isfinite(w)) ThrowInvalid("s", s, "rate * s + phase must be finite");
  PathEnd end;
  end.s = s;
  Elastica::Jacobi j{};
  end.chord = e.PositionAt(s, &j, &end.integral_sn2);
  if (std::isnan(end.integral_sn2)) {
    end.node = At(s, "s", true);
  } else {  // Position's reduction modulo 2K is At's (the same m and r): its odd half periods unflipped
    const double m = std::round(w / (2.0 * complete_k_));
    const double sign = IsOddInteger(m) ? -1.0 : 1.0;
    end.node = NodeFrom(m, sign * j.sn, sign * j.cn, j.dn, true);
  }
  end.q = RollingTo(end.node, s);
  return end;
}

// Sensitivity: one direction (drate, dk) of the parameters and what it moves: G, V, n and
// twist_factor_ (G = b^2 oscillating, (a k)^2 rotating; V = hypot(1 - G, 2 b k or 2 a);
// n = -4 G kappa^2 / (1 - G)^2; twist_factor_ = (1 + G) / ((1 - G) rate)).
struct ElasticaClosedRolling::Direction {
  double drate = 0.0, dk = 0.0;
  double dg = 0.0, dv = 0.0, dn = 0.0, dt = 0.0;
};

// A node's Jacobi functions, int_0^w sn^2 (Legendre's D of am w) and whole Pi(n; am w) moved
// along a Direction.
struct ElasticaClosedRolling::NodeDerivative {
  double dsn = 0.0, dcn = 0.0, ddn = 0.0, dintegral = 0.0, dpi_total = 0.0;
};

ElasticaClosedRolling::Direction ElasticaClosedRolling::MakeDirection(double drate, double dk) const {
  const bool oscillating = regime_ == PendulumRegime::kOscillating;
  const double k = modulus_, g = big_g_;
  Direction d;
  d.drate = drate;
  d.dk = dk;
  d.dg = oscillating ? 2.0 * rate_ * drate : 2.0 * rate_ * k * (k * drate + rate_ * dk);
  const double scale = oscillating ? 2.0 * rate_ * k : 2.0 * rate_;
  const double dscale = oscillating ? 2.0 * (k * drate + rate_ * dk) : 2.0 * drate;
  d.dv = (-one_minus_g_ * d.dg + scale * dscale) / norm_v_;
  d.dn = n_ * (d.dg / g + (oscillating ? 2.0 * dk / k : 0.0) + 2.0 * d.dg / one_minus_g_);
  d.dt = twist_factor_ * (d.dg / (1.0 + g) + d.dg / one_minus_g_ - drate / rate_);
  return d;
}

ElasticaClosedRolling::NodeDerivative ElasticaClosedRolling::Differentiate(
    const Node& j, double w, double integral_sn2, double dw, const Direction& d) const {
  const double k = modulus_, k2 = k * k, kc2 = kc2_, sc = j.sn * j.cn;
  // am(w, k) at fixed w: F(am, k) = w, dF/dk = E/(k k'^2) - F/k - k sin cos/(k'^2 Delta) with
  // F = w and E(am w) = w - k^2 D(am w): d am/dk = (k/k'^2)(sn cn - dn (w - D)).
  const double dphi = j.dn * dw + (k / kc2) * (sc - j.dn * (w - integral_sn2)) * d.dk;
  NodeDerivative out;
  out.dsn = j.cn * dphi;
  out.dcn = -j.sn * dphi;
  out.ddn = -(k * j.sn * j.sn * d.dk + k2 * sc * dphi) / j.dn;
  // D(phi, k) = (F - E)/k^2 at fixed phi: dD/dk = (w - (1 + k'^2) D - sn cn/dn)/(k k'^2).
  out.dintegral = j.sn * j.sn / j.dn * dphi + (w - (1.0 + kc2) * integral_sn2 - sc / j.dn) / (k * kc2) * d.dk;
  // Pi(n; phi, k): dPi/dphi = 1/((1 - n sin^2) Delta); dPi/dn and dPi/dk (Byrd and Friedman
  // 733.00, 710.00) in terms of F = w, E and Pi of the same phi (any phi: the whole periods included).
  const double n = n_, e_total = w - k2 * integral_sn2, pi_total = 2.0 * j.m * complete_pi_ + j.pi;
  const double lam = 1.0 - n * j.sn * j.sn;
  const double dpi_dn =
      (e_total + (k2 - n) * w / n + (n * n - k2) * pi_total / n - n * j.dn * sc / lam) / (2.0 * (k2 - n) * (n - 1.0));
  const double dpi_dk = k / (n - k2) * (-e_total / kc2 + pi_total + k2 * sc / (kc2 * j.dn));
  out.dpi_total = dphi / (lam * j.dn) + dpi_dk * d.dk + dpi_dn * d.dn;
  return out;
}

// The costate frame's spin omega, dF = hat(omega) F for F = [f1, f2 = u x f1, u] (the chart off
// G = 1), from the costate's derivative: omega = (f1 x df1 + f2 x df2 + u x du) / 2.
Eigen::Vector3d ElasticaClosedRolling::FrameSpin(const Node& j, const NodeDerivative& dj, const Direction& d) const {
  const Eigen::Vector3d v = PendulumCostate(j);
  Eigen::Vector3d dv;
  if (regime_ == PendulumRegime::kOscillating) {  // v = (2 k sn dn, 2 k^2 sn^2 - (1 - G), 2 k b cn)
    const double k = modulus_, b = rate_;
    dv << 2.0 * (d.dk * j.sn * j.dn + k * dj.dsn * j.dn + k * j.sn * dj.ddn),
        4.0 * k * d.dk * j.sn * j.sn + 4.0 * k * k * j.sn * dj.dsn + d.dg,
        2.0 * (d.dk * b * j.cn + k * d.drate * j.cn + k * b * dj.dcn);
  } else {  // v = (2 sn cn, 2 sn^2 - (1 - G), 2 a dn)
    dv << 2.0 * (dj.dsn * j.cn + j.sn * dj.dcn), 4.0 * j.sn * dj.dsn + d.dg, 2.0 * (d.drate * j.dn + rate_ * dj.ddn);
  }
  const double norm = v.norm(), rho2 = v.x() * v.x() + v.y() * v.y(), rho = std::sqrt(rho2);
  const Eigen::Vector3d u = v / norm, du = (dv - u * u.dot(dv)) / norm;
  const Eigen::Vector3d f1(-v.y() / rho, v.x() / rho, 0.0);
  const Eigen::Vector3d df1 =
      Eigen::Vector3d(-dv.y(), dv.x(), 0.0) / rho - f1 * (v.x() * dv.x() + v.y() * dv.y()) / rho2;
  const Eigen::Vector3d f2 = u.cross(f1), df2 = du.cross(f1) + u.cross(df1);
  const Eigen::Vector3d omega = 0.5 * (f1.cross(df1) + f2.cross(df2) + u.cross(du));  // pendulum frame
  return {cos_w_ * omega.x() - sin_w_ * omega.y(), sin_w_ * omega.x() + cos_w_ * omega.y(), omega.z()};
}

// d(x(s) - x(0)) from the positions' closed forms (Elastica::Position) in the pendulum frame
// (a = origin_, di = int_{u0}^{w} sn^2).
Eigen::Vector2d ElasticaClosedRolling::ChordDerivative(
    const Node& b, const NodeDerivative& da, const NodeDerivative& db, double di, const Direction& d) const {
  const Node& a = origin_;
  const double ddi = db.dintegral - da.dintegral;
  double dx = 0.0, dy = 0.0;
  if (regime_ == PendulumRegime::kOscillating) {  // x = s - 2 k^2 D / b, y = -2 k (cn1 - cn0) / b
    const double k = modulus_, r = rate_, dc = b.cn - a.cn;
    dx = -4.0 * k * d.dk * di / r - 2.0 * k * k * ddi / r + 2.0 * k * k * di * d.drate / (r * r);
    dy = -2.0 * d.dk * dc / r - 2.0 * k * (db.dcn - da.dcn) / r + 2.0 * k * dc * d.drate / (r * r);
  } else {  // x = s - 2 D / a, y = 2 (sn1^2 - sn0^2) / ((dn1 + dn0) a)
    const double r = rate_, p = b.sn * b.sn - a.sn * a.sn, q = b.dn + a.dn, y = 2.0 * p / (q * r);
    dx = -2.0 * ddi / r + 2.0 * di * d.drate / (r * r);
    const double dp = 2.0 * (b.sn * db.dsn - a.sn * da.dsn), dq = db.ddn + da.ddn;
    dy = 2.0 * dp / (q * r) - y * (dq / q + d.drate / r);
  }
  return {cos_w_ * dx - sin_w_ * dy, sin_w_ * dx + cos_w_ * dy};
}

bool ElasticaClosedRolling::Sensitivity(const PathEnd& path, PathSensitivity* out) const {
  const double s = path.s;
  if (straight_ || unit_chart_ || n_ == 0.0 || !(modulus_ >= kSensitivityMinModulus) ||
      !(std::abs(one_minus_g_) >= kSensitivityMinOneMinusG) || !(std::abs(rate_ * s) >= kSensitivityMinArc) ||
      std::isnan(path.integral_sn2))
    return false;
  const double w = rate_ * s + phase_, ia = integral_sn2_origin_, ib = path.integral_sn2;
  const Node &a = origin_, &b = path.node;
  const Eigen::Vector3d u0 = origin_frame_t_.row(2).transpose();  // u(0)
  const double delta_pi = 2.0 * (b.m - a.m) * complete_pi_ + (b.pi - a.pi);
  PathSensitivity result;
  for (int p = 0; p < 2; ++p) {
    const Direction d = MakeDirection(p == 0 ? 1.0 : 0.0, p == 0 ? 0.0 : 1.0);
    const NodeDerivative da = Differentiate(a, phase_, ia, 0.0, d), db = Differentiate(b, w, ib, s * d.drate, d);
    // psi(s) - psi(0) = -(V/2) [s + twist_factor_ Delta Pi].
    const double dpsi = -0.5 * d.dv * (s + twist_factor_ * delta_pi) -
                        0.5 * norm_v_ * (d.dt * delta_pi + twist_factor_ * (db.dpi_total - da.dpi_total));
    // Q = F(s) Rz(psi) F(0)^T and dF = hat(omega) F: dQ = Q hat(Q^T omega(s) - omega(0) + dpsi u(0)).
    const Eigen::Vector3d spin = path.q.transpose() * FrameSpin(b, db, d) - FrameSpin(a, da, d) + dpsi * u0;
    (p == 0 ? result.chord_rate : result.chord_modulus) = ChordDerivative(b, da, db, ib - ia, d);
    (p == 0 ? result.spin_rate : result.spin_modulus) = spin;
  }
  if (!result.chord_rate.allFinite() || !result.chord_modulus.allFinite() || !result.spin_rate.allFinite() ||
      !result.spin_modulus.allFinite())
    return false;
  *out = result;
  return true;
}

}  // namespace plateball::internal
