#include "plateball/closed_forms.h"

#include <cmath>
#include <limits>

#include "check.h"

namespace plateball {

std::string ToString(ClosedFormFamily family) {
  switch (family) {
    case ClosedFormFamily::kPositiveC:
      return "positive_c";
    case ClosedFormFamily::kNegativeC:
      return "negative_c";
    case ClosedFormFamily::kThroughPoles:
      return "through_poles";
  }
  return "unknown";
}

double AppendixC(const AngleState& s) { return std::sin(s.theta) * std::cos(s.phi - s.psi); }

double AppendixResidual34(const AngleState& s, double d, const BallModel& model) {
  const double c = AppendixC(s);
  return std::sqrt((model.lambda() - 1.0) * c * c + 1.0) * std::sin(s.phi - d) + std::sin(s.phi - s.psi);
}

AppendixSolution::AppendixSolution(const BallModel& model,
                                   const AngleState& initial,
                                   double mu,
                                   double pole_family_tolerance)
    : model_(model), mu_(mu) {
  internal::RequireFinite("theta", initial.theta);
  internal::RequireFinite("phi", initial.phi);
  internal::RequireFinite("psi", initial.psi);
  internal::RequirePositive("mu", mu);
  internal::RequireNonNegative("pole_family_tolerance", pole_family_tolerance);
  b_ = std::sqrt(mu);

  // theta into [0, pi] with (theta, phi, psi) ~ (-theta, phi + pi, psi); phi, psi kept unwrapped
  // otherwise so that At(0) is the given state whenever theta0 is already in [0, pi].
  AngleState s0 = initial;
  s0.theta = std::remainder(initial.theta, 2.0 * M_PI);
  if (s0.theta < 0) {
    s0.theta = -s0.theta;
    s0.phi += M_PI;
  }
  if (std::abs(std::sin(s0.theta)) <= pole_family_tolerance) {
    // On a pole z does not depend on phi and omega = b (cos psi, sin psi): z moves along the
    // meridian phi = psi - pi/2 at the north pole (w = -pi/2, theta' = b) and phi = psi + pi/2 at
    // the south pole (w = pi/2, theta' = -b).
    const bool north = std::cos(s0.theta) > 0;
    s0.theta = north ? 0.0 : M_PI;
    s0.phi = north ? s0.psi - M_PI / 2 : s0.psi + M_PI / 2;
  }
  initial_ = s0;

  const double w0 = s0.phi - s0.psi;
  k_.c = std::sin(s0.theta) * std::cos(w0);
  const double lambda = model.lambda();
  k_.s = std::sqrt((lambda - 1.0) * k_.c * k_.c + 1.0);
  if (std::abs(k_.c) <= pole_family_tolerance) {
    k_.family = ClosedFormFamily::kThroughPoles;
    k_.c = 0.0;
    k_.s = 1.0;
    k_.c1 = k_.c2 = 0.0;
    k_.c_bar = k_.m = std::numeric_limits<double>::infinity();
    k_.d_phi = s0.phi;
    k_.d34 = s0.phi + w0;  // sin(phi - d) + sin(w) = 0 with phi, w constant
    return;
  }
  k_.family = k_.c > 0 ? ClosedFormFamily::kPositiveC : ClosedFormFamily::kNegativeC;
  // Representative with c > 0: (theta, w) itself, or its mirror (pi - theta, w + pi).
  const bool mirror = k_.c < 0;
  const double theta_r = mirror ? M_PI - s0.theta : s0.theta;
  const double w_r = mirror ? w0 + M_PI : w0;
  const double k = std::round(w_r / (2.0 * M_PI));
  const double w_p = w_r - 2.0 * M_PI * k;  // in (-pi/2, pi/2) because cos(w_r) > 0
  w_offset_ = 2.0 * M_PI * k - (mirror ? M_PI : 0.0);
  const double abs_c = std::abs(k_.c);
  k_.c1 = std::cos(theta_r) / abs_c;  // C2(0) = cot(theta) / cos(w) (from (30))
  k_.c2 = std::tan(w_p);              // C1(0) = -tan(w0) (from (31))
  k_.c_bar = std::sqrt(1.0 + k_.c1 * k_.c1 + k_.c2 * k_.c2);
  k_.m = std::sqrt(lambda - 1.0 + k_.c_bar * k_.c_bar);
  const double sign = mirror ? -1.0 : 1.0;
  k_.d_phi = s0.phi - sign * std::asin(std::sin(w0) / k_.s);
  k_.d34 = mirror ? k_.d_phi : k_.d_phi + M_PI;
}

double AppendixSolution::Period() const { return 2.0 * M_PI / b_; }

double AppendixSolution::C1(double s) const { return k_.c1 * std::sin(s) - k_.c2 * std::cos(s); }
double AppendixSolution::C2(double s) const { return k_.c1 * std::cos(s) + k_.c2 * std::sin(s); }

double AppendixSolution::Theta1(double s) const {
  const double c1 = C1(s);
  // (30) with the branch in (0, pi): tan(theta) = sqrt(1 + C1^2) / C2 and sin(theta) > 0.
  const double theta_r = std::atan2(std::sqrt(1.0 + c1 * c1), C2(s));
  return k_.family == ClosedFormFamily::kNegativeC ? M_PI - theta_r : theta_r;
}

double AppendixSolution::W1(double s) const { return -std::atan(C1(s)) + w_offset_; }  // (31)

double AppendixSolution::Theta(double t) const {
  if (k_.family == ClosedFormFamily::kThroughPoles)
    return initial_.theta - b_ * std::sin(initial_.phi - initial_.psi) * t;
  return Theta1(b_ * t);
}

double AppendixSolution::W(double t) const {
  if (k_.family == ClosedFormFamily::kThroughPoles) return initial_.phi - initial_.psi;
  return W1(b_ * t);
}

double AppendixSolution::Phi(double t) const {
  if (k_.family == ClosedFormFamily::kThroughPoles) return initial_.phi;
  const double sign = k_.family == ClosedFormFamily::kNegativeC ? -1.0 : 1.0;
  return k_.d_phi + sign * std::asin(std::sin(W(t)) / k_.s);
}

AngleState AppendixSolution::At(double t) const {
  internal::RequireFinite("t", t);
  const double w = W(t);
  const double phi = Phi(t);
  return {Theta(t), phi, phi - w};
}

}  // namespace plateball
