#include "dense_qp.h"

#include <Eigen/Dense>
#include <cmath>
#include <limits>
#include <vector>

#include "dense_solve.h"

namespace plateball::internal {

namespace {

// The KKT matrix of the equalities and the active rows W of A.
Eigen::MatrixXd Kkt(const Eigen::MatrixXd& H,
                    const Eigen::MatrixXd& E,
                    const Eigen::MatrixXd& A,
                    const std::vector<int>& active) {
  const Eigen::Index n = H.rows(), ne = E.rows(), na = static_cast<Eigen::Index>(active.size());
  Eigen::MatrixXd k = Eigen::MatrixXd::Zero(n + ne + na, n + ne + na);
  k.topLeftCorner(n, n) = H;
  k.block(n, 0, ne, n) = E;
  k.block(0, n, n, ne) = E.transpose();
  for (Eigen::Index i = 0; i < na; ++i) {
    k.block(n + ne + i, 0, 1, n) = A.row(active[static_cast<std::size_t>(i)]);
    k.block(0, n + ne + i, n, 1) = A.row(active[static_cast<std::size_t>(i)]).transpose();
  }
  return k;
}

}  // namespace

DenseQpResult SolveDenseQp(const Eigen::MatrixXd& H,
                           const Eigen::VectorXd& c,
                           const Eigen::MatrixXd& E,
                           const Eigen::VectorXd& e,
                           const Eigen::MatrixXd& A,
                           const Eigen::VectorXd& b,
                           double tolerance,
                           int max_changes) {
  const Eigen::Index n = H.rows(), ne = E.rows();
  DenseQpResult out;
  out.inequality_multipliers = Eigen::VectorXd::Zero(A.rows());
  // The equality-constrained minimum.
  std::vector<int> active;
  {
    Eigen::VectorXd rhs(n + ne);
    rhs << -c, e;
    const Eigen::VectorXd sol = FullPivLuSolve(Kkt(H, E, A, active), rhs);
    out.d = sol.head(n);
    out.equality_multipliers = sol.tail(ne);
    if (ne > 0 && (E * out.d - e).cwiseAbs().maxCoeff() > 1e-8 * (1.0 + e.cwiseAbs().maxCoeff())) return out;
  }
  std::vector<double> mu;  // multipliers of the active rows
  Eigen::VectorXd& d = out.d;
  Eigen::VectorXd& nu = out.equality_multipliers;
  while (out.changes < max_changes) {
    // The most violated inactive row.
    int p = -1;
    double worst = tolerance;
    for (Eigen::Index i = 0; i < A.rows(); ++i) {
      if (!std::isfinite(b[i])) continue;
      bool is_active = false;
      for (int a : active) is_active = is_active || a == i;
      const double s = A.row(i).dot(d) - b[i];
      if (!is_active && s > worst) worst = s, p = static_cast<int>(i);
    }
    if (p < 0) {
      for (std::size_t i = 0; i < active.size(); ++i) out.inequality_multipliers[active[i]] = mu[i];
      out.solved = true;
      return out;
    }
    double u_p = 0.0;  // the multiplier of row p, built up by the steps
    for (;;) {
      if (++out.changes > max_changes) return out;
      // Direction: H z + E^T dnu + A_W^T dmu = -a_p, E z = 0, A_W z = 0.
      const Eigen::Index na = static_cast<Eigen::Index>(active.size());
      Eigen::VectorXd rhs = Eigen::VectorXd::Zero(n + ne + na);
      rhs.head(n) = -A.row(p).transpose();
      const Eigen::VectorXd sol = FullPivLuSolve(Kkt(H, E, A, active), rhs);
      const Eigen::VectorXd z = sol.head(n);
      const double curvature = z.dot(H * z);  // = -a_p^T z: the violation falls by t z^T H z
      const double violation = A.row(p).dot(d) - b[p];
      const double full =
          curvature > 1e-14 * (1.0 + H.diagonal().cwiseAbs().maxCoeff()) * z.squaredNorm() && z.norm() > 0
              ? violation / curvature
              : std::numeric_limits<double>::infinity();
      double partial = std::numeric_limits<double>::infinity();
      int drop = -1;
      for (Eigen::Index i = 0; i < na; ++i) {
        const double dmu = sol[n + ne + i];
        if (dmu < 0 && -mu[static_cast<std::size_t>(i)] / dmu < partial)
          partial = -mu[static_cast<std::size_t>(i)] / dmu, drop = static_cast<int>(i);
      }
      if (!std::isfinite(full) && !std::isfinite(partial)) return out;  // inconsistent constraints
      const double t = std::min(full, partial);
      if (std::isfinite(full)) d += t * z;
      nu += t * sol.segment(n, ne);
      for (Eigen::Index i = 0; i < na; ++i) mu[static_cast<std::size_t>(i)] += t * sol[n + ne + i];
      u_p += t;
      if (full <= partial) {
        active.push_back(p);
        mu.push_back(u_p);
        break;
      }
      mu[static_cast<std::size_t>(drop)] = 0.0;
      active.erase(active.begin() + drop);
      mu.erase(mu.begin() + drop);
    }
  }
  return out;
}

}  // namespace plateball::internal
