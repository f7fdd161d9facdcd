#include "identify_model.h"

#include <array>
#include <cmath>
#include <vector>

#include "dynamics.h"
#include "exact_chain.h"
#include "kinematics.h"

namespace plateball::internal {
namespace {

// The parameters that enter the equations of motion: (lambda, mu, theta, phi, psi); x0 only adds.
constexpr int kOde = 5;
using Jet = ceres::Jet<double, kOde>;

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

/// OmegaFromZK and ZxRhs on Jets of N directions: the value and the variational equations
/// together, state (z[3], x[2]) and their derivatives, component-major.
template <int N>
struct SensitivityRhs {
  using J = ceres::Jet<double, N>;
  using State = std::array<double, 5 * (1 + N)>;
  J lambda;
  J k[2];
  void operator()(const State& y, State& dy, double /*t*/) const {
    J z[3];
    for (int i = 0; i < 3; ++i) {
      z[i].a = y[i];
      for (int j = 0; j < N; ++j) z[i].v[j] = y[5 + N * i + j];
    }
    J w[2], d[5];
    OmegaFromZK(z, k, lambda, w);
    ZxRhs(z, w, d, d + 3);
    for (int i = 0; i < 5; ++i) {
      dy[i] = d[i].a;
      for (int j = 0; j < N; ++j) dy[5 + N * i + j] = d[i].v[j];
    }
  }
};
using TrackSensitivityRhs = SensitivityRhs<kOde>;

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

/// The samples of each flight: sample i belongs to flight f = the number of impulses strictly
/// before tau_i. first[f] .. first[f + 1] are its indices (m + 2 entries).
std::vector<std::size_t> FlightBounds(const double* tau, std::size_t n, const std::vector<double>& impulse_tau) {
  std::vector<std::size_t> first{0};
  std::size_t i = 0;
  for (double t : impulse_tau) {
    while (i < n && tau[i] <= t) ++i;
    first.push_back(i);
  }
  first.push_back(n);
  return first;
}

/// The times of flight f relative to its start: 0 (IntegrateDenseAtTimes starts at the first
/// time), its samples, then the next impulse (if any).
std::vector<double> FlightTimes(const double* tau, const std::vector<std::size_t>& first,
                                const std::vector<double>& impulse_tau, std::size_t f, double start) {
  std::vector<double> times{0.0};
  for (std::size_t i = first[f]; i < first[f + 1]; ++i) times.push_back(tau[i] - start);
  if (f < impulse_tau.size()) times.push_back(impulse_tau[f] - start);
  return times;
}

/// The values: flight by flight, the impulse applied to K at each flight's end (z and x
/// continuous); the flight starts into *flights.
void ImpulsiveValues(const double* q, const double* tau, std::size_t n, const std::vector<double>& impulse_tau,
                     const IntegrationOptions& options, double* x_out, std::vector<FlightStart>* flights, double* spin) {
  const std::array<double, 5> s = StartOf(q);
  FlightStart node{0.0, {s[0], s[1], s[2]}, {s[3], s[4]}, {q[5], q[6]}};
  const std::vector<std::size_t> first = FlightBounds(tau, n, impulse_tau);
  flights->clear();
  for (std::size_t f = 0; f <= impulse_tau.size(); ++f) {
    flights->push_back(node);
    const std::vector<double> times = FlightTimes(tau, first, impulse_tau, f, node.tau);
    const std::size_t samples = first[f + 1] - first[f];
    const MotionRhs rhs{q[0], {node.k.x(), node.k.y()}};
    MotionState end{};
    IntegrateDenseAtTimes(rhs, MotionState{node.z.x(), node.z.y(), node.z.z(), 0.0, 0.0}, times.data(), times.size(),
                          FirstStep(q[1]), options, [&](std::size_t j, const MotionState& y) {
      if (j-- == 0) return;  // the flight's start
      if (j < samples) {
        x_out[2 * (first[f] + j)] = node.x.x() + y[3];
        x_out[2 * (first[f] + j) + 1] = node.x.y() + y[4];
        if (spin != nullptr) spin[first[f] + j] = AxialSpinFromZK(y.data(), node.k.data(), q[0]);
      } else {
        end = y;
      }
    });
    if (f == impulse_tau.size()) break;
    FlightStart next{impulse_tau[f], {end[0], end[1], end[2]}, {}, node.x + Eigen::Vector2d(end[3], end[4])};
    ImpulseMomentum(next.z.data(), node.k.data(), q[7 + f], q[0], next.k.data());
    node = next;
  }
}

/// d K_after / d(z (3), K_before (2), s, lambda) of the impulse (ImpulseMomentum on Jets).
Eigen::Matrix<double, 2, 7> ImpulseDerivatives(const Eigen::Vector3d& z, const Eigen::Vector2d& k, double s, double lambda) {
  using J = ceres::Jet<double, 7>;
  const J zj[3] = {J(z.x(), 0), J(z.y(), 1), J(z.z(), 2)};
  const J kj[2] = {J(k.x(), 3), J(k.y(), 4)};
  J out[2];
  ImpulseMomentum(zj, kj, J(s, 5), J(lambda, 6), out);
  Eigen::Matrix<double, 2, 7> g;
  for (int i = 0; i < 2; ++i) g.row(i) = out[i].v.transpose();
  return g;
}

/// The chain rule over the flights. D (7 x P) holds d(z, K, x)/dq at the current flight's
/// start; each flight's variational equations give the derivatives of its samples and its end
/// with respect to its start (z, K) and lambda: the local directions, mapped to q by L (6 x P).
void ImpulsiveJacobian(const double* q, const double* tau, std::size_t n, const std::vector<double>& impulse_tau,
                       const IntegrationOptions& options, const std::vector<FlightStart>& flights, double* jacobian,
                       double* spin_jacobian) {
  using Rhs = SensitivityRhs<6>;
  const Eigen::Index p = kTrackParameters + static_cast<Eigen::Index>(impulse_tau.size());
  Eigen::MatrixXd d = Eigen::MatrixXd::Zero(7, p);
  double d0[5][kOde];
  StartDerivatives(q, d0);
  for (int i = 0; i < 5; ++i)
    for (int j = 0; j < kOde; ++j) d(i, j) = d0[i][j];
  d(5, 5) = d(6, 6) = 1.0;
  const std::vector<std::size_t> first = FlightBounds(tau, n, impulse_tau);
  using RowMajor = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;
  Eigen::Map<RowMajor> jac(jacobian, static_cast<Eigen::Index>(2 * n), p);
  Eigen::Map<RowMajor> spin_jac(spin_jacobian, spin_jacobian != nullptr ? static_cast<Eigen::Index>(n) : 0, p);
  for (std::size_t f = 0; f < flights.size(); ++f) {
    const FlightStart& node = flights[f];
    Eigen::MatrixXd local(6, p);
    local.topRows(5) = d.topRows(5);
    local.row(5).setZero();
    local(5, 0) = 1.0;
    Rhs rhs;
    rhs.lambda = Rhs::J(q[0], 5);
    for (int c = 0; c < 2; ++c) rhs.k[c] = Rhs::J(node.k[c], 3 + c);
    Rhs::State y0{};
    for (int i = 0; i < 3; ++i) {
      y0[static_cast<std::size_t>(i)] = node.z[i];
      y0[static_cast<std::size_t>(5 + 6 * i + i)] = 1.0;
    }
    const std::vector<double> times = FlightTimes(tau, first, impulse_tau, f, node.tau);
    const std::size_t samples = first[f + 1] - first[f];
    Eigen::Matrix<double, 5, 6> end = Eigen::Matrix<double, 5, 6>::Zero();  // d(z, x)_end / d local
    IntegrateDenseAtTimes(rhs, y0, times.data(), times.size(), FirstStep(q[1]), options, [&](std::size_t j, const Rhs::State& y) {
      if (j-- == 0) return;  // the flight's start
      Eigen::Matrix<double, 5, 6> g;
      for (int i = 0; i < 5; ++i)
        for (int k = 0; k < 6; ++k) g(i, k) = y[static_cast<std::size_t>(5 + 6 * i + k)];
      if (j < samples) {
        jac.middleRows(static_cast<Eigen::Index>(2 * (first[f] + j)), 2) = g.bottomRows(2) * local + d.bottomRows(2);
        if (spin_jacobian != nullptr) {
          // v0 on Jets of the local directions: z from the state, K and lambda the directions 3-5.
          Rhs::J z[3];
          for (int i = 0; i < 3; ++i) {
            z[i].a = y[static_cast<std::size_t>(i)];
            z[i].v = g.row(i).transpose();
          }
          spin_jac.row(static_cast<Eigen::Index>(first[f] + j)) = AxialSpinFromZK(z, rhs.k, rhs.lambda).v.transpose() * local;
        }
      } else {
        end = g;
      }
    });
    if (f + 1 == flights.size()) break;
    const FlightStart& next = flights[f + 1];
    const Eigen::Matrix<double, 2, 7> g = ImpulseDerivatives(next.z, node.k, q[7 + f], q[0]);
    Eigen::MatrixXd dn(7, p);
    dn.topRows(3) = end.topRows(3) * local;
    dn.middleRows(3, 2) = g.leftCols(3) * dn.topRows(3) + g.middleCols(3, 2) * d.middleRows(3, 2);
    dn.middleRows(3, 2).col(7 + static_cast<Eigen::Index>(f)) += g.col(5);
    dn.middleRows(3, 2).col(0) += g.col(6);
    dn.bottomRows(2) = d.bottomRows(2) + end.bottomRows(2) * local;
    d = dn;
  }
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
  TrackSensitivityRhs::State y0{};
  for (int i = 0; i < 3; ++i) {
    y0[i] = s[i];
    for (int j = 0; j < kOde; ++j) y0[5 + kOde * i + j] = d[i][j];
  }
  IntegrateDenseAtTimes(rhs, y0, tau, n, FirstStep(q[1]), jacobian_options != nullptr ? *jacobian_options : options,
                        [&](std::size_t i, const TrackSensitivityRhs::State& y) {
    for (int c = 0; c < 2; ++c) {
      double* row = jacobian + (2 * i + c) * kTrackParameters;
      for (int j = 0; j < kOde; ++j) row[j] = y[5 + kOde * (3 + c) + j];
      row[5] = c == 0 ? 1.0 : 0.0;
      row[6] = c == 1 ? 1.0 : 0.0;
    }
  });
}

void EvaluateImpulsiveTrack(const double* q, const double* tau, std::size_t n, const std::vector<double>& impulse_tau,
                            const IntegrationOptions& options, double* x_out, double* jacobian,
                            const IntegrationOptions* jacobian_options, std::vector<FlightStart>* flights,
                            const SpinOutput* spin) {
  if (impulse_tau.empty() && flights == nullptr && spin == nullptr) {
    EvaluateTrack(q, tau, n, options, x_out, jacobian, jacobian_options);
    return;
  }
  std::vector<FlightStart> own;
  std::vector<FlightStart>* nodes = flights != nullptr ? flights : &own;
  ImpulsiveValues(q, tau, n, impulse_tau, options, x_out, nodes, spin != nullptr ? spin->values : nullptr);
  if (jacobian != nullptr)
    ImpulsiveJacobian(q, tau, n, impulse_tau, jacobian_options != nullptr ? *jacobian_options : options, *nodes, jacobian,
                      spin != nullptr ? spin->jacobian : nullptr);
}

}  // namespace plateball::internal
