#include "connect.h"

namespace plateball::internal {

JoinSummary ConnectPoints(const BallModel& model, const AngleState& angles, double mu, const Eigen::Vector2d& x0,
                          const Eigen::Vector2d& target, const JoinOptions& options) {
  return Join(model, angles, mu, x0, target, options);
}

}  // namespace plateball::internal
