#include <gtest/gtest.h>

#include <cmath>

#include "plateball/ball_state.h"
#include "plateball/free_motion.h"

using namespace plateball;

TEST(FreeMotionSmoke, StateReturnsAfterTwoPiOverSqrtMu) {
  for (double lambda : {0.5, 2.0}) {
    const BallModel model = BallModel::FromLambda(lambda);
    const FreeMotion m = FreeMotion::FromAngles(model, {M_PI / 3, 0.4, 0.1}, 1.7);
    const MotionSample s0 = m.At(0.0);
    const auto direct = IntegrateFreeMotion(model, m.start(), {m.Period(), 3.7 * m.Period()});
    EXPECT_LT((direct[0].state.z - s0.state.z).norm(), 1e-10);
    EXPECT_LT((direct[0].state.omega - s0.state.omega).norm(), 1e-10);
    const MotionSample far = m.At(3.7 * m.Period());
    EXPECT_LT((far.x - direct[1].x).norm(), 1e-9);
    EXPECT_LT((far.A - direct[1].A).norm(), 1e-9);
    EXPECT_NEAR(far.energy, 1.7, 1e-10);
  }
}
