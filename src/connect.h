// Internal: the one place where the planner connects two consecutive partition points. It tries
// the local join of Lemma 2.1; a target beyond the local radius is reported as such (a global
// reach, reach.h, can be added here as the fallback).
#pragma once

#include <Eigen/Core>

#include "plateball/ball_model.h"
#include "plateball/ball_state.h"
#include "plateball/join.h"

namespace plateball::internal {

JoinSummary ConnectPoints(const BallModel& model, const AngleState& angles, double mu, const Eigen::Vector2d& x0,
                          const Eigen::Vector2d& target, const JoinOptions& options);

}  // namespace plateball::internal
