// Free rolling between impulses: z(t), x(t), A(t), omega(t) for all t from one stored period.
#pragma once

#include <Eigen/Core>
#include <array>
#include <vector>

#include "plateball/ball_model.h"
#include "plateball/ball_state.h"
#include "plateball/export.h"
#include "plateball/integration_options.h"

namespace plateball PLATEBALL_EXPORT {

/// Everything the library reports about the ball at one instant.
struct MotionSample {
  double t = 0.0;
  BallState state;                                  ///< z and omega
  Eigen::Vector2d x = Eigen::Vector2d::Zero();      ///< contact point p_WC on the plate
  Eigen::Matrix3d A = Eigen::Matrix3d::Identity();  ///< orientation R_WB, z = A e3
  AngleState angles;                                ///< canonical (theta in [0, pi])
  double energy = 0.0;                              ///< mu, eq. (9)
};

/// Initial data of a free motion.
struct FreeMotionStart {
  BallState state;
  Eigen::Vector2d x0 = Eigen::Vector2d::Zero();
  Eigen::Matrix3d A0 = Eigen::Matrix3d::Identity();
};

/// The free motion from a given start, integrated over one period T = 2 pi / sqrt(mu) with the
/// chart-free equations (smooth through theta = 0, pi). The state (z, omega) is T-periodic
/// (docs/paper_notes.md proves z3'' = -mu z3), x(t + T) = x(t) + drift, and
/// A(t + kT) = Phi(t) Phi(T)^k A0 with Phi the fundamental solution of A' = hat(omega) A,
/// so any time is evaluated from the stored period without integrating further.
class FreeMotion {
 public:
  /// Throws std::invalid_argument for an invalid state (naming the field), mu = 0 (a ball at
  /// rest has no period), a non-rotation A0 or invalid options.
  FreeMotion(const BallModel& model, const FreeMotionStart& start, const IntegrationOptions& options = {});
  /// The free motion from the angles (theta, phi, psi), energy mu, contact point x0 and orientation A0; throws as the
  /// constructor.
  static FreeMotion FromAngles(const BallModel& model,
                               const AngleState& angles,
                               double mu,
                               const Eigen::Vector2d& x0 = Eigen::Vector2d::Zero(),
                               const Eigen::Matrix3d& A0 = Eigen::Matrix3d::Identity(),
                               const IntegrationOptions& options = {});

  /// The ball model.
  const BallModel& model() const { return model_; }
  /// The initial state.
  const FreeMotionStart& start() const { return start_; }
  /// The energy mu (conserved along the free motion).
  double mu() const { return mu_; }
  /// T = 2 pi / sqrt(mu).
  double Period() const { return period_; }
  /// x(T) - x(0).
  Eigen::Vector2d DriftPerPeriod() const { return drift_; }
  /// Mean velocity of the contact point, drift / T.
  Eigen::Vector2d MeanVelocity() const { return drift_ / period_; }
  /// Phi(T): the reorientation accumulated over one period.
  const Eigen::Matrix3d& MonodromyRotation() const { return monodromy_; }
  /// The conserved vector K (docs/paper_notes.md).
  const Eigen::Vector2d& Momentum() const { return k_; }

  /// Full sample at any real t (negative too) with |t| <= 1e12 periods (beyond, std::invalid_argument:
  /// no significant digits would be left), accurate to the integration tolerance.
  MotionSample At(double t) const;
  /// Contact point only (cheaper: no orientation).
  Eigen::Vector2d PositionAt(double t) const;
  /// Samples at n >= 2 equally spaced times in [t0, t1].
  std::vector<MotionSample> Sample(double t0, double t1, int n) const;
  /// Number of accepted steps stored for the period.
  int StoredSteps() const { return static_cast<int>(checkpoint_t_.size()) - 1; }

 private:
  void LocalState(double tau, double* y14) const;  // tau in [0, T]
  BallModel model_;
  FreeMotionStart start_;
  IntegrationOptions options_;
  double mu_ = 0.0;
  double period_ = 0.0;
  Eigen::Vector2d k_;
  Eigen::Vector2d drift_;
  Eigen::Matrix3d monodromy_;
  Eigen::Vector3d monodromy_log_;
  std::vector<double> checkpoint_t_;
  std::vector<std::array<double, 14>> checkpoint_y_;
};

/// Direct integration (no use of periodicity) of the chart-free equations from `start`,
/// reporting the given non-decreasing times. The second method the tests compare against.
std::vector<MotionSample> IntegrateFreeMotion(const BallModel& model,
                                              const FreeMotionStart& start,
                                              const std::vector<double>& times,
                                              const IntegrationOptions& options = {});

}  // namespace PLATEBALL_EXPORT
