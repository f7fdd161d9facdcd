#include "identify_model.h"

#include <array>
#include <cmath>

#include "dynamics.h"
#include "kinematics.h"

namespace plateball::internal {
namespace {

// The parameters that enter the equations of motion: (lambda, mu, theta, phi, psi); x0 only adds.
constexpr int kOde = 5;
using Jet = ceres::Jet<double, kOde>;
// (z[3], x[2]) and their derivatives with respect to the kOde parameters, component-major.
using TrackState = std::array<double, 5 * (1 + kOde)>;

/// The start (z0, K) of the ODE from (lambda, mu, theta, phi, psi): eqs. (12)-(18) (PhaseFromTrig)
/// and K = omega_h + (lambda - 1) v0 z_h (MomentumFromOmega).
std::array<double, 5> StartOf(const double* p) {
  const AngleState s{p[2], p[3], p[4]};
  const PhaseVariables ph = PhaseFromTrig(TrigFromAngles(s), p[1], p[0]);
  double k[2];
  MomentumFromOmega(ph.z.data(), ph.omega.data(), ph.v0, p[0], k);
  return {ph.z.x(), ph.z.y(), ph.z.z(), k[0], k[1]};
}

/// d(z0, K)/d(lambda, mu, theta, phi, psi) by the fourth-order central difference of the closed
/// form StartOf (truncation ~h^4 ~ 1e-12 relative at h = 1e-3 of the scale, rounding ~1e-13):
/// the chart's formulas are written once, in double, in PhaseFromTrig.
void StartDerivatives(const double* p, double d[5][kOde]) {
  for (int j = 0; j < kOde; ++j) {
    const double h = j < 2 ? 1e-3 * p[j] : 1e-3;  // lambda, mu > 0: relative; angles: absolute
    std::array<double, 5> f[4];
    const double offsets[4] = {-2.0, -1.0, 1.0, 2.0};
    for (int m = 0; m < 4; ++m) {
      double q[kOde] = {p[0], p[1], p[2], p[3], p[4]};
      q[j] += offsets[m] * h;
      f[m] = StartOf(q);
    }
    for (int i = 0; i < 5; ++i) d[i][j] = (f[0][i] - 8.0 * f[1][i] + 8.0 * f[2][i] - f[3][i]) / (12.0 * h);
  }
}

/// OmegaFromZK and ZxRhs on Jets: the value and the variational equations together.
struct TrackSensitivityRhs {
  Jet lambda;
  Jet k[2];
  void operator()(const TrackState& y, TrackState& dy, double /*t*/) const {
    Jet z[3];
    for (int i = 0; i < 3; ++i) {
      z[i].a = y[i];
      for (int j = 0; j < kOde; ++j) z[i].v[j] = y[5 + kOde * i + j];
    }
    Jet w[2], d[5];
    OmegaFromZK(z, k, lambda, w);
    ZxRhs(z, w, d, d + 3);
    for (int i = 0; i < 5; ++i) {
      dy[i] = d[i].a;
      for (int j = 0; j < kOde; ++j) dy[5 + kOde * i + j] = d[i].v[j];
    }
  }
};

double FirstStep(double mu) { return 2.0 * M_PI / std::sqrt(mu) / 64.0; }

void ValuesOnly(const double* q, const double* tau, std::size_t n, const IntegrationOptions& options, double* x_out) {
  const std::array<double, 5> s = StartOf(q);
  const MotionRhs rhs{q[0], {s[3], s[4]}};
  const MotionState y0{s[0], s[1], s[2], 0.0, 0.0};
  IntegrateDenseAtTimes(rhs, y0, tau, n, FirstStep(q[1]), options, [&](std::size_t i, const MotionState& y) {
    x_out[2 * i] = q[5] + y[3];
    x_out[2 * i + 1] = q[6] + y[4];
  });
}

}  // namespace

void EvaluateTrack(const double* q, const double* tau, std::size_t n, const IntegrationOptions& options,
                   double* x_out, double* jacobian, const IntegrationOptions* jacobian_options) {
  ValuesOnly(q, tau, n, options, x_out);
  if (jacobian == nullptr) return;
  const std::array<double, 5> s = StartOf(q);
  double d[5][kOde];
  StartDerivatives(q, d);
  TrackSensitivityRhs rhs;
  rhs.lambda = Jet(q[0], 0);
  for (int c = 0; c < 2; ++c) {
    rhs.k[c].a = s[3 + c];
    for (int j = 0; j < kOde; ++j) rhs.k[c].v[j] = d[3 + c][j];
  }
  TrackState y0{};
  for (int i = 0; i < 3; ++i) {
    y0[i] = s[i];
    for (int j = 0; j < kOde; ++j) y0[5 + kOde * i + j] = d[i][j];
  }
  IntegrateDenseAtTimes(rhs, y0, tau, n, FirstStep(q[1]), jacobian_options != nullptr ? *jacobian_options : options,
                        [&](std::size_t i, const TrackState& y) {
    for (int c = 0; c < 2; ++c) {
      double* row = jacobian + (2 * i + c) * kTrackParameters;
      for (int j = 0; j < kOde; ++j) row[j] = y[5 + kOde * (3 + c) + j];
      row[5] = c == 0 ? 1.0 : 0.0;
      row[6] = c == 1 ? 1.0 : 0.0;
    }
  });
}

}  // namespace plateball::internal
