// Shared test helpers: SO(3) invariants and named tolerances.
#pragma once

#include <gtest/gtest.h>

#include <Eigen/Core>
#include <functional>
#include <string>

namespace plateball::testing {

/// R^T R = I, det R = 1 and exp(log R) = R, each to `tol`.
::testing::AssertionResult IsRotationMatrix(const Eigen::Matrix3d& r, double tol = 1e-10);

/// The message of the std::invalid_argument that f throws, or `if_none` when it throws none
/// (other exceptions propagate, so a wrong exception type fails the test).
std::string InvalidArgumentMessage(const std::function<void()>& f, const std::string& if_none = "");

/// Path of a file in the source tree (problems/, tests/data/ ...).
std::string SourcePath(const std::string& relative);

}  // namespace plateball::testing
