// The contact-point velocity and acceleration of a free arc (src/arc.h), as the planner's arcs
// measure them for the bounds: checked against forward-mode Jets and central differences.
#include <gtest/gtest.h>

#include <ceres/jet.h>

#include <cmath>

#include "arc.h"
#include "kinematics.h"

TEST(ContactVelocityAndAcceleration, HandDerivativeEqualsJetForwardModeAndFiniteDifferences) {
  // x'' = d/dt (omega_2, -omega_1) along z' = omega x z at constant K: the hand derivative against
  // forward-mode Jets through OmegaFromZK and against central differences along z'.
  using Jet = ceres::Jet<double, 1>;
  for (double lambda : {0.5, 1.0, 2.0, 7.0}) {
    for (int trial = 0; trial < 8; ++trial) {
      const double th = 0.3 + 0.37 * trial, ph = -1.0 + 0.61 * trial;
      const double z[3] = {std::sin(th) * std::cos(ph), std::sin(th) * std::sin(ph), std::cos(th)};
      const double k[2] = {0.7 - 0.2 * trial, 0.4 + 0.15 * trial};
      double w[2], acc[2], w_ref[2];
      plateball::internal::ContactVelocityAndAcceleration(lambda, z, k, w, acc);
      plateball::internal::OmegaFromZK(z, k, lambda, w_ref);
      EXPECT_EQ(w[0], w_ref[0]);
      EXPECT_EQ(w[1], w_ref[1]);
      const double dz[3] = {w[1] * z[2], -w[0] * z[2], w[0] * z[1] - w[1] * z[0]};
      Jet zj[3], kj[2] = {Jet(k[0]), Jet(k[1])}, wj[2];
      for (int i = 0; i < 3; ++i) zj[i] = Jet(z[i]), zj[i].v[0] = dz[i];
      plateball::internal::OmegaFromZK(zj, kj, lambda, wj);
      EXPECT_NEAR(acc[0], wj[1].v[0], 1e-14 * (1 + std::abs(wj[1].v[0])));
      EXPECT_NEAR(acc[1], -wj[0].v[0], 1e-14 * (1 + std::abs(wj[0].v[0])));
      const double h = 1e-5;
      double zp[3], zm[3], wp[2], wm[2];
      for (int i = 0; i < 3; ++i) zp[i] = z[i] + h * dz[i], zm[i] = z[i] - h * dz[i];
      plateball::internal::OmegaFromZK(zp, k, lambda, wp);
      plateball::internal::OmegaFromZK(zm, k, lambda, wm);
      EXPECT_NEAR(acc[0], (wp[1] - wm[1]) / (2 * h), 1e-8);
      EXPECT_NEAR(acc[1], -(wp[0] - wm[0]) / (2 * h), 1e-8);
      const Eigen::Vector2d a = plateball::internal::ContactAcceleration(lambda, Eigen::Vector3d(z[0], z[1], z[2]),
                                                                         Eigen::Vector2d(k[0], k[1]));
      EXPECT_EQ(a.x(), acc[0]);
      EXPECT_EQ(a.y(), acc[1]);
    }
  }
}
