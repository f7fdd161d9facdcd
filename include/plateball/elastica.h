// The optimal paths of the isoparallel problem in closed form (section 2.2, Figures 6 and 7).
//
// With unit speed x' = (cos g, sin g) (g the heading, s the arc length) the extremal equations
// v' = (e3 x x') x v, x'' = v^3 e3 x x' of section 2.2 give the curvature g' = v^3, and
// W = v_h + e3 x x' is a constant horizontal vector (docs/paper_notes.md, "Isoparallel extremals").
// Then g'' = -|W| cos(g - g_W): with theta = g - g_W + pi/2 the heading is the pendulum of Figure 6,
//     theta'' = -G sin(theta),   G = |W|   (1/length^2; the paper's g/R),
// with energy E = theta'^2/2 - G cos(theta). The paths are Euler's elastica:
//  - oscillating (E < G): sin(theta/2) = k sn(b s + u0, k), b = sqrt(G), k^2 = (E + G)/(2G);
//  - rotating (E > G):    theta/2 = am(a s + u0, k), |a| = sqrt(G)/k, k^2 = 2G/(E + G);
//  - G = 0: circles (rotating, k = 0) and straight lines (rate 0).
// Positions are elliptic integrals too (Jacobi epsilon / Legendre's D), so every quantity of the
// path is evaluated in closed form (Carlson's symmetric integrals), at any s, without integration.
#pragma once

#include <Eigen/Core>
#include <memory>
#include <string>

#include "plateball/export.h"

// Library-internal types (src/), declared outside the exported namespace so they stay hidden.
namespace plateball::internal {
struct ElasticaAccess;
class ElasticaClosedRolling;  // src/elastica_closed_rolling.h
struct JacobiAgm;             // src/jacobi_elliptic.h
}  // namespace plateball::internal

namespace plateball PLATEBALL_EXPORT {

enum class PendulumRegime { kOscillating, kRotating };
/// The value's word as the tools write it in their JSON output and messages.
std::string ToString(PendulumRegime regime);

/// The three pendulum parameters (G, energy, phase) of section 2.2 in the form the closed
/// forms use, plus the direction g_W of W (the plane's rotation freedom).
struct ElasticaParameters {
  PendulumRegime regime = PendulumRegime::kOscillating;
  /// Oscillating: b = +-sqrt(G) (the sign is the direction of pendulum time).
  /// Rotating: a = +-sqrt(G)/k (the sign is the sense of rotation: a > 0 turns left).
  /// Units 1/length. 0 gives a straight line.
  double rate = 0.0;
  /// Elliptic modulus k, |k| < 1 (only k^2 matters for the shape up to a phase shift).
  /// Oscillating: k = sin(amplitude/2); rotating: k = 0 is a circle of curvature 2a.
  double modulus = 0.0;
  /// u0, the argument of the Jacobi functions at s = 0.
  double phase = 0.0;
  /// g_W: direction of W; the heading is g = theta + g_W - pi/2.
  double heading_w = 0.0;
};

/// One optimal path x(s), s = arc length, starting at the origin: x(0) = 0.
class Elastica {
 public:
  /// Throws std::invalid_argument naming the field for non-finite values or |modulus| >= 1
  /// (the separatrix E = G has an infinite period and is not represented).
  explicit Elastica(const ElasticaParameters& parameters);
  /// The path with g'' = -G cos(g - g_W), g(0) = heading0, g'(0) = curvature0 (G >= 0).
  /// Throws std::invalid_argument on the separatrix (E = G to 1e-12 relative) or invalid values.
  static Elastica FromInitialState(double G, double heading_w, double heading0, double curvature0);

  /// The same elastica with rate `rate` (regime, modulus, phase and heading_w kept), equal bit for
  /// bit to Elastica with those parameters: the AGM sequence of k, K, D and the values at s = 0 do
  /// not depend on the rate and are shared, not recomputed (the rate column of the isoparallel
  /// searches' Jacobian, section 2.2). Throws std::invalid_argument naming the rate when not finite.
  Elastica WithRate(double rate) const;

  /// The parameters this elastica was built from.
  const ElasticaParameters& parameters() const { return p_; }
  /// G = |W| (1/length^2).
  double G() const { return g_; }
  /// Pendulum energy E = theta'^2/2 - G cos(theta).
  double Energy() const { return energy_; }
  /// Pendulum angle theta(s) (continuous in s).
  double PendulumAngle(double s) const;
  /// Heading g(s) = theta(s) + g_W - pi/2 (continuous in s).
  double Heading(double s) const;
  /// Signed curvature g'(s).
  double Curvature(double s) const;
  /// Unit tangent x'(s).
  Eigen::Vector2d Tangent(double s) const;
  /// Tangent(s) and Curvature(s), bit for bit, from one evaluation of the Jacobi functions.
  void TangentAndCurvature(double s, Eigen::Vector2d* tangent, double* curvature) const;
  /// x(s) - x(0), in closed form.
  Eigen::Vector2d Position(double s) const;
  /// Period of the curvature in s: 4K/|b| (oscillating), 2K/|a| (rotating); +infinity for
  /// straight lines. Over one period the tangent returns (the heading changes by 0 or +-2 pi).
  double Period() const { return period_; }
  /// x(Period()) - x(0) (zero vector for a straight line, whose period is infinite).
  Eigen::Vector2d DriftPerPeriod() const { return drift_; }
  /// True for rate = 0 (straight line).
  bool IsStraight() const { return p_.rate == 0.0; }

 private:
  friend struct internal::ElasticaAccess;        // elastica_rolling.cc marches the Jacobi functions
  friend class internal::ElasticaClosedRolling;  // shares the AGM sequence, K, k'^2, g_W and s = 0 values
  struct Jacobi {
    double sn, cn, dn;
  };
  Jacobi Eval(double u) const;
  // Position(s), and the Jacobi functions at u = phase + rate s and int_0^u sn^2 from which the
  // closed form took it (integral NaN on a short arc, which is integrated instead).
  Eigen::Vector2d PositionAt(double s, Jacobi* j, double* integral_sn2) const;
  Eigen::Vector2d TangentOf(const Jacobi& j) const;
  double CurvatureOf(const Jacobi& j) const;
  double IntegralSn2(double u) const;             // int_0^u sn^2
  double IntegralSn2(double u, Jacobi* j) const;  // the same, and the Jacobi functions at u
  double AmplitudeOf(double u) const;             // am(u), continuous
  void SetRateTerms();                            // G, E, the period and the drift from p_.rate (and k, K, D, g_W)
  ElasticaParameters p_;
  double k_ = 0.0;                                  // |modulus|
  std::shared_ptr<const internal::JacobiAgm> agm_;  // AGM sequence of k (immutable, shared by copies)
  double kk_ = 0.0;                                 // complete K(k)
  double dk_ = 0.0;                                 // complete D(k) = int_0^K sn^2
  double kc2_ = 1.0;                                // k'^2 = 1 - k^2 (formed without cancellation)
  Jacobi j0_{0.0, 1.0, 1.0};                        // the Jacobi functions at u = phase (s = 0)
  double i0_ = 0.0;                                 // int_0^phase sn^2
  double g_ = 0.0;
  double energy_ = 0.0;
  double period_ = 0.0;
  double cos_w_ = 1.0, sin_w_ = 0.0;  // rotation by g_W - pi/2 (pendulum frame -> plane)
  Eigen::Vector2d drift_ = Eigen::Vector2d::Zero();
};

}  // namespace PLATEBALL_EXPORT
