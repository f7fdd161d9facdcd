// The ghost ball of `plateball view`: a planned path as a dense polyline, and the ball rolling along
// it that passes the planned points at the impulse times (view_data.cc draws it beside the real ball).
#pragma once

#include <Eigen/Core>
#include <cstddef>
#include <vector>

#include "plateball/path.h"
#include "view/view_data.h"

namespace plateball::tools::view {

// The planned path as a dense polyline with its cumulative arc length.
struct Polyline {
  std::vector<Eigen::Vector2d> points;
  std::vector<double> s;
  explicit Polyline(std::vector<Eigen::Vector2d> pts);
  /// Arc length of the point of segments [from, end) nearest to p (the first one within 1e-6).
  double Locate(const Eigen::Vector2d& p, std::size_t* from) const;
  /// Point at arc length `arc`; `segment` is a hint moved forward.
  Eigen::Vector2d At(double arc, std::size_t* segment) const;
};

/// The ghost ball: rolls along the planned path, passing the planned point p_k at the ball's
/// impulse time t_k (arc length linear in time between them); its orientation is the rolling
/// along the dense polyline (exact per chord, rolling.h), reset to the result's A(tau_k) where
/// the result reports it. Appends one ghost sample per time of out->t.
void BuildGhost(const Polyline& path,
                const std::vector<double>& key_t,
                const std::vector<Eigen::Vector2d>& key_p,
                const std::vector<Eigen::Matrix3d>& key_A,
                ViewData* out);

/// The path as a dense polyline: about 4000 points, at least 64 per smooth piece.
std::vector<Eigen::Vector2d> SamplePath(const Path& path);

}  // namespace plateball::tools::view
