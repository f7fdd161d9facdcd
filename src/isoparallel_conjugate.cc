#include "isoparallel_conjugate.h"

#include <Eigen/Dense>
#include <algorithm>
#include <array>
#include <cmath>
#include <stdexcept>
#include <string>

#include "dopri5.h"

namespace plateball::internal {

namespace {

// (g, kappa) and per parameter j = W1, W2, g0, kappa0: (dg, dkappa, dx, dy, eta1, eta2, eta3).
constexpr int kColumns = 4;
constexpr int kPerColumn = 7;
constexpr std::size_t kSize = 2 + kColumns * kPerColumn;
using State = std::array<double, kSize>;

constexpr double kTolerance = 1e-12;  // dopri5 absolute and relative tolerance
// |det| of unit columns below this is round-off of the high-order zero at s = 0 (the Jacobian's
// columns agree to ~1e-12, a 5 x 5 determinant of them to ~1e-11): the sign is followed from the
// first grid point above it.
constexpr double kDeterminantNoise = 1e-9;
constexpr int kGridPerPeriod = 48;  // grid points per curvature period (and at least kMinGrid)
constexpr int kMinGrid = 96;
constexpr int kRootIterations = 60;
constexpr double kTimeTolerance = 1e-12;  // relative width of the root's bracket
constexpr double kFirstStep = 0.01;
constexpr long kMaxSteps = 1'000'000;  // per call; a stalled integration is an error, never a hang       // the first
                                       // trial step (the controller adapts it)

struct Rhs {
  Eigen::Vector2d w;
  void operator()(const State& y, State& dy, double /*s*/) const {
    const double g = y[0], c = std::cos(g), sn = std::sin(g);
    dy[0] = y[1];
    dy[1] = -(w[0] * c + w[1] * sn);
    const Eigen::Vector3d omega(-sn, c, 0.0);
    for (int j = 0; j < kColumns; ++j) {
      const double* v = &y[2 + kPerColumn * j];
      double* d = &dy[2 + kPerColumn * j];
      const double dw1 = j == 0 ? 1.0 : 0.0, dw2 = j == 1 ? 1.0 : 0.0;
      d[0] = v[1];
      d[1] = -(dw1 * c + dw2 * sn) + (w[0] * sn - w[1] * c) * v[0];
      d[2] = -sn * v[0];
      d[3] = c * v[0];
      const Eigen::Vector3d eta(v[4], v[5], v[6]);
      const Eigen::Vector3d e = Eigen::Vector3d(-c * v[0], -sn * v[0], 0.0) + omega.cross(eta);
      d[4] = e[0];
      d[5] = e[1];
      d[6] = e[2];
    }
  }
};

State Initial(const ExtremalData& data) {
  State y{};
  y[0] = data.heading;
  y[1] = data.curvature;
  y[2 + kPerColumn * 2 + 0] = 1.0;  // d g(0) / d g0
  y[2 + kPerColumn * 3 + 1] = 1.0;  // d kappa(0) / d kappa0
  return y;
}

// y from s0 to s1 (adaptive steps; *step carries the last accepted step size between calls).
void Advance(const Rhs& rhs, State* y, double s0, double s1, double* step) {
  double s = s0, h = *step;
  for (long steps = 0; s < s1; ++steps) {
    if (steps > kMaxSteps || !(h > 1e-14 * std::max(1.0, std::abs(s))))
      throw std::runtime_error("conjugate points: the variational equations stalled at s = " + std::to_string(s));
    const double h_free = h;
    h = std::min(h, s1 - s);
    State trial = *y;
    const double err = DormandPrince5Step(rhs, trial, s, h, kTolerance, kTolerance);
    if (err <= 1.0) {
      *y = trial;
      const bool last = s1 - s - h <= 1e-15 * std::max(1.0, std::abs(s1));
      s = last ? s1 : s + h;
      h *= std::min(4.0, 0.9 * std::pow(std::max(err, 1e-10), -0.2));
      if (last) h = std::max(h, h_free);  // a step cut to end on s1 does not shrink the next call's
    } else {
      h *= std::max(0.1, 0.9 * std::pow(err, -0.25));
    }
  }
}

double Determinant(ConjugateProblem problem, const State& y) {
  const double g = y[0];
  auto col = [&](int j) { return &y[2 + kPerColumn * j]; };
  if (problem == ConjugateProblem::kPlanarElastica) {
    Eigen::Matrix3d m;
    const int params[3] = {0, 1, 3};  // W1, W2, kappa0 (the heading at s = 0 is fixed)
    for (int i = 0; i < 3; ++i) {
      const double* v = col(params[i]);
      m.col(i) = Eigen::Vector3d(v[2], v[3], v[0]).normalized();
    }
    return m.determinant();
  }
  Eigen::Matrix<double, 5, 5> m;
  for (int j = 0; j < kColumns; ++j) {
    const double* v = col(j);
    Eigen::Matrix<double, 5, 1> c;
    c << v[2], v[3], v[4], v[5], v[6];
    m.col(j) = c.normalized();
  }
  Eigen::Matrix<double, 5, 1> ds;  // d/ds: (x', omega)
  ds << std::cos(g), std::sin(g), -std::sin(g), std::cos(g), 0.0;
  m.col(4) = ds.normalized();
  return m.determinant();
}

// The zero of f = sign det in [lo, hi] (f(lo) > 0 >= f(hi)), y the state at lo: Illinois
// regula falsi (the secant of the bracket, the retained end's value halved when one end stays
// twice), each trial integrated from the bracket's lower end.
double Refine(ConjugateProblem problem,
              const Rhs& rhs,
              State y,
              double lo,
              double f_lo,
              double hi,
              double f_hi,
              double sign,
              double step) {
  int side = 0;
  for (int k = 0; k < kRootIterations && hi - lo > kTimeTolerance * hi; ++k) {
    double mid = (lo * f_hi - hi * f_lo) / (f_hi - f_lo);
    if (!(mid > lo && mid < hi)) mid = 0.5 * (lo + hi);
    State m = y;
    double trial_step = step;
    Advance(rhs, &m, lo, mid, &trial_step);
    const double f = sign * Determinant(problem, m);
    if (f > 0.0) {
      lo = mid;
      f_lo = f;
      y = m;
      if (side == 1) f_hi *= 0.5;
      side = 1;
    } else {
      hi = mid;
      f_hi = f;
      if (f == 0.0) return mid;
      if (side == -1) f_lo *= 0.5;
      side = -1;
    }
  }
  const double root = (lo * f_hi - hi * f_lo) / (f_hi - f_lo);
  return root > lo && root < hi ? root : 0.5 * (lo + hi);
}

}  // namespace

ExtremalData ExtremalDataOf(const ElasticaParameters& parameters) {
  const Elastica e(parameters);
  ExtremalData d;
  d.w = e.G() * Eigen::Vector2d(std::cos(parameters.heading_w), std::sin(parameters.heading_w));
  d.heading = e.Heading(0.0);
  d.curvature = e.Curvature(0.0);
  return d;
}

double ConjugateDeterminant(ConjugateProblem problem, const ExtremalData& data, double s) {
  const Rhs rhs{data.w};
  State y = Initial(data);
  double step = kFirstStep;
  Advance(rhs, &y, 0.0, s, &step);
  return Determinant(problem, y);
}

ConjugateTime FirstConjugateTime(ConjugateProblem problem, const ExtremalData& data, double s_max) {
  const Rhs rhs{data.w};
  // Grid: the pendulum's small-oscillation period 2 pi / sqrt(G), or the curvature's scale.
  const double scale = 1.0 / std::max({std::sqrt(data.w.norm()), std::abs(data.curvature), 1e-3});
  const int grid = std::max(kMinGrid, static_cast<int>(std::ceil(kGridPerPeriod * s_max / (2 * M_PI * scale))));
  const double h = s_max / grid;
  State y = Initial(data);
  double s = 0.0, sign = 0.0, step = kFirstStep, previous = 0.0;
  for (int i = 1; i <= grid; ++i) {
    State next = y;
    const double s_next = i == grid ? s_max : i * h;
    Advance(rhs, &next, s, s_next, &step);
    const double det = Determinant(problem, next);
    if (sign == 0.0) {
      if (std::abs(det) > kDeterminantNoise) sign = det > 0 ? 1.0 : -1.0;
    } else if (det * sign <= 0.0) {
      return {true, Refine(problem, rhs, y, s, previous * sign, s_next, det * sign, sign, step)};
    }
    previous = det;
    y = next;
    s = s_next;
  }
  return {};
}

}  // namespace plateball::internal
