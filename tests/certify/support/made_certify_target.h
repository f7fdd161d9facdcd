// Test support: a certificate target made from a chosen path, which is then an exact solution by
// construction (its rolling by dopri5 is the target, its chord the circle's radius and goal).
#pragma once

#include <Eigen/Core>
#include <cmath>

#include "certify/support/dopri_rolling.h"
#include "certify/vocabulary.h"

namespace plateball::testing {

/// The target solved by the path x of the regime (rolling by dopri5 at tolerance 1e-12).
inline internal::CertifyTarget MadeCertifyTarget(PendulumRegime regime, const internal::CertifyPoint& x) {
  const Elastica e = internal::CertifyElastica(regime, x);
  const Eigen::Vector2d chord = e.Position(x[internal::kCertifyLength]);
  internal::CertifyTarget t;
  t.target = DopriElasticaRolling(e, x[internal::kCertifyLength], 1e-12);
  t.radius = chord.norm();
  t.goal_angle = std::atan2(chord.y(), chord.x());
  return t;
}

}  // namespace plateball::testing
