// Shared test helpers: SO(3) invariants and named tolerances.
#pragma once

#include <gtest/gtest.h>

#include <Eigen/Core>
#include <string>

namespace plateball::testing {

/// R^T R = I, det R = 1 and exp(log R) = R, each to `tol`.
::testing::AssertionResult IsRotationMatrix(const Eigen::Matrix3d& r, double tol = 1e-10);

/// Path of a file in the source tree (problems/, tests/data/ ...).
std::string SourcePath(const std::string& relative);

}  // namespace plateball::testing
