// Partitions 0 = tau_0 < tau_1 < ... < tau_n = T of a planned path (section 2.3), and their two
// norms ||P||_p and ||P||_[0,T].
#pragma once

#include <string>
#include <variant>
#include <vector>

#include "plateball/export.h"
#include "plateball/path.h"

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
void ValidatePartition(const SmoothCurve& curve,
                       const std::vector<double>& taus,
                       const std::string& field = "partition");

/// n equal steps of the parameter of a piece (n >= 1).
struct UniformParameter {
  int n = 16;
};
/// n steps of equal arc length of a piece (n >= 1).
struct UniformArcLength {
  int n = 16;
};
/// The given parameter values of a piece (the checks of ExplicitPartition).
struct ExplicitTaus {
  std::vector<double> taus;
};
/// How one smooth piece of a planned path is partitioned (section 2.3): a closed set of rules.
using PartitionRule = std::variant<UniformParameter, UniformArcLength, ExplicitTaus>;
/// "uniform_parameter", "uniform_arc_length" or "explicit" (the file's partition.type).
std::string ToString(const PartitionRule& rule);

/// One partition per smooth piece of `path`: `rules` holds one rule per piece, or a single rule
/// that applies to every piece. Throws std::invalid_argument naming `field`[i] for an invalid
/// rule or a rule count that is neither 1 nor the piece count.
std::vector<std::vector<double>> MakePartition(const Path& path,
                                               const std::vector<PartitionRule>& rules,
                                               const std::string& field = "partition");

/// ||P||_p = max_k |p(tau_{k+1}) - p(tau_k)|.
double PointNorm(const SmoothCurve& curve, const std::vector<double>& taus);
/// ||P||_[0,T] = max_k (tau_{k+1} - tau_k).
double ParameterNorm(const std::vector<double>& taus);

}  // namespace PLATEBALL_EXPORT
