// The appendix's explicit solutions (30)-(34) of the angle equations, corrected where the paper
// is wrong (docs/paper_notes.md, "Appendix closed forms"), for any energy mu > 0.
//
// With w = phi - psi and b = sqrt(mu), every solution at energy mu is the mu = 1 solution at time
// s = b t (the right-hand sides of (19)-(23) are b times those at mu = 1). The trajectories split
// by the sign of the constant c = sin(theta) cos(w) of (32):
//  - c > 0: (30)-(31) with theta = atan2(sqrt(1 + C1^2), C2) in (0, pi) (the paper's principal
//    arctan is wrong whenever C2 < 0) and w = -arctan(C1) + 2 pi k;
//  - c < 0: the image of a c > 0 solution under the symmetry (theta, w) -> (pi - theta, w + pi)
//    of (22)-(23), which leaves phi' unchanged;
//  - c = 0: the family through the poles: w = +-pi/2 and phi, psi constant, theta = theta0 -
//    b sin(w0) t in the extended chart (any real theta; see AngleState).
// phi(t) = d_phi + sign(c) arcsin(sin(w(t)) / s), s = sqrt((lambda - 1) c^2 + 1) = m / c_bar:
// the paper drops a minus sign in deriving (33); (33)-(34) hold along the whole trajectory with
// the constant d34() (which is d_phi + pi for c > 0 and d_phi for c < 0), not with the d that
// merely satisfies (34) at t = 0.
#pragma once

#include <string>

#include "plateball/ball_model.h"
#include "plateball/ball_state.h"
#include "plateball/export.h"

namespace plateball PLATEBALL_EXPORT {

/// The three families of the appendix, by the sign of c = sin(theta) cos(w), eq. (32).
enum class ClosedFormFamily {
  kPositiveC,     ///< c > 0: (30)-(31) directly
  kNegativeC,     ///< c < 0: the mirror (theta, w) -> (pi - theta, w + pi) of a c > 0 solution
  kThroughPoles,  ///< c = 0: great circle through both poles, theta linear in t
};
/// The value's word as the tools write it in their JSON output and messages.
std::string ToString(ClosedFormFamily family);

/// The constants of the appendix for one trajectory.
struct AppendixConstants {
  ClosedFormFamily family = ClosedFormFamily::kPositiveC;
  double c = 0.0;      ///< sin(theta) cos(w), eq. (32) (conserved)
  double c1 = 0.0;     ///< (30)-(31) of the c > 0 representative: C2(0) = c1 = cos(theta0)/|c|
  double c2 = 0.0;     ///< C1(0) = -c2, c2 = tan(w0) (of the representative)
  double c_bar = 0.0;  ///< sqrt(1 + c1^2 + c2^2) = 1/|c| (infinite for c = 0)
  double m = 0.0;      ///< sqrt(lambda - 1 + c_bar^2), eq. (33) (infinite for c = 0)
  double s = 1.0;      ///< m / c_bar = sqrt((lambda - 1) c^2 + 1), the factor of (34)
  double d_phi = 0.0;  ///< phi(t) = d_phi + sign(c) arcsin(sin(w(t)) / s)
  double d34 = 0.0;    ///< the d for which (33)-(34) hold along the whole trajectory
};

/// The explicit solution from an initial state (theta0, phi0, psi0) at energy mu.
class AppendixSolution {
 public:
  /// Throws std::invalid_argument (naming the field) for non-finite angles or mu <= 0.
  /// theta0 outside [0, pi] is first mapped by AngleState::Canonicalize(). A start on a pole
  /// (sin theta0 = 0, where phi is not determined by z) is put on the meridian it moves along.
  /// c is treated as 0 when |c| <= pole_family_tolerance.
  AppendixSolution(const BallModel& model, const AngleState& initial, double mu, double pole_family_tolerance = 1e-15);

  /// The constants of the closed form (appendix (30)-(34)) of this motion.
  const AppendixConstants& constants() const { return k_; }
  /// The energy mu of the motion.
  double mu() const { return mu_; }
  /// 2 pi / sqrt(mu): the period of the whole state (docs/paper_notes.md, periodicity theorem).
  double Period() const;

  double Theta(double t) const;  ///< (30), corrected branch; extended chart for c = 0
  double W(double t) const;      ///< (31) = phi - psi, continuous in t
  double Phi(double t) const;    ///< from (33), sign corrected

  /// psi = phi - w at t (from (31) and (33)).
  double Psi(double t) const { return Phi(t) - W(t); }
  /// (theta, phi, psi) at t, continuous in t (theta in (0, pi) unless c = 0).
  AngleState At(double t) const;

  /// The initial state actually used (canonicalised; on a pole: the meridian of motion).
  const AngleState& initial() const { return initial_; }

 private:
  double C1(double s) const;  // c1 sin s - c2 cos s at the mu = 1 time s
  double C2(double s) const;  // c1 cos s + c2 sin s
  double Theta1(double s) const;
  double W1(double s) const;
  BallModel model_;
  double mu_;
  double b_;
  AngleState initial_;
  AppendixConstants k_;
  double w_offset_ = 0.0;  // 2 pi k (+ pi for c < 0) added to -arctan(C1)
};

/// c = sin(theta) cos(phi - psi), eq. (32).
double AppendixC(const AngleState& s);
/// Left-hand side of (34): sqrt((lambda - 1) c^2 + 1) sin(phi - d) + sin(w) (zero on a solution).
double AppendixResidual34(const AngleState& s, double d, const BallModel& model);

}  // namespace PLATEBALL_EXPORT
