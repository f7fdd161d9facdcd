#include "identify_model.h"

#include <array>
#include <cmath>
#include <type_traits>
#include <vector>

#include "dynamics.h"
#include "exact_chain.h"
#include "kinematics.h"
#include "plateball/so3.h"

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
struct MotionSensitivityRhs {
  using J = ceres::Jet<double, N>;
  static constexpr int kS = 5;
  using State = std::array<double, 5 * (1 + N)>;
  J lambda;
  J k[2];
  // The inner loop of every Jacobian: the Jet arithmetic inlined whole (GCC stops inlining it
  // when the translation unit grows; measured 9% of T8).
  [[gnu::flatten]] void operator()(const State& y, State& dy, double /*t*/) const {
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

/// The same with the fundamental matrix Phi' = hat(omega) Phi (RotationRhs): state (z[3], x[2],
/// Phi[9] row-major) and their derivatives, component-major.
template <int N>
struct FrameSensitivityRhs {
  using J = ceres::Jet<double, N>;
  static constexpr int kS = 14;
  using State = std::array<double, kS*(1 + N)>;
  J lambda;
  J k[2];
  void operator()(const State& y, State& dy, double /*t*/) const {
    J v[kS];  // x (entries 3, 4) is not read by the right-hand side
    for (int i = 0; i < kS; ++i) {
      if (i == 3) i = 5;
      v[i].a = y[static_cast<std::size_t>(i)];
      for (int j = 0; j < N; ++j) v[i].v[j] = y[static_cast<std::size_t>(kS + N * i + j)];
    }
    J w[2], d[kS];
    OmegaFromZK(v, k, lambda, w);
    ZxRhs(v, w, d, d + 3);
    RotationRhs(w[0], w[1], v + 5, d + 5);
    for (int i = 0; i < kS; ++i) {
      dy[static_cast<std::size_t>(i)] = d[i].a;
      for (int j = 0; j < N; ++j) dy[static_cast<std::size_t>(kS + N * i + j)] = d[i].v[j];
    }
  }
};

template <int N, bool Frame>
using SensitivityRhs = std::conditional_t<Frame, FrameSensitivityRhs<N>, MotionSensitivityRhs<N>>;
using TrackSensitivityRhs = MotionSensitivityRhs<kOde>;

using RowMajor3 = Eigen::Matrix<double, 3, 3, Eigen::RowMajor>;

Eigen::Matrix3d Rz(double a) {
  return (Eigen::Matrix3d() << std::cos(a), -std::sin(a), 0, std::sin(a), std::cos(a), 0, 0, 0, 1).finished();
}
Eigen::Matrix3d Ry(double a) {
  return (Eigen::Matrix3d() << std::cos(a), 0, std::sin(a), 0, 1, 0, -std::sin(a), 0, std::cos(a)).finished();
}

/// vee of the skew part of m.
Eigen::Vector3d VeeSkew(const Eigen::Matrix3d& m) {
  return 0.5 * Eigen::Vector3d(m(2, 1) - m(1, 2), m(0, 2) - m(2, 0), m(1, 0) - m(0, 1));
}

/// The frame at the start and its derivatives: dA0/dq (9 x p, row-major entries) for
/// A0 = Rz(phi) Ry(theta) Rz(chi), chi = q[7].
Eigen::MatrixXd StartFrameDerivatives(const double* q, Eigen::Index p) {
  const double chi = q[7];
  const Eigen::Matrix3d e3 = Hat(Eigen::Vector3d::UnitZ()), e2 = Hat(Eigen::Vector3d::UnitY());
  const Eigen::Matrix3d a0 = StartFrame(q[2], q[3], chi);
  Eigen::MatrixXd da = Eigen::MatrixXd::Zero(9, p);
  const Eigen::Matrix3d d[3] = {Rz(q[3]) * e2 * Ry(q[2]) * Rz(chi), e3 * a0, a0 * e3};
  const Eigen::Index col[3] = {2, 3, 7};
  for (int k = 0; k < 3; ++k) da.col(col[k]) = Eigen::Map<const Eigen::Matrix<double, 9, 1>>(RowMajor3(d[k]).data());
  return da;
}

/// Column c of a 9 x p matrix of row-major entries as a 3 x 3 matrix.
Eigen::Matrix3d EntryColumn(const Eigen::MatrixXd& m, Eigen::Index c) {
  RowMajor3 r;
  for (int i = 0; i < 9; ++i) r.data()[i] = m(i, c);
  return r;
}

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
std::vector<double> FlightTimes(const double* tau,
                                const std::vector<std::size_t>& first,
                                const std::vector<double>& impulse_tau,
                                std::size_t f,
                                double start) {
  std::vector<double> times{0.0};
  for (std::size_t i = first[f]; i < first[f + 1]; ++i) times.push_back(tau[i] - start);
  if (f < impulse_tau.size()) times.push_back(impulse_tau[f] - start);
  return times;
}

/// One flight of ImpulsiveValues on the state (z, x) (MotionRhs) or (z, x, Phi) (FullRhs): the
/// samples first .. first + samples - 1 from the flight's times, the state at its end into *end.
template <typename State, typename Rhs>
void ValuesOfFlight(const double* q,
                    const Rhs& rhs,
                    const State& y0,
                    const FlightStart& node,
                    const std::vector<double>& times,
                    std::size_t first,
                    std::size_t samples,
                    double* x_out,
                    const BodyOutput* body,
                    State* end,
                    const IntegrationOptions& options) {
  IntegrateDenseAtTimes(
      rhs, y0, times.data(), times.size(), FirstStep(q[1]), options, [&](std::size_t j, const State& y) {
        if (j-- == 0) return;  // the flight's start
        if (j >= samples) {
          *end = y;
          return;
        }
        const std::size_t i = first + j;
        x_out[2 * i] = node.x.x() + y[3];
        x_out[2 * i + 1] = node.x.y() + y[4];
        if (body == nullptr) return;
        if (body->spin != nullptr) body->spin[i] = AxialSpinFromZK(y.data(), node.k.data(), q[0]);
        if constexpr (std::tuple_size_v<State> == 14) {
          const Eigen::Matrix3d a = MatrixFromRowMajor(y.data() + 5) * node.a;
          if (body->orientation != nullptr) RowMajorFromMatrix(a, body->orientation + 9 * i);
          double w[2];
          OmegaFromZK(y.data(), node.k.data(), q[0], w);
          if (body->body_rate != nullptr)
            Eigen::Map<Eigen::Vector3d>(body->body_rate + 3 * i) = a.transpose() * Eigen::Vector3d(w[0], w[1], 0.0);
        }
      });
}

/// The values: flight by flight, the impulse applied to K at each flight's end (z, x and the
/// frame continuous); the flight starts into *flights. With body->HasFrame() the fundamental
/// matrix Phi rides along (FullRhs): A(t) = Phi(t) A(flight start).
void ImpulsiveValues(const double* q,
                     const double* tau,
                     std::size_t n,
                     const std::vector<double>& impulse_tau,
                     const IntegrationOptions& options,
                     double* x_out,
                     std::vector<FlightStart>* flights,
                     const BodyOutput* body) {
  const std::array<double, 5> s = StartOf(q);
  const bool frame = body != nullptr && body->HasFrame();
  const std::size_t impulse0 = kTrackParameters + (frame ? 1 : 0);  // the first delta psi
  FlightStart node{0.0,
                   {s[0], s[1], s[2]},
                   {s[3], s[4]},
                   {q[5], q[6]},
                   frame ? StartFrame(q[2], q[3], q[7]) : Eigen::Matrix3d::Identity()};
  const std::vector<std::size_t> first = FlightBounds(tau, n, impulse_tau);
  flights->clear();
  for (std::size_t f = 0; f <= impulse_tau.size(); ++f) {
    flights->push_back(node);
    const std::vector<double> times = FlightTimes(tau, first, impulse_tau, f, node.tau);
    const std::size_t samples = first[f + 1] - first[f];
    FlightStart next;
    next.tau = f < impulse_tau.size() ? impulse_tau[f] : 0.0;
    if (frame) {
      FullState end{};
      ValuesOfFlight(q,
                     FullRhs{q[0], {node.k.x(), node.k.y()}},
                     InitialFullState(node.z),
                     node,
                     times,
                     first[f],
                     samples,
                     x_out,
                     body,
                     &end,
                     options);
      next.z = {end[0], end[1], end[2]};
      next.x = node.x + Eigen::Vector2d(end[3], end[4]);
      next.a = MatrixFromRowMajor(end.data() + 5) * node.a;
    } else {
      MotionState end{};
      ValuesOfFlight(q,
                     MotionRhs{q[0], {node.k.x(), node.k.y()}},
                     MotionState{node.z.x(), node.z.y(), node.z.z(), 0.0, 0.0},
                     node,
                     times,
                     first[f],
                     samples,
                     x_out,
                     body,
                     &end,
                     options);
      next.z = {end[0], end[1], end[2]};
      next.x = node.x + Eigen::Vector2d(end[3], end[4]);
    }
    if (f == impulse_tau.size()) break;
    ImpulseMomentum(next.z.data(), node.k.data(), q[impulse0 + f], q[0], next.k.data());
    node = next;
  }
}

/// d K_after / d(z (3), K_before (2), s, lambda) of the impulse (ImpulseMomentum on Jets).
Eigen::Matrix<double, 2, 7> ImpulseDerivatives(const Eigen::Vector3d& z,
                                               const Eigen::Vector2d& k,
                                               double s,
                                               double lambda) {
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
/// start, DA (9 x P) dA/dq of its frame (row-major entries; with body->HasFrame()); each
/// flight's variational equations give the derivatives of its samples and its end with respect
/// to its start (z, K) and lambda: the local directions, mapped to q by L (6 x P).
template <bool Frame>
void ImpulsiveJacobian(const double* q,
                       const double* tau,
                       std::size_t n,
                       const std::vector<double>& impulse_tau,
                       const IntegrationOptions& options,
                       const std::vector<FlightStart>& flights,
                       double* jacobian,
                       const BodyOutput* body) {
  using Rhs = SensitivityRhs<6, Frame>;
  constexpr int kS = Rhs::kS;
  constexpr Eigen::Index kImpulse0 = kTrackParameters + (Frame ? 1 : 0);  // the column of the first delta psi
  const Eigen::Index p = kImpulse0 + static_cast<Eigen::Index>(impulse_tau.size());
  Eigen::MatrixXd d = Eigen::MatrixXd::Zero(7, p);
  double d0[5][kOde];
  StartDerivatives(q, d0);
  for (int i = 0; i < 5; ++i)
    for (int j = 0; j < kOde; ++j) d(i, j) = d0[i][j];
  d(5, 5) = d(6, 6) = 1.0;
  Eigen::MatrixXd da = Frame ? StartFrameDerivatives(q, p) : Eigen::MatrixXd();
  const std::vector<std::size_t> first = FlightBounds(tau, n, impulse_tau);
  using RowMajor = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;
  auto rows = [&](double* m, std::size_t per_sample) {
    return Eigen::Map<RowMajor>(m, m != nullptr ? static_cast<Eigen::Index>(per_sample * n) : 0, p);
  };
  Eigen::Map<RowMajor> jac = rows(jacobian, 2);
  Eigen::Map<RowMajor> spin_jac = rows(body != nullptr ? body->spin_jacobian : nullptr, 1);
  Eigen::Map<RowMajor> frame_jac = rows(body != nullptr ? body->orientation_jacobian : nullptr, 3);
  Eigen::Map<RowMajor> rate_jac = rows(body != nullptr ? body->body_rate_jacobian : nullptr, 3);
  for (std::size_t f = 0; f < flights.size(); ++f) {
    const FlightStart& node = flights[f];
    Eigen::MatrixXd local(6, p);
    local.topRows(5) = d.topRows(5);
    local.row(5).setZero();
    local(5, 0) = 1.0;
    Rhs rhs;
    rhs.lambda = typename Rhs::J(q[0], 5);
    for (int c = 0; c < 2; ++c) rhs.k[c] = typename Rhs::J(node.k[c], 3 + c);
    typename Rhs::State y0{};
    for (int i = 0; i < 3; ++i) {
      y0[static_cast<std::size_t>(i)] = node.z[i];
      y0[static_cast<std::size_t>(kS + 6 * i + i)] = 1.0;
      if constexpr (Frame) y0[static_cast<std::size_t>(5 + 4 * i)] = 1.0;  // Phi(0) = I
    }
    const std::vector<double> times = FlightTimes(tau, first, impulse_tau, f, node.tau);
    const std::size_t samples = first[f + 1] - first[f];
    Eigen::Matrix<double, kS, 6> end = Eigen::Matrix<double, kS, 6>::Zero();  // d(z, x[, Phi])_end / d local
    RowMajor3 phi_end = RowMajor3::Identity();
    IntegrateDenseAtTimes(rhs,
                          y0,
                          times.data(),
                          times.size(),
                          FirstStep(q[1]),
                          options,
                          [&](std::size_t j, const typename Rhs::State& y) {
                            if (j-- == 0) return;  // the flight's start
                            Eigen::Matrix<double, kS, 6> g;
                            for (int i = 0; i < kS; ++i)
                              for (int k = 0; k < 6; ++k) g(i, k) = y[static_cast<std::size_t>(kS + 6 * i + k)];
                            if (j >= samples) {
                              end = g;
                              if constexpr (Frame) phi_end = MatrixFromRowMajor(y.data() + 5);
                              return;
                            }
                            const auto i = static_cast<Eigen::Index>(first[f] + j);
                            jac.middleRows(2 * i, 2) = g.middleRows(3, 2) * local + d.bottomRows(2);
                            // omega and v0 on Jets of the local directions: z from the state, K and lambda the
                            // directions 3-5.
                            typename Rhs::J z[3];
                            for (int c = 0; c < 3; ++c) {
                              z[c].a = y[static_cast<std::size_t>(c)];
                              z[c].v = g.row(c).transpose();
                            }
                            if (spin_jac.rows() > 0)
                              spin_jac.row(i) = AxialSpinFromZK(z, rhs.k, rhs.lambda).v.transpose() * local;
                            if constexpr (Frame) {
                              // A = Phi A_start: dA/dq_c = dPhi_c A_start + Phi dA_start_c.
                              const Eigen::Matrix3d phi = MatrixFromRowMajor(y.data() + 5), a = phi * node.a;
                              const Eigen::Matrix<double, 9, Eigen::Dynamic> dphi = g.template bottomRows<9>() * local;
                              typename Rhs::J w[2];
                              OmegaFromZK(z, rhs.k, rhs.lambda, w);
                              const Eigen::Vector3d omega(w[0].a, w[1].a, 0.0);
                              for (Eigen::Index c = 0; c < p; ++c) {
                                RowMajor3 dp;
                                for (int e = 0; e < 9; ++e) dp.data()[e] = dphi(e, c);
                                const Eigen::Matrix3d dac = dp * node.a + phi * EntryColumn(da, c);
                                if (frame_jac.rows() > 0)
                                  frame_jac.block(3 * i, c, 3, 1) = VeeSkew(a.transpose() * dac);
                                if (rate_jac.rows() > 0) {
                                  const Eigen::Vector3d dw(w[0].v.dot(local.col(c)), w[1].v.dot(local.col(c)), 0.0);
                                  rate_jac.block(3 * i, c, 3, 1) = dac.transpose() * omega + a.transpose() * dw;
                                }
                              }
                            }
                          });
    if (f + 1 == flights.size()) break;
    const FlightStart& next = flights[f + 1];
    const Eigen::Matrix<double, 2, 7> gi =
        ImpulseDerivatives(next.z, node.k, q[kImpulse0 + static_cast<Eigen::Index>(f)], q[0]);
    Eigen::MatrixXd dn(7, p);
    dn.topRows(3) = end.topRows(3) * local;
    dn.middleRows(3, 2) = gi.leftCols(3) * dn.topRows(3) + gi.middleCols(3, 2) * d.middleRows(3, 2);
    dn.middleRows(3, 2).col(kImpulse0 + static_cast<Eigen::Index>(f)) += gi.col(5);
    dn.middleRows(3, 2).col(0) += gi.col(6);
    dn.bottomRows(2) = d.bottomRows(2) + end.middleRows(3, 2) * local;
    if constexpr (Frame) {
      const Eigen::Matrix<double, 9, Eigen::Dynamic> dphi = end.template bottomRows<9>() * local;
      Eigen::MatrixXd dan(9, p);
      for (Eigen::Index c = 0; c < p; ++c) {
        RowMajor3 dp;
        for (int e = 0; e < 9; ++e) dp.data()[e] = dphi(e, c);
        const RowMajor3 dac = dp * node.a + phi_end * EntryColumn(da, c);
        dan.col(c) = Eigen::Map<const Eigen::Matrix<double, 9, 1>>(dac.data());
      }
      da = dan;
    }
    d = dn;
  }
}

}  // namespace

void EvaluateTrack(const double* q,
                   const double* tau,
                   std::size_t n,
                   const IntegrationOptions& options,
                   double* x_out,
                   double* jacobian,
                   const IntegrationOptions* jacobian_options) {
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
  IntegrateDenseAtTimes(rhs,
                        y0,
                        tau,
                        n,
                        FirstStep(q[1]),
                        jacobian_options != nullptr ? *jacobian_options : options,
                        [&](std::size_t i, const TrackSensitivityRhs::State& y) {
                          for (int c = 0; c < 2; ++c) {
                            double* row = jacobian + (2 * i + c) * kTrackParameters;
                            for (int j = 0; j < kOde; ++j) row[j] = y[5 + kOde * (3 + c) + j];
                            row[5] = c == 0 ? 1.0 : 0.0;
                            row[6] = c == 1 ? 1.0 : 0.0;
                          }
                        });
}

void EvaluateImpulsiveTrack(const double* q,
                            const double* tau,
                            std::size_t n,
                            const std::vector<double>& impulse_tau,
                            const IntegrationOptions& options,
                            double* x_out,
                            double* jacobian,
                            const IntegrationOptions* jacobian_options,
                            std::vector<FlightStart>* flights,
                            const BodyOutput* body) {
  if (impulse_tau.empty() && flights == nullptr && body == nullptr) {
    EvaluateTrack(q, tau, n, options, x_out, jacobian, jacobian_options);
    return;
  }
  std::vector<FlightStart> own;
  std::vector<FlightStart>* nodes = flights != nullptr ? flights : &own;
  ImpulsiveValues(q, tau, n, impulse_tau, options, x_out, nodes, body);
  if (jacobian == nullptr) return;
  const IntegrationOptions& jo = jacobian_options != nullptr ? *jacobian_options : options;
  if (body != nullptr && body->HasFrame())
    ImpulsiveJacobian<true>(q, tau, n, impulse_tau, jo, *nodes, jacobian, body);
  else
    ImpulsiveJacobian<false>(q, tau, n, impulse_tau, jo, *nodes, jacobian, body);
}

Eigen::Matrix3d StartFrame(double theta, double phi, double chi) { return Rz(phi) * Ry(theta) * Rz(chi); }

}  // namespace plateball::internal
