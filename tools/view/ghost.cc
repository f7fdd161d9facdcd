#include "view/ghost.h"

#include <algorithm>
#include <cmath>
#include <utility>

#include "plateball/rolling.h"

namespace plateball::tools::view {

namespace {
constexpr int kPathPoints = 4000;  // dense polyline of a planned path
}  // namespace

Polyline::Polyline(std::vector<Eigen::Vector2d> pts) : points(std::move(pts)), s(points.size(), 0.0) {
  for (std::size_t i = 1; i < points.size(); ++i) s[i] = s[i - 1] + (points[i] - points[i - 1]).norm();
}

double Polyline::Locate(const Eigen::Vector2d& p, std::size_t* from) const {
  double best = INFINITY, best_s = s[*from];
  std::size_t best_i = *from;
  for (std::size_t i = *from; i + 1 < points.size(); ++i) {
    const Eigen::Vector2d d = points[i + 1] - points[i];
    const double len2 = d.squaredNorm();
    const double u = len2 > 0 ? std::clamp((p - points[i]).dot(d) / len2, 0.0, 1.0) : 0.0;
    const double dist = (points[i] + u * d - p).norm();
    if (dist < best) {
      best = dist;
      best_s = s[i] + u * (s[i + 1] - s[i]);
      best_i = i;
    }
    if (dist <= 1e-6) break;
  }
  *from = best_i;
  return best_s;
}

Eigen::Vector2d Polyline::At(double arc, std::size_t* segment) const {
  while (*segment + 2 < points.size() && s[*segment + 1] < arc) ++*segment;
  const std::size_t i = *segment;
  const double len = s[i + 1] - s[i];
  const double u = len > 0 ? std::clamp((arc - s[i]) / len, 0.0, 1.0) : 0.0;
  return points[i] + u * (points[i + 1] - points[i]);
}

void BuildGhost(const Polyline& path,
                const std::vector<double>& key_t,
                const std::vector<Eigen::Vector2d>& key_p,
                const std::vector<Eigen::Matrix3d>& key_A,
                ViewData* out) {
  std::vector<double> key_s;
  std::size_t from = 0;
  for (const Eigen::Vector2d& p : key_p) key_s.push_back(path.Locate(p, &from));
  std::size_t key = 0, segment = 0;
  Eigen::Matrix3d A = key_A.front();
  Eigen::Vector2d prev = path.At(key_s.front(), &segment);
  for (const double t : out->t) {
    while (key + 2 < key_t.size() && t >= key_t[key + 1]) {
      ++key;
      if (key < key_A.size()) {  // the result's A(tau_k) at the planned point p_k
        A = key_A[key];
        prev = path.At(key_s[key], &segment);
      }
    }
    const double span = key_t[key + 1] - key_t[key];
    const double u = span > 0 ? std::clamp((t - key_t[key]) / span, 0.0, 1.0) : 0.0;
    const double arc = key_s[key] + u * (key_s[key + 1] - key_s[key]);
    std::size_t walk = segment;
    const Eigen::Vector2d x = path.At(arc, &walk);
    for (std::size_t i = segment + 1; i <= walk; ++i) {  // through the polyline's vertices
      A = RollAlongSegment(prev, path.points[i]) * A;
      prev = path.points[i];
    }
    A = RollAlongSegment(prev, x) * A;
    prev = x;
    segment = walk;
    out->ghost_x.push_back(x);
    out->ghost_A.push_back(A);
  }
  if (key + 2 == key_t.size() && key + 1 < key_A.size()) {  // the last arc ends at the result's A(T)
    out->ghost_A.back() = key_A[key + 1];
  }
}

std::vector<Eigen::Vector2d> SamplePath(const Path& path) {
  std::vector<Eigen::Vector2d> pts;
  const int per_piece = std::max(64, kPathPoints / path.PieceCount());
  for (const SmoothCurve& c : path.pieces())
    for (int i = pts.empty() ? 0 : 1; i <= per_piece; ++i)
      pts.push_back(c.Value(c.Begin() + (c.End() - c.Begin()) * i / per_piece));
  return pts;
}

}  // namespace plateball::tools::view
