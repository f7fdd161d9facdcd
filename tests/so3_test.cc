// SO(3) helpers: exp/log round trips (near 0 and near pi), the operator-norm distance against
// an SVD, projection, rotations about e3 and quaternions.
#include "plateball/so3.h"

#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <random>
#include <stdexcept>
#include <string>

#include "kinematics.h"
#include "support/test_support.h"

namespace plateball {
namespace {

using testing::IsRotationMatrix;

TEST(So3, HatIsTheCrossProductAndVeeInvertsIt) {
  const Eigen::Vector3d w(0.3, -1.2, 2.0), v(1.0, 0.5, -0.7);
  EXPECT_LT((Hat(w) * v - w.cross(v)).norm(), 1e-15);
  EXPECT_LT((Vee(Hat(w)) - w).norm(), 1e-15);
}

TEST(So3, ExpMatchesEigenAngleAxisOnBothSidesOfTheSeriesThreshold) {
  // ExpSO3 switches from Taylor series to sin/cos at 0.2 rad: both branches against Eigen.
  const Eigen::Vector3d axis = Eigen::Vector3d(0.3, -0.8, 0.52).normalized();
  for (double angle : {1e-9, 1e-4, 0.05, 0.15, 0.1999999, 0.2, 0.2000001, 0.3, 1.0, 3.0}) {
    const Eigen::Matrix3d ref = Eigen::AngleAxisd(angle, axis).toRotationMatrix();
    EXPECT_LT((ExpSO3(angle * axis) - ref).norm(), 1e-15) << angle;
  }
}

TEST(So3, ExpAndLogRoundTripNearZeroNearPiAndBetween) {
  std::mt19937 rng(3);
  std::normal_distribution<double> n(0.0, 1.0);
  for (double angle : {0.0, 1e-12, 1e-6, 1e-3, 0.5, 2.0, 3.0, M_PI - 1e-6, M_PI - 1e-9}) {
    for (int i = 0; i < 5; ++i) {
      const Eigen::Vector3d axis = Eigen::Vector3d(n(rng), n(rng), n(rng)).normalized();
      const Eigen::Vector3d w = angle * axis;
      const Eigen::Matrix3d r = ExpSO3(w);
      EXPECT_TRUE(IsRotationMatrix(r, 1e-14));
      // Rodrigues against Eigen's angle-axis (independent implementation).
      EXPECT_LT((r - Eigen::AngleAxisd(angle, axis).toRotationMatrix()).norm(), 1e-14);
      EXPECT_LT((ExpSO3(LogSO3(r)) - r).norm(), 1e-12) << "angle " << angle;
      EXPECT_NEAR(LogSO3(r).norm(), angle, 1e-8 + 1e-12);
    }
  }
  // Exactly pi: the log has norm pi and exp of it gives back the rotation.
  const Eigen::Matrix3d half_turn = Eigen::AngleAxisd(M_PI, Eigen::Vector3d(1, 2, 2).normalized()).toRotationMatrix();
  EXPECT_NEAR(LogSO3(half_turn).norm(), M_PI, 1e-12);
  EXPECT_LT((ExpSO3(LogSO3(half_turn)) - half_turn).norm(), 1e-12);
}

TEST(So3, OperatorNormDistanceIsTheLargestSingularValue) {
  std::mt19937 rng(5);
  std::normal_distribution<double> n(0.0, 1.0);
  for (int i = 0; i < 20; ++i) {
    const Eigen::Matrix3d a = ExpSO3({n(rng), n(rng), n(rng)}), b = ExpSO3({n(rng), n(rng), n(rng)});
    Eigen::JacobiSVD<Eigen::Matrix3d> svd(a - b);
    EXPECT_NEAR(OperatorNormDistance(a, b), svd.singularValues()(0), 1e-13);
    // For rotations: ||a - b||_2 = 2 sin(angle / 2) with angle the rotation angle of a^T b.
    EXPECT_NEAR(OperatorNormDistance(a, b), 2.0 * std::sin(RotationAngle(a, b) / 2.0), 1e-12);
  }
}

TEST(So3, ProjectionRotationZAndQuaternions) {
  const Eigen::Matrix3d r = ExpSO3({0.4, -0.1, 1.3});
  Eigen::Matrix3d noisy = r;
  noisy(0, 1) += 1e-6;
  const Eigen::Matrix3d p = ProjectToSO3(noisy);
  EXPECT_TRUE(IsRotationMatrix(p, 1e-14));
  EXPECT_LT((p - r).norm(), 2e-6);
  EXPECT_TRUE(IsRotation(r));
  EXPECT_FALSE(IsRotation(2.0 * r));
  EXPECT_LT((RotationZ(0.7) - ExpSO3({0, 0, 0.7})).norm(), 1e-15);
  // q = (cos(a/2), sin(a/2) n) is the rotation by a about n; scaling q does not matter.
  const Eigen::Vector3d axis = Eigen::Vector3d(1, -1, 0.5).normalized();
  const Eigen::Vector4d q(std::cos(0.6), std::sin(0.6) * axis.x(), std::sin(0.6) * axis.y(), std::sin(0.6) * axis.z());
  EXPECT_LT((QuaternionToRotation(3.0 * q) - ExpSO3(1.2 * axis)).norm(), 1e-14);
  try {
    QuaternionToRotation(Eigen::Vector4d::Zero(), "start.orientation");
    ADD_FAILURE() << "no exception";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("start.orientation"), std::string::npos);
  }
}

TEST(SO3, AlignOrientationToAxisIsTheMinimalRotationOntoZ) {
  std::mt19937 gen(11);
  std::normal_distribution<double> n(0.0, 1.0);
  for (int k = 0; k < 50; ++k) {
    const Eigen::Matrix3d a0 = ExpSO3({n(gen), n(gen), n(gen)});
    const Eigen::Vector3d z = Eigen::Vector3d(n(gen), n(gen), n(gen)).normalized();
    const Eigen::Matrix3d a = AlignOrientationToAxis(a0, z);
    EXPECT_TRUE(IsRotationMatrix(a, 1e-14));
    EXPECT_LT((a.col(2) - z).norm(), 1e-14);
    // Minimal: the geodesic angle from a0 equals the angle between a0 e3 and z (no rotation
    // can move e3's image by that angle with less), and the rotation a a0^T fixes a0 e3 x z.
    const double needed = std::acos(std::clamp(a0.col(2).dot(z), -1.0, 1.0));
    EXPECT_NEAR(RotationAngle(a0, a), needed, 1e-9);
    const Eigen::Vector3d axis = a0.col(2).cross(z);
    if (axis.norm() > 1e-6) {
      EXPECT_LT((a * a0.transpose() * axis - axis).norm(), 1e-12);
    }
  }
  // Already aligned: unchanged. Reversed: a half turn about a0 e1.
  const Eigen::Matrix3d r = ExpSO3({0.3, -0.2, 0.9});
  EXPECT_LT((AlignOrientationToAxis(r, r.col(2)) - r).norm(), 1e-15);
  const Eigen::Matrix3d flipped = AlignOrientationToAxis(r, -r.col(2));
  EXPECT_LT((flipped.col(2) + r.col(2)).norm(), 1e-14);
  EXPECT_LT((flipped.col(0) - r.col(0)).norm(), 1e-14);
  try {
    AlignOrientationToAxis(2.0 * r, r.col(2));
    ADD_FAILURE() << "no exception";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("A0"), std::string::npos);
  }
}

// A start orientation that is no rotation (a reflection: det = -1) is refused in the library's
// message format, naming the field and showing the matrix.
TEST(So3, RotateAxisOntoRefusesAReflectionInTheStandardFormat) {
  const Eigen::Matrix3d reflection = Eigen::Vector3d(1.0, 1.0, -1.0).asDiagonal();
  try {
    internal::RotateAxisOnto(reflection, Eigen::Vector3d::UnitZ());
    FAIL() << "a reflection was accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_EQ(std::string(e.what()),
              "A0: value [[1, 0, 0], [0, 1, 0], [0, 0, -1]]: not a rotation matrix (R^T R = I, det R = 1 to 1e-9)");
  }
  // A rotation passes: the identity already has its axis on z.
  EXPECT_TRUE(internal::RotateAxisOnto(Eigen::Matrix3d::Identity(), Eigen::Vector3d::UnitZ()).isIdentity(0.0));
}

}  // namespace
}  // namespace plateball
