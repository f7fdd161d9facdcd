// Internal: the rolling of the ball along an elastica in closed form.
//
// Along an extremal the costate v(s) = (W - e3 x x'(s), g'(s)) is transported by the rolling,
// Q(s0, s1) v(s0) = v(s1) (section 2.2; isoparallel_families.h), and |v| = V is constant,
// V^2 = 1 + G^2 + 2E. With the costate frame F(s) = [f1 f2 u], u = v / V, f1 = e3 x u / |e3 x u|,
// f2 = u x f1, the rolling is a rotation about u by the twist psi:
//     Q(s0, s1) = F(s1) Rz(psi(s1) - psi(s0)) F(s0)^T,
//     psi(s) = -(V / 2) [ s + (1 - G^2) J(s) ],   J(s) = int_0^s ds / (1 + G^2 - 2 G cos theta),
// and J is Legendre's incomplete integral of the third kind Pi(n; am(rate s + u0), k) with
// n = -4 G kappa^2 / (1 - G)^2 (kappa = k oscillating, 1 rotating). The derivation, the G = 1
// chart, the accuracy and the costs are in docs/paper_notes.md, "Rolling along an elastica in
// closed form (costate frame and twist)". ElasticaRollingTable (elastica_rolling.h) computes the
// same Q(0, s) by sixth-order Magnus steps.
#pragma once

#include <Eigen/Core>

#include "jacobi_elliptic.h"
#include "plateball/elastica.h"

namespace plateball::internal {

/// Q(s0, s1), the solution of dQ/ds = hat(e3 x x'(s)) Q with Q(s0, s0) = I (the convention of
/// ElasticaRollingTable: Rolling(0, s) = ElasticaRollingTable::Rolling(s)), in closed form at
/// any s0, s1: O(1) work whatever the number of periods between them.
class ElasticaClosedRolling {
  // The Jacobi functions at w = rate s + u0 = 2 K m + r, |r| <= K.
  struct Node {
    double m = 0.0;                       // number of half periods 2K (an integer)
    double sn = 0.0, cn = 1.0, dn = 1.0;  // at w
    double pi = 0.0;                      // Pi(n; am(r), k), when asked for and n != 0
  };

 public:
  /// Keeps the elastica's parameters (not a reference to it). Throws std::invalid_argument naming
  /// the rate when |rate| > kMaxRate (G and V^2 would overflow).
  explicit ElasticaClosedRolling(const Elastica& e);
  static constexpr double kMaxRate = 1e150;

  /// Q(s0, s1) (a rotation; Q(s1, s0) = Q(s0, s1)^T). Throws std::invalid_argument naming s0 or
  /// s1 when it is not finite or when rate * s overflows.
  Eigen::Matrix3d Rolling(double s0, double s1) const;
  /// Q(0, s) = Rolling(0, s) with the frame and Pi at s = 0 kept from the construction (half the
  /// work): ElasticaRollingTable::Rolling(s) in closed form.
  Eigen::Matrix3d Rolling(double s) const;
  /// The costate v(s) = (W - e3 x x'(s), g'(s)) in the plane's coordinates.
  Eigen::Vector3d Costate(double s) const;
  /// The costate frame F(s) = [f1 f2 u] (a rotation). On the chart G = 1 (|1 - G| < 1e-150,
  /// where v_h vanishes at the zeros of theta) f1 = (-sin(theta/2), cos(theta/2)) in the pendulum
  /// frame instead, which is smooth there. Throws std::invalid_argument when the costate is zero
  /// (the straight line with G = 1, whose rolling Rolling() still gives).
  Eigen::Matrix3d Frame(double s) const;
  /// psi(s) - psi(0), the angle about u(s) in Q(0, s) = F(s) Rz(Twist(s)) F(0)^T.
  double Twist(double s) const;
  /// V = |v(s)| (constant).
  double CostateNorm() const { return norm_v_; }

  /// First derivatives of the path from 0 to s, x(s) - x(0) = e.Position(s) and Q(0, s) =
  /// Rolling(s), with respect to the rate and to the modulus (the other parameters fixed): the
  /// chord's directly, the rolling's as the spin omega with dQ/dp = Q hat(omega).
  struct PathSensitivity {
    Eigen::Vector2d chord_rate = Eigen::Vector2d::Zero(), chord_modulus = Eigen::Vector2d::Zero();
    Eigen::Vector3d spin_rate = Eigen::Vector3d::Zero(), spin_modulus = Eigen::Vector3d::Zero();
  };
  /// The path from 0 to s: its chord x(s) - x(0) and Q(0, s), bit for bit e.Position(s) and
  /// Rolling(s) (`e` the elastica this object was built from), from one evaluation of the Jacobi
  /// functions at s; what Sensitivity needs is kept.
  struct PathEnd {
    double s = 0.0;
    Eigen::Vector2d chord = Eigen::Vector2d::Zero();
    Eigen::Matrix3d q = Eigen::Matrix3d::Identity();

   private:
    friend class ElasticaClosedRolling;
    Node node;
    double integral_sn2 = 0.0;  // int_0^w sn^2 (NaN on a short arc: Position integrates it)
  };
  /// Throws like Rolling(s).
  PathEnd Path(const Elastica& e, double s) const;
  /// The derivatives in closed form at the end of `path` (from Path(e, s)): each Jacobi function,
  /// Legendre's D and E and the twist's Pi differentiated at fixed argument w = rate s + u0 (d am /
  /// dk, and dPi/dn, dPi/dk in terms of F, E, Pi: Byrd and Friedman 710.00, 733.00), the costate
  /// frame through its costate. False (out untouched) where these forms are not used: straight
  /// lines, circles and tiny moduli (modulus < kSensitivityMinModulus, also every negative
  /// modulus), |1 - G| < kSensitivityMinOneMinusG (the frame's layer), short arcs (|rate s| <
  /// kSensitivityMinArc, where the chord cancels).
  bool Sensitivity(const PathEnd& path, PathSensitivity* out) const;
  static constexpr double kSensitivityMinModulus = 1e-3;
  static constexpr double kSensitivityMinOneMinusG = 1e-3;
  static constexpr double kSensitivityMinArc = 0.05;
  /// True when the curvature vanishes identically (rate 0, or oscillating with k = 0).
  bool IsStraight() const { return straight_; }
  /// True when the frame uses the G = 1 chart (|1 - G| < kUnitChart).
  bool UnitChart() const { return unit_chart_; }
  /// |1 - G| below which the G = 1 chart is used: there n = -4 G kappa^2 / (1 - G)^2 would
  /// overflow, and the two charts differ only where |sn| < |1 - G|.
  static constexpr double kUnitChart = 1e-150;

 private:
  Node At(double s, const char* field, bool with_pi) const;
  // The node from m and the Jacobi functions of r (before the sign flip of odd m).
  Node NodeFrom(double m, double sn, double cn, double dn, bool with_pi) const;
  void SetUpThirdKind(double k2, double kc2);
  double ThirdKind(double sn, double cn, double dn) const;
  void CacheOrigin(const Elastica& e);
  Eigen::Vector3d PendulumCostate(const Node& j) const;
  Eigen::Matrix3d FrameAt(const Node& j) const;
  // psi(s1) - psi(s0) from the nodes (s1 - s0 passed exactly).
  double TwistBetween(const Node& a, const Node& b, double ds) const;
  // Sensitivity's pieces: one direction (drate, dk) of the parameters.
  struct Direction;
  struct NodeDerivative;
  NodeDerivative Differentiate(const Node& j, double w, double integral_sn2, double dw, const Direction& d) const;
  Direction MakeDirection(double drate, double dk) const;
  Eigen::Vector3d FrameSpin(const Node& j, const NodeDerivative& dj, const Direction& d) const;
  Eigen::Vector2d ChordDerivative(
      const Node& b, const NodeDerivative& da, const NodeDerivative& db, double di, const Direction& d) const;
  Eigen::Matrix3d RollingTo(const Node& b, double s) const;

  PendulumRegime regime_;
  double rate_, modulus_, phase_;  // modulus_ signed, as in ElasticaParameters
  double big_g_, one_minus_g_;     // G and 1 - G (the latter without cancellation)
  double cos_w_, sin_w_;           // pendulum frame -> plane: rotation by g_W - pi/2
  double norm_v_;                  // V
  double n_ = 0.0;                 // characteristic of Pi
  double complete_k_ = 0.0;        // K(k)
  double complete_pi_ = 0.0;       // Pi(n; pi/2, k)
  struct {
    double n_big = 0.0, one_minus_n_big = 0.0, c1 = 0.0, c2 = 0.0, c3 = 0.0, p2 = 0.0;
  } third_;                    // Pi(n) through Pi(N), 0 < N < 1 (ThirdKind)
  double twist_factor_ = 0.0;  // (1 + G) / ((1 - G) rate): (1 - G^2) J = twist_factor_ Delta Pi
  bool straight_, unit_chart_;
  JacobiAgm agm_;
  Eigen::Vector3d straight_omega_;                                // e3 x x' on a straight line
  double kc2_ = 1.0;                                              // k'^2
  double integral_sn2_origin_ = 0.0;                              // int_0^u0 sn^2
  Node origin_;                                                   // at s = 0, with Pi
  Eigen::Matrix3d origin_frame_t_ = Eigen::Matrix3d::Identity();  // F(0)^T (not for straight lines)
};

}  // namespace plateball::internal
