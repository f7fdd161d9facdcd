#include "plateball/error_bounds.h"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "check.h"

namespace plateball {

CurveDerivativeBounds EstimateCurveDerivativeBounds(const SmoothCurve& curve, double a, double b, int samples) {
  if (samples < 2) internal::ThrowInvalid("samples", samples, "must be >= 2");
  CurveDerivativeBounds out;
  if (curve.kind() == CurveKind::kLine || curve.kind() == CurveKind::kCircle) {
    // Constant on a line (|v|, 0) and a circle (rho, rho, either direction): one evaluation is the
    // maximum (no sampling, no neighbour term).
    out.max_speed = curve.Derivative(a).norm();
    out.max_acceleration = curve.kind() == CurveKind::kCircle ? out.max_speed : 0.0;
    return out;
  }
  double prev_v = 0.0, prev_a = 0.0, jump_v = 0.0, jump_a = 0.0;
  for (int i = 0; i < samples; ++i) {
    const double tau = a + (b - a) * i / (samples - 1);
    const auto [v, acc] = curve.DerivativeNorms(tau);
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

double KBarP(double K_p, double M_prime_p) { return K_p * M_prime_p; }
double KTilde(double K_10, double M_prime) { return 2.0 * K_10 * M_prime; }
double KTildeP(double K_tilde, double K1, double D_p) { return K_tilde * std::pow(K1 * D_p, 3); }
double Theorem25Bound(double K_bar_p, double sum_dtau_cubed) { return K_bar_p * sum_dtau_cubed; }
double Corollary2Bound(double K_bar_p, int n, double parameter_norm) {
  return K_bar_p * n * std::pow(parameter_norm, 3);
}
double Theorem26Bound(double K_bar_p, double K_tilde_p, double sum_dtau_cubed) {
  return (K_bar_p + K_tilde_p) * sum_dtau_cubed;
}
double Corollary3Bound(double K_bar_p, double K_tilde_p, int n, double parameter_norm) {
  return (K_bar_p + K_tilde_p) * n * std::pow(parameter_norm, 3);
}

void AccumulateSegment(const SegmentMeasures& m, ErrorBounds* b) {
  ErrorBoundConstants& c = b->constants;
  b->a_posteriori_path += SegmentBound(m.path.max_speed, m.path.max_acceleration, m.h);
  b->a_posteriori_arcs += SegmentBound(m.arc_max_speed, m.arc_max_acceleration, m.arc_time);
  b->sum_dtau_cubed += m.h * m.h * m.h;
  b->parameter_norm = std::max(b->parameter_norm, m.h);
  c.K_p = std::max(c.K_p, m.path.max_acceleration);
  c.M_prime_p = std::max(c.M_prime_p, m.path.max_speed);
  c.C_p = std::max(c.C_p, m.h / m.chord);
  c.M_prime = std::max(c.M_prime, m.arc_max_speed);
  c.K_10 = std::max(c.K_10, 0.5 * m.arc_max_acceleration);
  c.K1 = std::max(c.K1, m.arc_time / m.chord);
}

void CompleteBounds(int n, ErrorBounds* b) {
  ErrorBoundConstants& c = b->constants;
  c.K_bar_p = KBarP(c.K_p, c.M_prime_p);
  c.D_p = c.M_prime_p;
  c.K_tilde = KTilde(c.K_10, c.M_prime);
  c.K_tilde_p = KTildeP(c.K_tilde, c.K1, c.D_p);
  b->segments = n;
  b->theorem_2_5 = Theorem25Bound(c.K_bar_p, b->sum_dtau_cubed);
  b->corollary_2 = Corollary2Bound(c.K_bar_p, n, b->parameter_norm);
  b->theorem_2_6 = Theorem26Bound(c.K_bar_p, c.K_tilde_p, b->sum_dtau_cubed);
  b->corollary_3 = Corollary3Bound(c.K_bar_p, c.K_tilde_p, n, b->parameter_norm);
  b->a_posteriori = b->a_posteriori_path + b->a_posteriori_arcs;
}

std::string ErrorBounds::BriefReport() const {
  std::ostringstream os;
  os.precision(4);
  os << "bounds: a-posteriori " << a_posteriori << " (path " << a_posteriori_path << ", arcs " << a_posteriori_arcs
     << "), Theorem 2.6 " << theorem_2_6 << ", Corollary 3 " << corollary_3 << ", Theorem 2.5 " << theorem_2_5
     << "; K_p " << constants.K_p << ", M'_p " << constants.M_prime_p << ", Ktilde " << constants.K_tilde << ", K1 "
     << constants.K1 << ", D_p " << constants.D_p;
  return os.str();
}

}  // namespace plateball
