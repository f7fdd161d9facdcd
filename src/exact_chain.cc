#include "exact_chain.h"

#include <ceres/jet.h>

#include <algorithm>
#include <array>

#include "dynamics.h"
#include "plateball/so3.h"

namespace plateball::internal {
namespace {

// (z, x, Phi) = 14 values, then the derivatives with respect to p = (z0 (3), K (2)) of z, x and the
// rotation, 8 x 5 row by row: y[14 + 5 i + j] = d y_i / d p_j for i < 5 (z, x), and for i = 5..7
// the rotation's derivative as three numbers, eta_j with dPhi/dp_j = hat(eta_j) Phi. From
// Phi' = hat(omega) Phi: eta_j' = d omega/dp_j + omega x eta_j, eta_j(0) = 0 (Phi(0) = I), 54 values
// where the nine entries of dPhi/dp_j would take 84.
constexpr int kValues = 14;
constexpr int kParams = 5;
constexpr int kTracked = 8;  // z (3), x (2), eta (3)
using ArcSensState = std::array<double, kValues + kTracked * kParams>;

// The right-hand side written out in forward mode for the five parameters at once, line by line
// as SensitivityRhs (dynamics.h) does for one: OmegaFromZK, ZxRhs and RotationRhs for the values,
// their derivatives for z and x, and eta' = d omega + omega x eta (ExactChain tests check the
// Jacobian against central differences).
struct ArcSensRhs {
  double lambda;
  double k[2];
  void operator()(const ArcSensState& y, ArcSensState& dy, double /*t*/) const {
    const double z0 = y[0], z1 = y[1], z2 = y[2];
    // v0 = p / q with p = <K, z_h>, q = z3^2 + lambda |z_h|^2 (OmegaFromZK).
    const double p = k[0] * z0 + k[1] * z1;
    const double q = z2 * z2 + lambda * (z0 * z0 + z1 * z1);
    const double inv_q = 1.0 / q;
    const double v0 = p * inv_q;
    const double c = lambda - 1.0;
    const double w0 = k[0] - c * v0 * z0, w1 = k[1] - c * v0 * z1;
    dy[0] = w1 * z2;
    dy[1] = -w0 * z2;
    dy[2] = w0 * z1 - w1 * z0;
    dy[3] = w1;
    dy[4] = -w0;
    RotationRhs(w0, w1, y.data() + 5, dy.data() + 5);
    const double* d = y.data() + kValues;  // d[kParams * i + j] = d y_i / d p_j
    double* dd = dy.data() + kValues;
    for (int j = 0; j < kParams; ++j) {
      const double d0 = d[j], d1 = d[kParams + j], d2 = d[2 * kParams + j];
      const double dk0 = j == 3 ? 1.0 : 0.0, dk1 = j == 4 ? 1.0 : 0.0;  // p_3, p_4 = K
      const double dp = dk0 * z0 + k[0] * d0 + dk1 * z1 + k[1] * d1;
      const double dq = 2.0 * (z2 * d2 + lambda * (z0 * d0 + z1 * d1));
      const double dv0 = (dp - v0 * dq) * inv_q;
      const double dw0 = dk0 - c * (dv0 * z0 + v0 * d0), dw1 = dk1 - c * (dv0 * z1 + v0 * d1);
      dd[j] = dw1 * z2 + w1 * d2;
      dd[kParams + j] = -(dw0 * z2 + w0 * d2);
      dd[2 * kParams + j] = dw0 * z1 + w0 * d1 - (dw1 * z0 + w1 * d0);
      dd[3 * kParams + j] = dw1;
      dd[4 * kParams + j] = -dw0;
      // eta' = d omega + omega x eta with omega = (w0, w1, 0).
      const double e0 = d[5 * kParams + j], e1 = d[6 * kParams + j], e2 = d[7 * kParams + j];
      dd[5 * kParams + j] = dw0 + w1 * e2;
      dd[6 * kParams + j] = dw1 - w0 * e2;
      dd[7 * kParams + j] = w0 * e1 - w1 * e0;
    }
  }
};

// The arc's end (z, x, Phi row-major) and its Jacobian with respect to (z0, K, t): rows z (3), x (2)
// and eta (3, dPhi = hat(eta) Phi), the last column d/dt (eta: omega at the end).
struct ArcDerivative {
  Eigen::Matrix<double, kValues, 1> end;
  Eigen::Matrix<double, kTracked, kParams + 1> d;
};

// `step` (optional): in, the first step to try (0: the whole arc); out, the arc's largest accepted
// step when it took more than one, else 0.
ArcDerivative DifferentiateArc(double lambda,
                               const Eigen::Vector3d& z0,
                               const Eigen::Vector2d& k,
                               double t,
                               const IntegrationOptions& options,
                               double* step = nullptr) {
  ArcSensState y{};
  for (int i = 0; i < 3; ++i) {
    y[i] = z0[i];
    y[kValues + kParams * i + i] = 1.0;
  }
  y[5] = y[9] = y[13] = 1.0;
  const ArcSensRhs rhs{lambda, {k.x(), k.y()}};
  namespace odeint = boost::numeric::odeint;
  const double first = step && *step > 0 ? std::min(*step, t) : t;
  double largest = 0.0, reached = 0.0;
  if (t > 0)
    IntegrateAdaptive<odeint::runge_kutta_fehlberg78<ArcSensState>>(
        rhs, y, 0.0, t, first, options, [&](double now, const auto&) {
          largest = std::max(largest, now - reached);
          reached = now;
        });
  if (step) *step = largest < t ? largest : 0.0;
  ArcSensState f{};
  rhs(y, f, t);
  ArcDerivative out;
  for (int i = 0; i < kValues; ++i) out.end[i] = y[i];
  for (int i = 0; i < kTracked; ++i)
    for (int j = 0; j < kParams; ++j) out.d(i, j) = y[kValues + kParams * i + j];
  for (int i = 0; i < 5; ++i) out.d(i, kParams) = f[i];
  double w[2];
  OmegaFromZK(y.data(), k.data(), lambda, w);
  out.d.col(kParams).tail<3>() << w[0], w[1], 0.0;
  return out;
}

// dK_after / d(z (3), K_before (2), s) of the impulse.
Eigen::Matrix<double, 2, 6> DifferentiateImpulse(const Eigen::Vector3d& z,
                                                 const Eigen::Vector2d& k,
                                                 double s,
                                                 double lambda) {
  using Jet = ceres::Jet<double, 6>;
  const Jet zj[3] = {Jet(z.x(), 0), Jet(z.y(), 1), Jet(z.z(), 2)};
  const Jet kj[2] = {Jet(k.x(), 3), Jet(k.y(), 4)};
  Jet out[2];
  ImpulseMomentum(zj, kj, Jet(s, 5), lambda, out);
  Eigen::Matrix<double, 2, 6> g;
  for (int i = 0; i < 2; ++i) g.row(i) = out[i].v.transpose();
  return g;
}

// One free arc from (z0, K) over [0, t]: Fehlberg 7(8) (the rollouts run at 1e-14, where an
// eighth-order method takes a fraction of dopri5's steps), no speed tracking.
FullState RollArc(
    double lambda, const Eigen::Vector3d& z0, const Eigen::Vector2d& k, double t, const IntegrationOptions& options) {
  namespace odeint = boost::numeric::odeint;
  FullState y = InitialFullState(z0);
  const FullRhs rhs{lambda, {k.x(), k.y()}};
  if (t > 0)
    IntegrateAdaptive<odeint::runge_kutta_fehlberg78<FullState>>(
        rhs, y, 0.0, t, t, options, [](double, const auto&) {});
  return y;
}

// (z, length) with z' = omega x z, length' = |x'| = |omega_h|.
struct LengthRhs {
  double lambda;
  double k[2];
  void operator()(const std::array<double, 4>& y, std::array<double, 4>& dy, double /*t*/) const {
    double w[2], dx[2];
    OmegaFromZK(y.data(), k, lambda, w);
    ZxRhs(y.data(), w, dy.data(), dx);
    dy[3] = std::hypot(w[0], w[1]);
  }
};

}  // namespace

double ChainPathLength(double lambda,
                       const std::vector<ChainNode>& nodes,
                       const Eigen::VectorXd& u,
                       const IntegrationOptions& integration) {
  const int n = static_cast<int>(u.size() / 2);
  double length = 0.0;
  for (int k = 0; k < n; ++k) {
    const ChainNode& a = nodes[static_cast<std::size_t>(k)];
    const Eigen::Vector2d& kk = nodes[static_cast<std::size_t>(k) + 1].k;  // the arc's K
    std::array<double, 4> y{a.z.x(), a.z.y(), a.z.z(), 0.0};
    if (u[n + k] > 0) IntegrateAdaptive(LengthRhs{lambda, {kk.x(), kk.y()}}, y, 0.0, u[n + k], u[n + k], integration);
    length += y[3];
  }
  return length;
}

Eigen::Matrix3d LeftJacobianInverse(const Eigen::Vector3d& phi) {
  const double th = phi.norm();
  const Eigen::Matrix3d h = Hat(phi);
  // 1/th^2 - (1 + cos th)/(2 th sin th) -> 1/12 as th -> 0.
  const double c =
      th < 1e-4 ? 1.0 / 12.0 + th * th / 720.0 : 1.0 / (th * th) - (1.0 + std::cos(th)) / (2.0 * th * std::sin(th));
  return Eigen::Matrix3d::Identity() - 0.5 * h + c * h * h;
}

Eigen::Matrix<double, 5, 1> ArrivalResidual(const ChainNode& end,
                                            const Eigen::Vector2d& x1,
                                            const Eigen::Matrix3d& A1) {
  Eigen::Matrix<double, 5, 1> r;
  r.head<2>() = end.x - x1;
  r.tail<3>() = LogSO3(A1.transpose() * end.A);
  return r;
}

Eigen::MatrixXd ArrivalJacobian(const ChainJacobian& jacobian, const ChainNode& end, const Eigen::Matrix3d& A1) {
  Eigen::MatrixXd j(5, jacobian.rotation.cols());
  j.topRows<2>() = jacobian.dx.back();
  // A_n -> exp(hat d) A_n turns A1^T A_n into exp(hat(A1^T d)) A1^T A_n.
  j.bottomRows<3>() = LeftJacobianInverse(LogSO3(A1.transpose() * end.A)) * A1.transpose() * jacobian.rotation;
  return j;
}

void RollChain(double lambda,
               const Eigen::VectorXd& u,
               const IntegrationOptions& integration,
               std::vector<ChainNode>* nodes,
               ChainJacobian* jacobian,
               const ChainColumns* columns) {
  const int n = static_cast<int>(u.size() / 2);
  nodes->resize(static_cast<std::size_t>(n) + 1);
  const int cols = columns ? columns->columns : 2 * n;
  const auto s_column = [&](int k) { return columns ? columns->s_column[static_cast<std::size_t>(k)] : k; };
  const auto t_column = [&](int k) { return columns ? columns->t_column[static_cast<std::size_t>(k)] : n + k; };
  const auto t_scale = [&](int k) { return columns ? columns->t_scale[static_cast<std::size_t>(k)] : 1.0; };
  // Derivatives of the node state: z (3), K before (2), x (2), and delta (3) with dA = hat(delta) A.
  Eigen::MatrixXd dz = Eigen::MatrixXd::Zero(3, cols), dk = Eigen::MatrixXd::Zero(2, cols);
  Eigen::MatrixXd dxk = Eigen::MatrixXd::Zero(2, cols), delta = Eigen::MatrixXd::Zero(3, cols);
  if (jacobian) {
    jacobian->dx.assign(1, dxk);
    jacobian->dz.assign(1, dz);
    jacobian->dk.assign(1, dk);
  }
  // With columns (a chain cut into sub-arcs), each sub-arc's first step is the largest its
  // predecessor took when that one needed several (the whole sub-arc otherwise): a sub-arc as long
  // as the step allows is then not first tried at its whole length and rejected.
  double step = 0.0;
  for (int k = 0; k < n; ++k) {
    ChainNode& a = (*nodes)[static_cast<std::size_t>(k)];
    Eigen::Vector2d k_after;
    ImpulseMomentum(a.z.data(), a.k.data(), u[k], lambda, k_after.data());
    ArcDerivative arc_d;
    if (jacobian) {
      arc_d = DifferentiateArc(lambda, a.z, k_after, u[n + k], integration, columns ? &step : nullptr);
    } else {
      const FullState arc = RollArc(lambda, a.z, k_after, u[n + k], integration);
      for (int i = 0; i < kValues; ++i) arc_d.end[i] = arc[static_cast<std::size_t>(i)];
    }
    const Eigen::Matrix3d phi = MatrixFromRowMajor(arc_d.end.data() + 5);
    ChainNode& b = (*nodes)[static_cast<std::size_t>(k) + 1];
    b.z = arc_d.end.head<3>().normalized();
    b.k = k_after;
    b.x = a.x + arc_d.end.segment<2>(3);
    b.A = ProjectToSO3(phi * a.A);
    if (!jacobian) continue;
    const Eigen::Matrix<double, 2, 6> g = DifferentiateImpulse(a.z, a.k, u[k], lambda);
    Eigen::MatrixXd dk_after = g.leftCols<3>() * dz + g.middleCols<2>(3) * dk;
    if (s_column(k) >= 0) dk_after.col(s_column(k)) += g.col(5);
    Eigen::MatrixXd dy = arc_d.d.leftCols<3>() * dz + arc_d.d.middleCols<2>(3) * dk_after;  // 8 x cols
    dy.col(t_column(k)) += arc_d.d.col(kParams) * t_scale(k);
    // A_{k+1} = Phi A_k: dA_{k+1} = hat(eta) Phi A_k + Phi hat(delta_k) A_k = hat(eta + Phi delta_k) A_{k+1}.
    delta = dy.bottomRows<3>() + phi * delta;
    dz = dy.topRows<3>();
    dxk += dy.middleRows<2>(3);
    dk = dk_after;
    jacobian->dx.push_back(dxk);
    jacobian->dz.push_back(dz);
    jacobian->dk.push_back(dk);
  }
  if (jacobian) jacobian->rotation = delta;
}

}  // namespace plateball::internal
