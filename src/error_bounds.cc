#include "plateball/error_bounds.h"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "check.h"

namespace plateball {

CurveDerivativeBounds EstimateCurveDerivativeBounds(const SmoothCurve& curve, double a, double b, int samples) {
  if (samples < 2) internal::ThrowInvalid("samples", samples, "must be >= 2");
  CurveDerivativeBounds out;
  double prev_v = 0.0, prev_a = 0.0, jump_v = 0.0, jump_a = 0.0;
  for (int i = 0; i < samples; ++i) {
    const double tau = a + (b - a) * i / (samples - 1);
    const double v = curve.Derivative(tau).norm();
    const double acc = curve.SecondDerivative(tau).norm();
    if (i > 0) {
      jump_v = std::max(jump_v, std::abs(v - prev_v));
      jump_a = std::max(jump_a, std::abs(acc - prev_a));
    }
    out.max_speed = std::max(out.max_speed, v);
    out.max_acceleration = std::max(out.max_acceleration, acc);
    prev_v = v;
    prev_a = acc;
  }
  out.max_speed += jump_v;
  out.max_acceleration += jump_a;
  return out;
}

std::string ErrorBounds::BriefReport() const {
  std::ostringstream os;
  os.precision(4);
  os << "bounds: a-posteriori " << a_posteriori << " (path " << a_posteriori_path << ", arcs " << a_posteriori_arcs
     << "), Theorem 2.6 " << theorem_2_6 << ", Corollary 3 " << corollary_3 << ", Theorem 2.5 " << theorem_2_5
     << "; K_p " << constants.K_p << ", M'_p " << constants.M_prime_p << ", Ktilde " << constants.K_tilde
     << ", K1 " << constants.K1 << ", D_p " << constants.D_p;
  return os.str();
}

}  // namespace plateball
