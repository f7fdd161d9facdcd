// The dense QP solver of the constrained arrival's Gauss-Newton steps (src/dense_qp.h): its
// answers meet the KKT conditions, and agree with NLopt's SLSQP on the same programmes.
#include "dense_qp.h"

#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <nlopt.hpp>
#include <random>
#include <vector>

namespace plateball::internal {
namespace {

// Round-off of the dense LU solves on well-scaled data of size ~1.
constexpr double kKktTolerance = 1e-9;
// SLSQP stops at its own tolerance (1e-12 relative in x): its optimum agrees to about its square root.
constexpr double kAgreement = 1e-6;

struct Qp {
  Eigen::MatrixXd H, E, A;
  Eigen::VectorXd c, e, b;
};

// A random strictly convex QP whose constraints hold at a random point (so it is feasible), with
// some inequalities cutting the unconstrained minimum.
Qp RandomQp(std::mt19937& rng, int n, int ne, int m) {
  std::normal_distribution<double> g;
  const auto random = [&](int r, int c) {
    Eigen::MatrixXd x(r, c);
    for (int i = 0; i < r; ++i)
      for (int j = 0; j < c; ++j) x(i, j) = g(rng);
    return x;
  };
  Qp q;
  const Eigen::MatrixXd L = random(n, n);
  q.H = L * L.transpose() + 0.1 * Eigen::MatrixXd::Identity(n, n);
  q.c = random(n, 1);
  const Eigen::VectorXd feasible = random(n, 1);
  q.E = random(ne, n);
  q.e = q.E * feasible;
  q.A = random(m, n);
  q.b = q.A * feasible + 0.3 * random(m, 1).cwiseAbs();
  return q;
}

void ExpectKkt(const Qp& q, const DenseQpResult& r) {
  ASSERT_TRUE(r.solved);
  const Eigen::VectorXd stationarity =
      q.H * r.d + q.c + q.E.transpose() * r.equality_multipliers + q.A.transpose() * r.inequality_multipliers;
  EXPECT_LE(stationarity.cwiseAbs().maxCoeff(), kKktTolerance);
  if (q.E.rows() > 0) {
    EXPECT_LE((q.E * r.d - q.e).cwiseAbs().maxCoeff(), kKktTolerance);
  }
  const Eigen::VectorXd slack = q.A * r.d - q.b;
  EXPECT_LE(slack.maxCoeff(), kKktTolerance);
  EXPECT_GE(r.inequality_multipliers.minCoeff(), 0.0);
  EXPECT_LE((r.inequality_multipliers.array() * slack.array()).abs().maxCoeff(), kKktTolerance);
}

// The same QP by NLopt's SLSQP from the origin.
Eigen::VectorXd SlsqpSolution(const Qp& q) {
  const unsigned n = static_cast<unsigned>(q.H.rows());
  nlopt::opt opt(nlopt::LD_SLSQP, n);
  const auto objective = [](unsigned nv, const double* x, double* grad, void* data) {
    const Qp& p = *static_cast<const Qp*>(data);
    const Eigen::Map<const Eigen::VectorXd> d(x, nv);
    const Eigen::VectorXd hd = p.H * d;
    if (grad) Eigen::Map<Eigen::VectorXd>(grad, nv) = hd + p.c;
    return 0.5 * d.dot(hd) + p.c.dot(d);
  };
  opt.set_min_objective(objective, const_cast<Qp*>(&q));
  static thread_local const Qp* current = nullptr;
  current = &q;
  const auto rows = [](unsigned m, double* result, unsigned nv, const double* x, double* grad, void* data) {
    const bool equality = data != nullptr;
    const Eigen::MatrixXd& M = equality ? current->E : current->A;
    const Eigen::VectorXd& v = equality ? current->e : current->b;
    const Eigen::Map<const Eigen::VectorXd> d(x, nv);
    for (unsigned i = 0; i < m; ++i) {
      result[i] = M.row(i).dot(d) - v[i];
      if (grad)
        for (unsigned j = 0; j < nv; ++j) grad[i * nv + j] = M(i, j);
    }
  };
  static int tag = 0;
  if (q.E.rows() > 0) opt.add_equality_mconstraint(rows, &tag, std::vector<double>(q.E.rows(), 1e-13));
  opt.add_inequality_mconstraint(rows, nullptr, std::vector<double>(q.A.rows(), 1e-13));
  opt.set_xtol_rel(1e-12);
  opt.set_maxeval(2000);
  std::vector<double> x(n, 0.0);
  double f = 0.0;
  opt.optimize(x, f);
  return Eigen::Map<Eigen::VectorXd>(x.data(), n);
}

TEST(DenseQp, MeetsKktAndAgreesWithSlsqp) {
  std::mt19937 rng(7);
  int with_active = 0;
  for (int trial = 0; trial < 40; ++trial) {
    const int n = 3 + trial % 6, ne = trial % 3, m = 4 + trial % 12;
    const Qp q = RandomQp(rng, n, ne, m);
    const DenseQpResult r = SolveDenseQp(q.H, q.c, q.E, q.e, q.A, q.b);
    ExpectKkt(q, r);
    with_active += r.inequality_multipliers.maxCoeff() > 0 ? 1 : 0;
    const Eigen::VectorXd x = SlsqpSolution(q);
    EXPECT_LE((x - r.d).cwiseAbs().maxCoeff(), kAgreement * (1.0 + r.d.cwiseAbs().maxCoeff())) << "trial " << trial;
  }
  EXPECT_GE(with_active, 30);  // the cases exercise the active set, not just the unconstrained minimum
}

TEST(DenseQp, InconsistentConstraintsAreNotSolved) {
  // d_0 <= -1 and d_0 >= 1.
  const Eigen::MatrixXd H = Eigen::MatrixXd::Identity(2, 2);
  Eigen::MatrixXd A(2, 2);
  A << 1, 0, -1, 0;
  const DenseQpResult r =
      SolveDenseQp(H, Eigen::VectorXd::Zero(2), Eigen::MatrixXd(0, 2), Eigen::VectorXd(0), A, Eigen::Vector2d(-1, -1));
  EXPECT_FALSE(r.solved);
}

}  // namespace
}  // namespace plateball::internal
