// Partitions 0 = tau_0 < tau_1 < ... < tau_n = T of a planned path (section 2.3), and their two
// norms ||P||_p and ||P||_[0,T].
#pragma once

#include <string>
#include <vector>

#include "plateball/export.h"
#include "plateball/path.h"
#include "plateball/problem.h"

namespace plateball PLATEBALL_EXPORT {

/// n equal steps of the parameter (n >= 1, i.e. at least 2 points).
std::vector<double> UniformParameterPartition(const SmoothCurve& curve, int n);
/// n steps of equal arc length (arc length by adaptive Gauss-Kronrod, inverted by Newton to 1e-14).
std::vector<double> UniformArcLengthPartition(const SmoothCurve& curve, int n);
/// Given parameter values: at least 2, finite, strictly increasing, the first and last at the
/// ends of the curve's interval (to 1e-12, then snapped), consecutive points p(tau) distinct.
std::vector<double> ExplicitPartition(const SmoothCurve& curve, const std::vector<double>& taus);

/// Validates a partition of `curve` (the checks of ExplicitPartition) and throws
/// std::invalid_argument naming `field`[k] for the first violation, including repeated path
/// points p(tau_k) == p(tau_{k+1}).
void ValidatePartition(const SmoothCurve& curve, const std::vector<double>& taus, const std::string& field = "partition");

/// One partition per smooth piece of `path` from a PartitionSpec (problem.h): for a piecewise
/// path n applies to each piece; explicit taus are accepted for a single-piece path only.
std::vector<std::vector<double>> MakePartition(const Path& path, const PartitionSpec& spec,
                                               const std::string& field = "partition");

/// ||P||_p = max_k |p(tau_{k+1}) - p(tau_k)|.
double PointNorm(const SmoothCurve& curve, const std::vector<double>& taus);
/// ||P||_[0,T] = max_k (tau_{k+1} - tau_k).
double ParameterNorm(const std::vector<double>& taus);

}  // namespace plateball
