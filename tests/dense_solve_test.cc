// The shared dense solves against independent routes: the SVD's null vector and pseudo-inverse,
// the normal equations of a full-rank wide system, the residual of a square one.
#include "dense_solve.h"

#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <Eigen/SVD>
#include <algorithm>
#include <cstdlib>

namespace plateball::internal {
namespace {

// Round-off of a few products of order-one numbers in double precision.
constexpr double kRoundOff = 1e-12;

TEST(DenseSolve, OrientedNullVectorIsTheSvdNullVectorWithPositiveDeterminant) {
  std::srand(7);
  for (int trial = 0; trial < 100; ++trial) {
    const Eigen::Matrix<double, 3, 4> a = Eigen::Matrix<double, 3, 4>::Random();
    const Eigen::Vector4d n = OrientedNullVector(a);
    EXPECT_NEAR(n.norm(), 1.0, kRoundOff);
    EXPECT_LE((a * n).norm(), kRoundOff);
    Eigen::Matrix4d m;
    m.topRows<3>() = a;
    m.row(3) = n.transpose();
    EXPECT_GT(m.determinant(), 0.0);
    Eigen::Matrix4d padded = Eigen::Matrix4d::Zero();
    padded.topRows<3>() = a;
    const Eigen::JacobiSVD<Eigen::Matrix4d> null(padded, Eigen::ComputeFullV);
    const Eigen::Vector4d v = null.matrixV().col(3);
    EXPECT_LE(std::min((n - v).norm(), (n + v).norm()), 1e-10) << "trial " << trial;
  }
}

TEST(DenseSolve, OrientedNullVectorOfARankDeficientMatrixIsZero) {
  Eigen::Matrix<double, 3, 4> a;
  a << 1, 2, 3, 4, 2, 4, 6, 8, 0, 1, 0, 1;
  EXPECT_EQ(OrientedNullVector(a), Eigen::Vector4d::Zero());
}

TEST(DenseSolve, MinimumNormSolveOfAWideSystemIsTheNormalEquationsSolution) {
  std::srand(11);
  const Eigen::MatrixXd a = Eigen::MatrixXd::Random(5, 8);
  const Eigen::VectorXd b = Eigen::VectorXd::Random(5);
  const Eigen::VectorXd expected = a.transpose() * (a * a.transpose()).llt().solve(b);
  EXPECT_LE((MinimumNormSolve(a, b) - expected).norm(), kRoundOff);
}

TEST(DenseSolve, MinimumNormSolveOfARankDeficientSystemIsThePseudoInverseSolution) {
  std::srand(13);
  const Eigen::MatrixXd u = Eigen::MatrixXd::Random(7, 3), w = Eigen::MatrixXd::Random(3, 6);
  const Eigen::MatrixXd a = u * w;  // 7 x 6 of rank 3
  const Eigen::VectorXd b = Eigen::VectorXd::Random(7);
  const Eigen::JacobiSVD<Eigen::MatrixXd> svd(a, Eigen::ComputeThinU | Eigen::ComputeThinV);
  Eigen::VectorXd s_inv = svd.singularValues();
  for (Eigen::Index i = 0; i < s_inv.size(); ++i) s_inv[i] = i < 3 ? 1.0 / s_inv[i] : 0.0;
  const Eigen::VectorXd expected = svd.matrixV() * s_inv.asDiagonal() * svd.matrixU().transpose() * b;
  EXPECT_LE((MinimumNormSolve(a, b) - expected).norm(), 1e-10);
}

TEST(DenseSolve, FullPivLuSolveSolvesASquareSystem) {
  std::srand(17);
  const Eigen::MatrixXd a = Eigen::MatrixXd::Random(9, 9) + 3.0 * Eigen::MatrixXd::Identity(9, 9);
  const Eigen::VectorXd b = Eigen::VectorXd::Random(9);
  const Eigen::VectorXd x = FullPivLuSolve(a, b);
  EXPECT_LE((a * x - b).norm(), kRoundOff);
  EXPECT_LE((x - a.partialPivLu().solve(b)).norm(), kRoundOff);
}

}  // namespace
}  // namespace plateball::internal
