// Shared test helpers: SO(3) invariants and named tolerances.
#pragma once

#include <gtest/gtest.h>

#include <Eigen/Core>
#include <functional>
#include <string>

#include "plateball/ball_model.h"
#include "plateball/error_model.h"

namespace plateball::testing {

/// R^T R = I, det R = 1 and exp(log R) = R, each to `tol`.
::testing::AssertionResult IsRotationMatrix(const Eigen::Matrix3d& r, double tol = 1e-10);

/// The message of the std::invalid_argument that f throws, or `if_none` when it throws none
/// (other exceptions propagate, so a wrong exception type fails the test).
std::string InvalidArgumentMessage(const std::function<void()>& f, const std::string& if_none = "");

/// Path of a file in the source tree (problems/, tests/data/ ...).
std::string SourcePath(const std::string& relative);

/// problems/physical_units.json's ball and plate: a 2 cm, 100 g ball (I1 = 1.6e-5, I3 = 1.2e-5 kg m^2)
/// under a 50 g upper plate.
PhysicalParameters PhysicalUnitsBall();

/// The execution errors of the controller's tests: 2 % impulse magnitude, 0.02 rad impulse angle,
/// 2 % lambda and 0.1 % energy loss per impulse.
ErrorModel ControllerTestErrors();

}  // namespace plateball::testing
