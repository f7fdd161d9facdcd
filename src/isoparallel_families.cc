#include "plateball/isoparallel_families.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <boost/math/tools/toms748_solve.hpp>
#include <cmath>
#include <cstdint>
#include <limits>
#include <sstream>
#include <stdexcept>

#include "check.h"
#include "elastica_rolling.h"
#include "jacobi_elliptic.h"
#include "parallel_for.h"

namespace plateball {
namespace {

// xi = atanh(k) is searched up to kXiMax (1 - k ~ 1e-11): closer to the separatrix the modulus
// is not resolved in double precision.
constexpr double kXiMax = 13.0;
// Longest family searched: max(kSearchLengthPerChord chord, kMinSearchLength). The sampling
// cost grows with the length (longer periods, faster-turning m phi); a longer cap is clamped
// and the search then does not claim completeness.
constexpr double kSearchLengthPerChord = 64.0;
constexpr double kMinSearchLength = 200.0;
// Coarse rollings (bracketing): ~1e-8 rad. Accurate rollings (polish): below 1e-13 rad
// (tests/isoparallel_families_test.cc checks both against dopri5).
constexpr int kCoarseSteps = 12;
constexpr double kCoarseMaxStep = 0.5;
constexpr int kAccurateSteps = 96;
constexpr double kAccurateMaxStep = 0.015;
constexpr double kCoarseMaxU = 0.5;
constexpr double kAccurateMaxU = 0.05;
// Adaptive sampling: a cell is accepted when m phi changes by at most a quarter of a level
// spacing across it and its midpoint lies within 1/32 of a spacing of the chord.
constexpr double kMaxLevelChange = 0.25 * 2.0 * M_PI;
constexpr double kMaxMidpointBend = (1.0 / 32.0) * 2.0 * M_PI;
constexpr int kMaxDepth = 40;
constexpr int kPolishIterations = 8;
// A family within this (relative) of the chord is the straight segment: only a straight path is
// as short as its chord. When the chord is a multiple of 2 pi, m phi vanishes at k = 0 for every m,
// and the polish finds that degenerate root (k ~ 1e-5 and below) at every period count.
constexpr double kStraightFamilyTol = 1e-9;

struct Shape {
  double T1 = 0.0;   // curvature period in the Jacobi argument u: 4K (oscillating), 2K (rotating)
  double rho = 0.0;  // drift per period / period (signed)
};

Shape ShapeOf(PendulumRegime regime, double k) {
  // D = (K - E) / k^2; k'^2 = (1 - k)(1 + k), not 1 - k^2 (jacobi_elliptic.h).
  const double kk = internal::CompleteEllipticK(k), dd = internal::CompleteEllipticD(k);
  Shape s;
  if (regime == PendulumRegime::kOscillating) {
    s.T1 = 4.0 * kk;
    s.rho = 1.0 - 2.0 * k * k * dd / kk;
  } else {
    s.T1 = 2.0 * kk;
    s.rho = 1.0 - 2.0 * dd / kk;
  }
  return s;
}

ElasticaParameters MakeParameters(PendulumRegime regime, double k, int m, double chord, const Shape& sh) {
  ElasticaParameters p;
  p.regime = regime;
  p.modulus = k;
  p.rate = m * sh.T1 * std::abs(sh.rho) / chord;
  p.phase = 0.0;
  p.heading_w = M_PI / 2;
  return p;
}

ElasticaParameters MakeParameters(PendulumRegime regime, double k, int m, double chord) {
  return MakeParameters(regime, k, m, chord, ShapeOf(regime, k));
}

double LengthOf(PendulumRegime regime, double k, double chord) { return chord / std::abs(ShapeOf(regime, k).rho); }

// The xi-intervals where L(k) <= max_length. L is monotone on each branch: oscillating, rising
// from the chord (k = 0) to infinity at the figure-eight modulus (rho = 0), then falling back;
// rotating, falling from infinity (k = 0, circles) towards the chord.
std::vector<std::pair<double, double>> AllowedIntervals(PendulumRegime regime, double chord, double max_length) {
  auto excess = [&](double xi) { return LengthOf(regime, std::tanh(xi), chord) - max_length; };
  auto solve = [&](double a, double b) {
    // L - max_length changes sign on [a, b] unless the cap lies beyond the far end's length.
    if (!(excess(a) * excess(b) < 0)) return excess(a) <= 0 ? b : a;
    std::uintmax_t iters = 200;
    const auto r =
        boost::math::tools::toms748_solve(excess, a, b, boost::math::tools::eps_tolerance<double>(50), iters);
    return 0.5 * (r.first + r.second);
  };
  std::vector<std::pair<double, double>> out;
  if (regime == PendulumRegime::kOscillating) {
    // Figure-eight modulus: rho(k*) = 0, i.e. 2 E(k) = K(k).
    auto rho = [](double xi) { return ShapeOf(PendulumRegime::kOscillating, std::tanh(xi)).rho; };
    std::uintmax_t iters = 200;
    const auto r8 =
        boost::math::tools::toms748_solve(rho, 0.5, 3.0, boost::math::tools::eps_tolerance<double>(50), iters);
    const double xi8 = 0.5 * (r8.first + r8.second);
    if (excess(0.0) < 0) out.push_back({0.0, solve(0.0, xi8 * (1 - 1e-12))});
    if (excess(kXiMax) < 0) out.push_back({solve(xi8 * (1 + 1e-12), kXiMax), kXiMax});
  } else {
    if (excess(kXiMax) < 0) out.push_back({solve(1e-3, kXiMax), kXiMax});
  }
  return out;
}

struct Point {
  double xi;
  double phi;    // principal or lifted angle of P about v(0)
  double limit;  // Phi_inf = +-chord at this k
};

// phi(k) for m periods spanning the chord, with the coarse or the accurate rolling.
Point EvaluatePhi(PendulumRegime regime, double chord, int m, double xi, bool accurate) {
  const double k = std::tanh(xi);
  const Shape shape = ShapeOf(regime, k);
  const Elastica e(MakeParameters(regime, k, m, chord, shape));
  // Steps short in arc length and in the Jacobi argument (near the separatrix the turning
  // concentrates in a few units of u out of a period of 4K or 2K).
  const double max_step = accurate ? kAccurateMaxStep : kCoarseMaxStep;
  const int steps = std::max({accurate ? kAccurateSteps : kCoarseSteps,
                              static_cast<int>(std::ceil(e.Period() / max_step)),
                              static_cast<int>(std::ceil(shape.T1 / (accurate ? kAccurateMaxU : kCoarseMaxU)))});
  const Eigen::Matrix3d p = internal::PeriodRolling(e, steps);
  const Eigen::Vector3d v = ElasticaCostate(e, 0.0);
  const double norm = v.norm();
  const Eigen::Vector3d n = norm > 0 ? Eigen::Vector3d(v / norm) : Eigen::Vector3d::UnitY();
  // Many short periods roll like the chord: rotation by the chord length about
  // e3 x (drift direction) = sign(rho) e_y.
  return {xi, SignedRotationAngle(p, n), chord * (shape.rho >= 0 ? 1.0 : -1.0) * (n.y() >= 0 ? 1.0 : -1.0)};
}

double Lift(double phi, double reference) { return phi + 2.0 * M_PI * std::round((reference - phi) / (2.0 * M_PI)); }

// A crossing of the level 2 pi j by m phi(k) found on the coarse rolling.
struct CoarseRoot {
  PendulumRegime regime;
  int m;
  int j;
  double xi, lo, hi;  // root and its bracket in xi
  double length;
};

// Scans one regime for one m: adaptive sampling of m phi over the xi-intervals where
// L(k) <= max_length, every crossing bracketed and refined on the coarse rolling.
class PeriodScan {
 public:
  PeriodScan(PendulumRegime regime, double chord, int m, const FamilySearchOptions& options)
      : regime_(regime), chord_(chord), m_(m), options_(options) {}

  void Run(double max_length) {
    for (const auto& [a, b] : AllowedIntervals(regime_, chord_, max_length)) Sample(a, b);
  }

  std::vector<CoarseRoot> roots;
  double deviation = 0.0;  // max |m phi - Phi_inf| over the samples
  long evaluations = 0;

 private:
  Point Evaluate(double xi) {
    ++evaluations;
    return EvaluatePhi(regime_, chord_, m_, xi, false);
  }

  void Sample(double a, double b) {
    const int cells = std::max(8, static_cast<int>(std::ceil((b - a) / options_.cell)));
    Point left = Evaluate(a);
    Track(left);
    for (int i = 1; i <= cells; ++i) {
      const double xi = i == cells ? b : a + (b - a) * i / cells;
      left = Cell(left, Evaluate(xi), 0);
    }
  }

  void Track(const Point& p) {
    deviation = std::max(deviation, std::abs(m_ * std::remainder(p.phi, 2.0 * M_PI) - p.limit));
  }

  // Refines [a, b] (a lifted, b principal) until accepted; returns b lifted.
  Point Cell(const Point& a, Point b, int depth) {
    b.phi = Lift(b.phi, a.phi);
    const double fa = m_ * a.phi, fb = m_ * b.phi;
    if (depth < kMaxDepth) {
      Point mid = Evaluate(0.5 * (a.xi + b.xi));
      mid.phi = Lift(mid.phi, a.phi);
      const double bend = std::abs(m_ * mid.phi - 0.5 * (fa + fb));
      // Lifting b through the midpoint must agree with lifting it directly.
      const bool consistent = Lift(b.phi, mid.phi) == b.phi;
      if (std::abs(fb - fa) > kMaxLevelChange || bend > kMaxMidpointBend || !consistent) {
        Track(mid);
        return Cell(Cell(a, mid, depth + 1), b, depth + 1);
      }
    }
    Track(b);
    Roots(a, b);
    return b;
  }

  // Every level 2 pi j crossed in (a, b]: bracketed and refined on the coarse rolling.
  void Roots(const Point& a, const Point& b) {
    const double fa = m_ * a.phi, fb = m_ * b.phi;
    const double lo = std::min(fa, fb), hi = std::max(fa, fb);
    const long j0 = static_cast<long>(std::floor(lo / (2.0 * M_PI))) + 1;
    const long j1 = static_cast<long>(std::floor(hi / (2.0 * M_PI)));
    for (long j = j0; j <= j1; ++j) {
      const double level = 2.0 * M_PI * static_cast<double>(j);
      const double slope = (b.phi - a.phi) / (b.xi - a.xi);
      auto f = [&](double xi) {
        const Point p = Evaluate(xi);
        return m_ * Lift(p.phi, a.phi + slope * (xi - a.xi)) - level;
      };
      const double flo = fa - level, fhi = fb - level;
      double xi = flo == 0.0 ? a.xi : b.xi;
      if (flo != 0.0 && fhi != 0.0) {
        std::uintmax_t iters = 60;
        const auto r = boost::math::tools::toms748_solve(
            f, a.xi, b.xi, flo, fhi, boost::math::tools::eps_tolerance<double>(30), iters);
        xi = 0.5 * (r.first + r.second);
      }
      roots.push_back({regime_, m_, static_cast<int>(j), xi, a.xi, b.xi, LengthOf(regime_, std::tanh(xi), chord_)});
    }
  }

  PendulumRegime regime_;
  double chord_;
  int m_;
  FamilySearchOptions options_;
};

// Newton then secant steps on the accurate rolling from a coarse root (the first slope from the
// coarse rolling, which is smooth in xi); false when not converged.
bool Polish(const CoarseRoot& root, double chord, double tolerance, ElasticaFamily* out, long* evaluations) {
  const double level = 2.0 * M_PI * root.j;
  auto f = [&](double x, bool accurate) {
    ++*evaluations;
    const Point p = EvaluatePhi(root.regime, chord, root.m, x, accurate);
    return root.m * Lift(p.phi, level / root.m) - level;
  };
  const double h = 1e-6 * (1.0 + root.xi);
  const double slope = (f(root.xi + h, false) - f(root.xi - h, false)) / (2.0 * h);
  double x0 = root.xi, f0 = f(x0, true);
  double x1 = x0 - f0 / slope;
  if (!(std::isfinite(x1) && std::abs(x1 - x0) <= root.hi - root.lo)) x1 = x0 + h;
  double f1 = f(x1, true);
  for (int it = 0; it < kPolishIterations && std::abs(f1) > 0.1 * tolerance && f1 != f0; ++it) {
    const double x2 = x1 - f1 * (x1 - x0) / (f1 - f0);
    if (!std::isfinite(x2) || x2 < 0.0 || x2 > kXiMax) break;
    x0 = x1;
    f0 = f1;
    x1 = x2;
    f1 = f(x1, true);
  }
  if (std::abs(f0) < std::abs(f1)) {
    std::swap(x0, x1);
    std::swap(f0, f1);
  }
  const double k = std::tanh(x1);
  // Near the separatrix the modulus itself is the limit: one unit in the last place of k moves
  // m phi by |slope| ulp(k) / (1 - k^2) (e.g. ~1e-11 rad at 1 - k ~ 1e-7). Accept that floor.
  const double k_ulp = std::nextafter(k, 2.0) - k;
  const double floor = 4.0 * std::abs(slope) * k_ulp / ((1.0 - k) * (1.0 + k));
  if (!(std::abs(f1) <= std::max(tolerance, floor))) return false;
  const ElasticaParameters p = MakeParameters(root.regime, k, root.m, chord);
  out->regime = root.regime;
  out->modulus = k;
  out->rate = p.rate;
  out->periods = root.m;
  out->winding = root.j;
  out->length = root.m * Elastica(p).Period();
  out->residual = std::abs(f1);
  return true;
}

}  // namespace

std::string FamilySearchOptions::Validate() const {
  using internal::InvalidValueMessage;
  if (!(std::isfinite(max_length) && max_length > 0))
    return InvalidValueMessage("max_length", max_length, "must be finite and > 0");
  if (!(length_cap_factor == 0 || (length_cap_factor >= 1 && length_cap_factor <= internal::kMaxLengthCapFactor)))
    return InvalidValueMessage(
        "length_cap_factor",
        length_cap_factor,
        "must be 0 (no cap) or in [1, " + internal::FormatNumber(internal::kMaxLengthCapFactor) + "]");
  if (!(tolerance >= internal::kMinTolerance && tolerance < 1))
    return InvalidValueMessage("tolerance", tolerance, "must be in [1e-15, 1)");
  if (!(cell >= 1e-4 && cell <= 2.0)) return InvalidValueMessage("cell", cell, "must be in [1e-4, 2]");
  if (max_periods < 1 || max_periods > 100000)
    return InvalidValueMessage("max_periods", max_periods, "must be in [1, 100000]");
  if (certified_run < 1 || certified_run > 1000)
    return InvalidValueMessage("certified_run", certified_run, "must be in [1, 1000]");
  if (threads < 1 || threads > 256) return InvalidValueMessage("threads", threads, "must be in [1, 256]");
  return {};
}

ElasticaParameters ElasticaFamily::Parameters() const {
  ElasticaParameters p;
  p.regime = regime;
  p.modulus = modulus;
  p.rate = rate;
  p.phase = 0.0;
  p.heading_w = M_PI / 2;
  return p;
}

double SignedRotationAngle(const Eigen::Matrix3d& p, const Eigen::Vector3d& n) {
  const double c = 0.5 * (p.trace() - 1.0);
  const Eigen::Vector3d axial(p(2, 1) - p(1, 2), p(0, 2) - p(2, 0), p(1, 0) - p(0, 1));
  return std::atan2(0.5 * n.dot(axial), c);
}

Eigen::Vector3d ElasticaCostate(const Elastica& e, double s) {
  const double gw = e.parameters().heading_w, g = e.Heading(s), big_g = e.G();
  return {big_g * std::cos(gw) + std::sin(g), big_g * std::sin(gw) - std::cos(g), e.Curvature(s)};
}

FamilySearch EnumerateIdentityFamilies(double chord, const FamilySearchOptions& options) {
  internal::RequirePositive("chord", chord);
  if (chord > internal::kMaxIsoparallelChord)  // the work grows like chord^3 (README, "Limits")
    internal::ThrowInvalid("chord", chord, "must be <= " + internal::FormatNumber(internal::kMaxIsoparallelChord));
  internal::ThrowIfInvalid(options.Validate());
  FamilySearch out;
  const double search_limit = std::max(kSearchLengthPerChord * chord, kMinSearchLength);
  double cap = std::min(options.max_length, search_limit);
  // A straight segment rolls the ball through its length about a horizontal axis: the identity
  // when the chord is a multiple of 2 pi. No path is shorter than the chord.
  const double turns = std::round(chord / (2.0 * M_PI));
  if (std::abs(chord - 2.0 * M_PI * turns) <= options.tolerance && chord <= cap) {
    ElasticaFamily f;
    f.winding = static_cast<int>(turns);
    f.length = chord;
    f.residual = std::abs(chord - 2.0 * M_PI * turns);
    out.families.push_back(f);
    if (options.length_cap_factor > 0) cap = std::min(cap, options.length_cap_factor * chord);
  }
  // Families at m are certified absent when every sample keeps |m phi - Phi_inf| below the
  // distance from the chord to 2 pi Z (then m phi cannot reach a level 2 pi j).
  const double margin = 0.9 * std::abs(std::remainder(chord, 2.0 * M_PI));
  const PendulumRegime regimes[2] = {PendulumRegime::kOscillating, PendulumRegime::kRotating};
  int certified[2] = {0, 0};
  bool done[2] = {cap <= chord, cap <= chord};
  for (int m = 1; m <= options.max_periods && !(done[0] && done[1]); ++m) {
    out.periods_searched = m;
    std::vector<PeriodScan> scans;
    for (int r = 0; r < 2; ++r) scans.emplace_back(regimes[r], chord, m, options);
    internal::ParallelFor(2, options.threads, [&](int r) {
      if (!done[r]) scans[r].Run(cap);
    });
    std::vector<CoarseRoot> roots;
    for (int r = 0; r < 2; ++r) {
      if (done[r]) continue;
      out.evaluations += scans[r].evaluations;
      const bool none = scans[r].roots.empty();
      certified[r] = (none && scans[r].deviation < margin) ? certified[r] + 1 : 0;
      if (certified[r] >= options.certified_run) done[r] = true;
      for (const CoarseRoot& c : scans[r].roots)
        if (c.length <= cap * (1 + 1e-6)) roots.push_back(c);
    }
    std::vector<ElasticaFamily> polished(roots.size());
    std::vector<char> ok(roots.size(), 0);
    std::vector<long> evals(roots.size(), 0);
    internal::ParallelFor(static_cast<int>(roots.size()), options.threads, [&](int i) {
      ok[i] = Polish(roots[i], chord, options.tolerance, &polished[i], &evals[i]);
    });
    for (std::size_t i = 0; i < roots.size(); ++i) {
      out.evaluations += evals[i];
      if (!ok[i] || polished[i].length > cap || polished[i].length <= chord * (1 + kStraightFamilyTol)) continue;
      bool duplicate = false;  // two brackets that polished onto one root
      for (const ElasticaFamily& f : out.families)
        duplicate =
            duplicate || (f.regime == polished[i].regime && f.periods == polished[i].periods &&
                          f.winding == polished[i].winding && std::abs(f.modulus - polished[i].modulus) <= 1e-10);
      if (duplicate) continue;
      out.families.push_back(polished[i]);
      if (options.length_cap_factor > 0) cap = std::min(cap, options.length_cap_factor * polished[i].length);
    }
    if (options.progress) options.progress(m);
  }
  out.complete = done[0] && done[1] && (options.max_length <= search_limit || cap < search_limit);
  out.searched_length = cap;
  std::stable_sort(out.families.begin(), out.families.end(), [](const ElasticaFamily& a, const ElasticaFamily& b) {
    return a.length < b.length;
  });
  // Families found before the cap shrank may lie beyond it.
  while (!out.families.empty() && out.families.back().length > cap) out.families.pop_back();
  return out;
}

}  // namespace plateball
