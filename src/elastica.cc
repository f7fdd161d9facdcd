#include "plateball/elastica.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>
#include <stdexcept>

#include "carlson.h"
#include "check.h"
#include "jacobi_elliptic.h"

namespace plateball {
namespace internal {

// sn, cn, dn by the descending Landen / arithmetic-geometric mean scheme (Abramowitz and Stegun
// 16.4; the iteration of Numerical Recipes' sncndn), 0 <= k < 1. About 6x faster than
// boost::math::jacobi_elliptic, which the tests use as the reference.
JacobiAgm::JacobiAgm(double modulus) : k(modulus) {
  if (k == 0.0) return;
  double emc = (1.0 - k) * (1.0 + k);  // complementary parameter 1 - k^2
  double a = 1.0;
  for (int i = 0; i < 16; ++i) {
    levels = i;
    em[i] = a;
    emc = std::sqrt(emc);
    en[i] = emc;
    c = 0.5 * (a + emc);
    if (std::abs(a - emc) <= 1e-9 * a) break;
    emc *= a;
    a = c;
  }
}

void JacobiSnCnDn(double u, const JacobiAgm& agm, double* sn, double* cn, double* dn) {
  if (std::abs(u) < kJacobiTinyArgument) {  // sn = u + O(u^3), cn, dn = 1 - O(u^2): exact in double
    *sn = u;
    *cn = 1.0;
    *dn = 1.0;
    return;
  }
  if (agm.k == 0.0) {
    *sn = std::sin(u);
    *cn = std::cos(u);
    *dn = 1.0;
    return;
  }
  double c = agm.c, d = 1.0, a;
  u *= c;
  double s = std::sin(u), co = std::cos(u);
  if (s != 0.0) {
    a = co / s;
    c *= a;
    for (int ii = agm.levels; ii >= 0; --ii) {
      const double b = agm.em[ii];
      a *= c;
      c *= d;
      d = (agm.en[ii] + a) / (b + a);
      a = c / b;
    }
    a = 1.0 / std::sqrt(c * c + 1.0);
    s = s >= 0.0 ? a : -a;
    co = c * s;
  }
  *sn = s;
  *cn = co;
  *dn = d;
}

void JacobiSnCnDn(double u, double k, double* sn, double* cn, double* dn) { JacobiSnCnDn(u, JacobiAgm(k), sn, cn, dn); }

double CompleteEllipticK(double k) { return CompleteEllipticKD(std::abs(k), std::sqrt(OneMinusSquare(k))).k; }

double CompleteEllipticD(double k) { return CompleteEllipticKD(std::abs(k), std::sqrt(OneMinusSquare(k))).d; }

double EllipticFSinCos(double sin_phi, double cos_phi, double kc2) {
  if (sin_phi == 0.0) return 0.0;
  const double c2 = cos_phi * cos_phi;
  return sin_phi * CarlsonRF(c2, c2 + kc2 * sin_phi * sin_phi, 1.0);
}

double EllipticDSinCos(double sin_phi, double cos_phi, double kc2) {
  if (sin_phi == 0.0) return 0.0;
  const double c2 = cos_phi * cos_phi, s2 = sin_phi * sin_phi;
  return sin_phi * s2 * CarlsonRD(c2, c2 + kc2 * s2, 1.0) / 3.0;
}

}  // namespace internal

namespace {

// Incomplete F(phi, k) for any real phi: F(phi + m pi) = F(phi) + 2 m K.
double FullEllipticF(double k, double phi, double complete_k) {
  const double m = std::round(phi / M_PI);
  const double r = phi - m * M_PI;  // |r| <= pi/2
  return 2.0 * m * complete_k + internal::EllipticFSinCos(std::sin(r), std::cos(r), internal::OneMinusSquare(k));
}

// 8-point Gauss-Legendre nodes/weights on [-1, 1] (for short arcs where the closed form loses
// relative accuracy to cancellation).
constexpr double kGlNodes[4] = {0.1834346424956498, 0.5255324099163290, 0.7966664774136267, 0.9602898564975363};
constexpr double kGlWeights[4] = {0.3626837833783620, 0.3137066458778873, 0.2223810344533745, 0.1012285362903763};

// Below this |u - u0| the position is evaluated by quadrature of the closed-form tangent:
// the closed form divides a difference of O(|u - u0|) by the rate.
constexpr double kShortArcArgument = 0.05;
// Below this |u - u0| (the searches' finite-difference steps, ~1e-6) the 2-point rule, nodes
// +-1/sqrt(3), suffices: its error is s^5 x'^(4) / 4320, |u - u0|^4 / 4320 < 4e-19 relative
// (derivatives of the tangent scale with rate^n).
constexpr double kTinyArcArgument = 2e-4;
constexpr double kGl2Node = 0.57735026918962576451;

}  // namespace

std::string ToString(PendulumRegime regime) {
  switch (regime) {
    case PendulumRegime::kOscillating:
      return "oscillating";
    case PendulumRegime::kRotating:
      return "rotating";
  }
  return "unknown";
}

Elastica::Elastica(const ElasticaParameters& parameters) : p_(parameters) {
  internal::RequireFinite("rate", p_.rate);
  internal::RequireFinite("modulus", p_.modulus);
  internal::RequireFinite("phase", p_.phase);
  internal::RequireFinite("heading_w", p_.heading_w);
  if (!(std::abs(p_.modulus) < 1.0))
    internal::ThrowInvalid(
        "modulus", p_.modulus, "|modulus| must be < 1 (the separatrix k = 1 has an infinite period)");
  k_ = std::abs(p_.modulus);
  agm_ = std::make_shared<const internal::JacobiAgm>(k_);
  kc2_ = internal::OneMinusSquare(k_);
  const internal::CompleteKD complete = internal::CompleteEllipticKD(k_, std::sqrt(kc2_));
  kk_ = complete.k;
  dk_ = complete.d;
  // Position(s) subtracts the values at s = 0 (u = phase): kept.
  i0_ = IntegralSn2(p_.phase, &j0_);
  cos_w_ = std::sin(p_.heading_w);   // cos(g_W - pi/2)
  sin_w_ = -std::cos(p_.heading_w);  // sin(g_W - pi/2)
  SetRateTerms();
}

Elastica Elastica::WithRate(double rate) const {
  internal::RequireFinite("rate", rate);
  Elastica e = *this;  // k, its AGM sequence, K, D, k'^2, g_W and the values at u = phase: independent of the rate
  e.p_.rate = rate;
  e.SetRateTerms();
  return e;
}

void Elastica::SetRateTerms() {
  const double r = p_.rate;
  if (p_.regime == PendulumRegime::kOscillating) {
    g_ = r * r;
    energy_ = g_ * (2.0 * k_ * k_ - 1.0);
    period_ = r == 0.0 ? std::numeric_limits<double>::infinity() : 4.0 * kk_ / std::abs(r);
  } else {
    g_ = r * r * k_ * k_;
    energy_ = 2.0 * r * r - g_;
    period_ = r == 0.0 ? std::numeric_limits<double>::infinity() : 2.0 * kk_ / std::abs(r);
  }
  drift_ = Eigen::Vector2d::Zero();
  if (std::isfinite(period_)) {
    // Over one period u advances by 4K (oscillating) or 2K (rotating); int sn^2 by 4D(k) or
    // 2D(k); the transverse coordinate returns. (Position(Period()) agrees: elastica_test.)
    const double x = p_.regime == PendulumRegime::kOscillating ? period_ - 8.0 * k_ * k_ * dk_ / std::abs(r)
                                                               : period_ - 4.0 * dk_ / std::abs(r);
    drift_ = Eigen::Vector2d(cos_w_ * x, sin_w_ * x);
  }
}

Elastica Elastica::FromInitialState(double G, double heading_w, double heading0, double curvature0) {
  internal::RequireNonNegative("G", G);
  internal::RequireFinite("heading_w", heading_w);
  internal::RequireFinite("heading0", heading0);
  internal::RequireFinite("curvature0", curvature0);
  const double theta_raw = heading0 - heading_w + M_PI / 2;
  const double theta0 = std::remainder(theta_raw, 2.0 * M_PI);  // in [-pi, pi]
  ElasticaParameters p;
  p.heading_w = heading_w + (theta_raw - theta0);  // so that Heading(0) = heading0 exactly
  const double energy = 0.5 * curvature0 * curvature0 - G * std::cos(theta0);
  if (G == 0.0) {
    // Circle of curvature curvature0 (or a line): theta = 2 am(a s + u0, 0) = 2 (a s + u0).
    p.regime = PendulumRegime::kRotating;
    p.rate = 0.5 * curvature0;
    p.modulus = 0.0;
    p.phase = 0.5 * theta0;
    return Elastica(p);
  }
  if (std::abs(energy - G) <= 1e-12 * G)
    internal::ThrowInvalid("curvature0", curvature0, "gives the pendulum separatrix E = G (infinite period)");
  if (energy < G) {
    p.regime = PendulumRegime::kOscillating;
    const double k2 = std::max(0.0, (energy + G) / (2.0 * G));
    const double k = std::sqrt(k2);
    const double b = std::sqrt(G);
    p.rate = b;
    p.modulus = k;
    if (k == 0.0) {
      p.phase = 0.0;
    } else {
      const double kk = internal::CompleteEllipticK(k);
      const double phi0 = std::atan2(std::sin(0.5 * theta0) / k, curvature0 / (2.0 * k * b));
      p.phase = FullEllipticF(k, phi0, kk);
    }
  } else {
    p.regime = PendulumRegime::kRotating;
    const double k = std::sqrt(2.0 * G / (energy + G));
    p.modulus = k;
    p.rate = (curvature0 > 0 ? 1.0 : -1.0) * std::sqrt(0.5 * (energy + G));
    p.phase = FullEllipticF(k, 0.5 * theta0, internal::CompleteEllipticK(k));
  }
  return Elastica(p);
}

Elastica::Jacobi Elastica::Eval(double u) const {
  const double quarter4 = 4.0 * kk_;
  const double r = u - quarter4 * std::round(u / quarter4);
  Jacobi j{};
  internal::JacobiSnCnDn(r, *agm_, &j.sn, &j.cn, &j.dn);
  return j;
}

double Elastica::IntegralSn2(double u) const {
  Jacobi j{};
  return IntegralSn2(u, &j);
}

double Elastica::IntegralSn2(double u, Jacobi* j) const {
  const double m = std::round(u / (2.0 * kk_));
  const double r = u - 2.0 * kk_ * m;  // |r| <= K: cn(r) >= 0
  internal::JacobiSnCnDn(r, *agm_, &j->sn, &j->cn, &j->dn);
  // D(am r) with sin(am r) = sn, cos(am r) = cn (no atan2, no 1 - k^2 sin^2 formed).
  const double integral = 2.0 * m * dk_ + internal::EllipticDSinCos(j->sn, j->cn, kc2_);
  if (internal::IsOddInteger(m)) {  // sn(r + 2K) = -sn(r), cn(r + 2K) = -cn(r), dn(r + 2K) = dn(r)
    j->sn = -j->sn;
    j->cn = -j->cn;
  }
  return integral;
}

double Elastica::AmplitudeOf(double u) const {
  const double m = std::round(u / (2.0 * kk_));
  const double r = u - 2.0 * kk_ * m;
  double sn = 0, cn = 0, dn = 0;
  internal::JacobiSnCnDn(r, *agm_, &sn, &cn, &dn);
  return m * M_PI + std::atan2(sn, cn);
}

double Elastica::PendulumAngle(double s) const {
  const double u = p_.rate * s + p_.phase;
  if (p_.regime == PendulumRegime::kOscillating) {
    const double v = std::clamp(p_.modulus * Eval(u).sn, -1.0, 1.0);
    return 2.0 * std::asin(v);
  }
  return 2.0 * AmplitudeOf(u);
}

double Elastica::Heading(double s) const { return PendulumAngle(s) + p_.heading_w - M_PI / 2; }

double Elastica::Curvature(double s) const { return CurvatureOf(Eval(p_.rate * s + p_.phase)); }

double Elastica::CurvatureOf(const Jacobi& j) const {
  if (p_.regime == PendulumRegime::kOscillating) return 2.0 * p_.modulus * p_.rate * j.cn;
  return 2.0 * p_.rate * j.dn;
}

void Elastica::TangentAndCurvature(double s, Eigen::Vector2d* tangent, double* curvature) const {
  const Jacobi j = Eval(p_.rate * s + p_.phase);
  *tangent = TangentOf(j);
  *curvature = CurvatureOf(j);
}

Eigen::Vector2d Elastica::Tangent(double s) const { return TangentOf(Eval(p_.rate * s + p_.phase)); }

Eigen::Vector2d Elastica::TangentOf(const Jacobi& j) const {
  double c, sn;  // cos(theta), sin(theta) in the pendulum frame
  if (p_.regime == PendulumRegime::kOscillating) {
    const double ks = p_.modulus;
    c = 1.0 - 2.0 * ks * ks * j.sn * j.sn;
    sn = 2.0 * ks * j.sn * j.dn;
  } else {
    c = 1.0 - 2.0 * j.sn * j.sn;
    sn = 2.0 * j.sn * j.cn;
  }
  return {cos_w_ * c - sin_w_ * sn, sin_w_ * c + cos_w_ * sn};
}

Eigen::Vector2d Elastica::Position(double s) const {
  Jacobi j{};
  double integral_sn2 = 0.0;
  return PositionAt(s, &j, &integral_sn2);
}

Eigen::Vector2d Elastica::PositionAt(double s, Jacobi* jacobi, double* integral_sn2) const {
  const double du = p_.rate * s;
  if (std::abs(du) < kShortArcArgument) {
    *integral_sn2 = std::numeric_limits<double>::quiet_NaN();
    // Short arc (or straight line): 8-point Gauss-Legendre quadrature of the closed-form
    // tangent; the tangent is analytic, so the error is O(du^16) relative (2 points: O(du^4)).
    const double half = 0.5 * s;
    if (std::abs(du) < kTinyArcArgument)
      return half * (Tangent(half * (1.0 - kGl2Node)) + Tangent(half * (1.0 + kGl2Node)));
    Eigen::Vector2d acc = Eigen::Vector2d::Zero();
    for (int i = 0; i < 4; ++i) {
      acc += kGlWeights[i] * (Tangent(half * (1.0 - kGlNodes[i])) + Tangent(half * (1.0 + kGlNodes[i])));
    }
    return half * acc;
  }
  // At u = phase + du: sn, cn, dn and int_0^u sn^2 from one reduction modulo 2K.
  *integral_sn2 = IntegralSn2(p_.phase + du, jacobi);
  const double di = *integral_sn2 - i0_;
  const Jacobi& j = *jacobi;
  const Jacobi& j0 = j0_;
  double x, y;  // pendulum frame
  if (p_.regime == PendulumRegime::kOscillating) {
    const double ks = p_.modulus, b = p_.rate;
    x = s - 2.0 * ks * ks * di / b;
    y = -2.0 * ks * (j.cn - j0.cn) / b;
  } else {
    const double a = p_.rate;
    x = s - 2.0 * di / a;
    y = 2.0 * (j.sn * j.sn - j0.sn * j0.sn) / ((j.dn + j0.dn) * a);
  }
  return {cos_w_ * x - sin_w_ * y, sin_w_ * x + cos_w_ * y};
}

}  // namespace plateball
