// Test support: the reorientation of rolling along an elastica by dopri5 (the independent second
// method the certificate tests compare against).
#pragma once

#include <Eigen/Core>

#include "plateball/elastica.h"
#include "plateball/rolling.h"

namespace plateball::testing {

/// Q(0, length) along the elastica's closed-form tangent, dopri5 at absolute and relative
/// tolerance `tolerance`.
inline Eigen::Matrix3d DopriElasticaRolling(const Elastica& e, double length, double tolerance) {
  IntegrationOptions o;
  o.absolute_tolerance = tolerance;
  o.relative_tolerance = tolerance;
  return RollingReorientation([&e](double s) { return e.Tangent(s); }, 0.0, length, {}, o);
}

}  // namespace plateball::testing
