#include "support/test_support.h"

#include <Eigen/Dense>
#include <sstream>
#include <stdexcept>

#include "plateball/so3.h"

namespace plateball::testing {

::testing::AssertionResult IsRotationMatrix(const Eigen::Matrix3d& r, double tol) {
  if (!r.allFinite()) return ::testing::AssertionFailure() << "matrix has non-finite entries:\n" << r;
  const double orth = (r.transpose() * r - Eigen::Matrix3d::Identity()).cwiseAbs().maxCoeff();
  const double det = r.determinant();
  const double round_trip = (ExpSO3(LogSO3(r)) - r).cwiseAbs().maxCoeff();
  if (orth > tol || std::abs(det - 1.0) > tol || round_trip > tol) {
    return ::testing::AssertionFailure() << "not a rotation to " << tol << ": |R^T R - I|_max = " << orth
                                         << ", det - 1 = " << det - 1.0 << ", |exp(log R) - R|_max = " << round_trip
                                         << "\n"
                                         << r;
  }
  return ::testing::AssertionSuccess();
}

std::string InvalidArgumentMessage(const std::function<void()>& f, const std::string& if_none) {
  try {
    f();
  } catch (const std::invalid_argument& e) {
    return e.what();
  }
  return if_none;
}

std::string SourcePath(const std::string& relative) { return std::string(PLATEBALL_SOURCE_DIR) + "/" + relative; }

PhysicalParameters PhysicalUnitsBall() {
  PhysicalParameters p;
  p.inertia_1 = 1.6e-5;
  p.inertia_3 = 1.2e-5;
  p.ball_mass = 0.1;
  p.radius = 0.02;
  p.plate_mass = 0.05;
  return p;
}

ErrorModel ControllerTestErrors() {
  ErrorModel e;
  e.impulse_magnitude = 0.02;
  e.impulse_angle = 0.02;
  e.lambda = 0.02;
  e.energy_loss = 0.001;
  return e;
}

}  // namespace plateball::testing
