// Rolling kinematics (section 2.1, "Rolling and reorientations"): the reorientation
// A(b) A(a)^-1 of the ball rolled without sliding or spinning along a planar path.
#pragma once

#include <Eigen/Core>
#include <functional>
#include <vector>

#include "plateball/export.h"
#include "plateball/integration_options.h"

namespace plateball PLATEBALL_EXPORT {

/// x'(tau) of a planar C^1 path.
using PlanarVelocity = std::function<Eigen::Vector2d(double)>;

/// omega = e3 x x' (no sliding, x' = omega x e3 with r = 1; no spinning, omega_3 = 0).
inline Eigen::Vector3d RollingAngularVelocity(const Eigen::Vector2d& xdot) { return {-xdot.y(), xdot.x(), 0.0}; }

/// R = A(b) A(a)^-1 where A' = hat(e3 x x'(tau)) A on [a, b]. Independent of the
/// parametrisation (checked by tests). `breakpoints` inside (a, b) are where x' may jump (a
/// piecewise-smooth path); integration restarts there. Throws std::invalid_argument for
/// non-finite bounds and std::runtime_error when the integration fails (non-finite velocity).
Eigen::Matrix3d RollingReorientation(const PlanarVelocity& velocity,
                                     double a,
                                     double b,
                                     const std::vector<double>& breakpoints = {},
                                     const IntegrationOptions& options = {});

/// Exact reorientation along the straight segment from p to q: exp(hat(e3 x (q - p))).
Eigen::Matrix3d RollAlongSegment(const Eigen::Vector2d& p, const Eigen::Vector2d& q);
/// Product of RollAlongSegment over consecutive points.
Eigen::Matrix3d RollAlongPolyline(const std::vector<Eigen::Vector2d>& points);
/// Reorientation along the natural C^2 cubic spline through the samples (chord-length knots).
Eigen::Matrix3d RollAlongSamples(const std::vector<Eigen::Vector2d>& points, const IntegrationOptions& options = {});

}  // namespace PLATEBALL_EXPORT
