#include "elastica_rolling.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

#include "plateball/so3.h"

namespace plateball::internal {
namespace {

Eigen::Vector3d Omega(const Eigen::Vector2d& t) { return {-t.y(), t.x(), 0.0}; }  // e3 x x'

const double kSqrt15 = std::sqrt(15.0);
const double kGaussOffset = kSqrt15 / 10.0;
// The Jacobi functions along the table are marched by the addition theorem (a few flops instead
// of an AGM) and re-evaluated directly every kResync steps to bound round-off growth.
constexpr int kResync = 16;
// Marching by the addition theorem needs 1 - k^2 sn^2(u) sn^2(step) >= 1 - kMaxMarchSn2.
constexpr double kMaxMarchSn2 = 0.5;

struct Sncndn {
  double sn, cn, dn;
};

// Addition theorem: f(u + v) from f(u), f(v) (Abramowitz and Stegun 16.17).
Sncndn Add(const Sncndn& a, const Sncndn& b, double k2) {
  const double den = 1.0 / (1.0 - k2 * a.sn * a.sn * b.sn * b.sn);
  return {(a.sn * b.cn * b.dn + b.sn * a.cn * a.dn) * den,
          (a.cn * b.cn - a.sn * b.sn * a.dn * b.dn) * den,
          (a.dn * b.dn - k2 * a.sn * b.sn * a.cn * b.cn) * den};
}

}  // namespace

// Private access to the Jacobi evaluation of an Elastica (friend of the class).
struct ElasticaAccess {
  static Sncndn Jacobi(const Elastica& e, double u) {
    const Elastica::Jacobi j = e.Eval(u);
    return {j.sn, j.cn, j.dn};
  }
  static Eigen::Vector2d TangentOf(const Elastica& e, const Sncndn& s) { return e.TangentOf({s.sn, s.cn, s.dn}); }
};

static Sncndn ElasticaJacobi(const Elastica& e, double u) { return ElasticaAccess::Jacobi(e, u); }
static Eigen::Vector2d ElasticaTangentOf(const Elastica& e, const Sncndn& s) { return ElasticaAccess::TangentOf(e, s); }

// x(s0 + h) - x(s0) from the tangents at the step's three Gauss nodes: three-point
// Gauss-Legendre quadrature of x' (order 6).
static Eigen::Vector2d GaussDisplacement(const Eigen::Vector2d& t1,
                                         const Eigen::Vector2d& t2,
                                         const Eigen::Vector2d& t3,
                                         double h) {
  return (h / 18.0) * (5.0 * t1 + 8.0 * t2 + 5.0 * t3);
}

// The Magnus step's rotation vector (Q(s0, s0 + h) = exp(hat(omega))) from the tangents at the
// three Gauss nodes: Blanes, Casas, Ros (2000), order 6 with Gauss-Legendre nodes ([hat a, hat b] =
// hat(a x b)),
//   a1 = h w2, a2 = sqrt(15) h (w3 - w1) / 3, a3 = 10 h (w3 - 2 w2 + w1) / 3, c1 = a1 x a2,
//   c2 = -a1 x (2 a3 + c1) / 60, omega = a1 + a3 / 12 + (-20 a1 - a3 + c1) x (a2 + c2) / 240,
// written out for w = e3 x t in the plane (a1, a2, a3 in the plane, c1 along e3): the cross
// products' terms with a zero factor are left out (each is an exact zero: the same bits).
static Eigen::Vector3d MagnusVector(const Eigen::Vector2d& t1,
                                    const Eigen::Vector2d& t2,
                                    const Eigen::Vector2d& t3,
                                    double h) {
  const Eigen::Vector2d w1(-t1.y(), t1.x()), w2(-t2.y(), t2.x()), w3(-t3.y(), t3.x());
  const Eigen::Vector2d a1 = h * w2;
  const Eigen::Vector2d a2 = (kSqrt15 * h / 3.0) * (w3 - w1);
  const Eigen::Vector2d a3 = (10.0 * h / 3.0) * (w3 - 2.0 * w2 + w1);
  const double c1 = a1.x() * a2.y() - a1.y() * a2.x();  // along e3
  // c2 = -(1/60) a1 x d, d = (2 a3, c1): in the plane a1 x (0, 0, c1) = (a1.y c1, -a1.x c1), along e3 a1 x 2 a3.
  const Eigen::Vector2d d = 2.0 * a3;
  const Eigen::Vector3d c2 =
      -(1.0 / 60.0) * Eigen::Vector3d(a1.y() * c1, -(a1.x() * c1), a1.x() * d.y() - a1.y() * d.x());
  const Eigen::Vector3d f(-20.0 * a1.x() - a3.x(), -20.0 * a1.y() - a3.y(), c1);  // -20 a1 - a3 + c1
  const Eigen::Vector3d g(a2.x() + c2.x(), a2.y() + c2.y(), c2.z());              // a2 + c2
  return Eigen::Vector3d(a1.x() + a3.x() / 12.0, a1.y() + a3.y() / 12.0, 0.0) + (1.0 / 240.0) * f.cross(g);
}

// The Magnus step from the tangents at the three Gauss nodes.
static Eigen::Matrix3d MagnusFromTangents(const Eigen::Vector2d& t1,
                                          const Eigen::Vector2d& t2,
                                          const Eigen::Vector2d& t3,
                                          double h,
                                          Eigen::Vector2d* displacement) {
  if (displacement) *displacement = GaussDisplacement(t1, t2, t3, h);  // same Gauss nodes
  return ExpSO3(MagnusVector(t1, t2, t3, h));
}

Eigen::Quaterniond QuaternionExp(const Eigen::Vector3d& w) {
  const double t2 = w.squaredNorm();
  double c, a;      // cos(t / 2) and sin(t / 2) / t
  if (t2 < 0.36) {  // Taylor series in x = (t / 2)^2 < 0.09: the first term left out is below 1e-20
    const double x = t2 / 4.0;
    c = 1.0 +
        x * (-1.0 / 2 +
             x * (1.0 / 24 + x * (-1.0 / 720 + x * (1.0 / 40320 + x * (-1.0 / 3628800 +
                                                                       x * (1.0 / 479001600 - x / 87178291200.0))))));
    a = 0.5 *
        (1.0 + x * (-1.0 / 6 +
                    x * (1.0 / 120 +
                         x * (-1.0 / 5040 + x * (1.0 / 362880 + x * (-1.0 / 39916800 + x * (1.0 / 6227020800.0 -
                                                                                            x / 1307674368000.0)))))));
  } else {
    const double t = std::sqrt(t2);
    c = std::cos(0.5 * t);
    a = std::sin(0.5 * t) / t;
  }
  return Eigen::Quaterniond(c, a * w.x(), a * w.y(), a * w.z());
}

Eigen::Matrix3d MagnusRollingStep(const Elastica& e, double s0, double s1, Eigen::Vector2d* displacement) {
  const double h = s1 - s0;
  if (h == 0.0) {
    if (displacement) displacement->setZero();
    return Eigen::Matrix3d::Identity();
  }
  const double c = kGaussOffset;
  return MagnusFromTangents(
      e.Tangent(s0 + (0.5 - c) * h), e.Tangent(s0 + 0.5 * h), e.Tangent(s0 + (0.5 + c) * h), h, displacement);
}

ElasticaRollingTable::ElasticaRollingTable(
    const Elastica& e, double s_limit, int steps_per_period, double max_step, int max_total_steps, bool positions_only)
    : ElasticaRollingTable(e,
                           s_limit,
                           steps_per_period,
                           max_step,
                           max_total_steps,
                           positions_only ? TableRotations::kNone : TableRotations::kMatrices) {}

ElasticaRollingTable::ElasticaRollingTable(const Elastica& e,
                                           double s_limit,
                                           int steps_per_period,
                                           double max_step,
                                           int max_total_steps,
                                           TableRotations rotations)
    : e_(&e), s_limit_(s_limit), max_total_steps_(max_total_steps), rotations_(rotations) {
  steps_per_period = std::max(4, steps_per_period);
  straight_ = e.IsStraight();
  monodromy_.setIdentity();
  monodromy_quat_.setIdentity();
  if (straight_) {
    period_ = s_limit;
    steps_ = 1;
    h_ = s_limit;
    const Eigen::Vector3d w = s_limit * Omega(e.Tangent(0.0));
    if (rotations_ == TableRotations::kQuaternions) {
      quat_ = {Eigen::Quaterniond::Identity(), QuaternionExp(w)};
      monodromy_quat_ = quat_[1];
    } else {
      rot_ = {Eigen::Matrix3d::Identity(), ExpSO3(w)};
      monodromy_ = rot_[1];
    }
    pos_ = {Eigen::Vector2d::Zero(), e.Position(s_limit)};
    drift_ = pos_[1];
    return;
  }
  period_ = e.Period();
  const double periods = s_limit / period_;
  const double steps = std::max<double>(steps_per_period, std::ceil(period_ / max_step));
  if (!(std::isfinite(period_) && steps * std::min(1.0, periods) <= max_total_steps && periods <= max_total_steps)) {
    valid_ = false;
    return;
  }
  // Tables never need more than s_limit: a period longer than s_limit is tabulated up to s_limit.
  double span = period_;
  if (periods < 1.0) span = s_limit;
  steps_ = static_cast<int>(std::ceil(steps * span / period_));
  steps_ = std::max(steps_, 4);
  h_ = span / steps_;
  Build(steps_);
  if (periods < 1.0) {
    period_ = std::numeric_limits<double>::infinity();  // no repetition needed
    drift_.setZero();
  } else {
    if (rotations_ == TableRotations::kMatrices) monodromy_ = rot_[steps_];
    if (rotations_ == TableRotations::kQuaternions) monodromy_quat_ = quat_[steps_];
    drift_ = e.DriftPerPeriod();
  }
}

// Marches the Jacobi functions over `steps` uniform steps of length h from s = 0 and calls
// on_step(j, t1, t2, t3) with the unit tangents at the step's three Gauss nodes.
template <class OnStep>
static void MarchGaussTangents(const Elastica& e, double h, int steps, OnStep&& on_step) {
  const double rate = e.parameters().rate, u0 = e.parameters().phase;
  const double k2 = e.parameters().modulus * e.parameters().modulus;
  const double offsets[3] = {(0.5 - kGaussOffset) * h, 0.5 * h, (0.5 + kGaussOffset) * h};
  const Sncndn step = ElasticaJacobi(e, rate * h);
  // The addition theorem divides by 1 - k^2 sn^2(u) sn^2(step): stable for short steps only
  // (near the separatrix, k -> 1, long steps cancel catastrophically).
  const int resync = k2 * step.sn * step.sn <= kMaxMarchSn2 ? kResync : 1;
  Sncndn node[3] = {};
  for (int j = 0; j < steps; ++j) {
    for (int i = 0; i < 3; ++i) {
      const double u = u0 + rate * (j * h + offsets[i]);
      node[i] = (j % resync == 0) ? ElasticaJacobi(e, u) : Add(node[i], step, k2);
    }
    on_step(j, ElasticaTangentOf(e, node[0]), ElasticaTangentOf(e, node[1]), ElasticaTangentOf(e, node[2]));
  }
}

void ElasticaRollingTable::Build(int steps) {
  pos_.resize(steps + 1);
  pos_[0].setZero();
  if (rotations_ == TableRotations::kNone) {  // the displacement of MagnusFromTangents, without the rotation
    MarchGaussTangents(
        *e_, h_, steps, [this](int j, const Eigen::Vector2d& t1, const Eigen::Vector2d& t2, const Eigen::Vector2d& t3) {
          pos_[j + 1] = pos_[j] + GaussDisplacement(t1, t2, t3, h_);
        });
    return;
  }
  if (rotations_ == TableRotations::kQuaternions) {  // the same steps, exp and products as quaternions
    quat_.resize(steps + 1);
    quat_[0].setIdentity();
    MarchGaussTangents(
        *e_, h_, steps, [this](int j, const Eigen::Vector2d& t1, const Eigen::Vector2d& t2, const Eigen::Vector2d& t3) {
          quat_[j + 1] = QuaternionExp(MagnusVector(t1, t2, t3, h_)) * quat_[j];
          pos_[j + 1] = pos_[j] + GaussDisplacement(t1, t2, t3, h_);
        });
    return;
  }
  rot_.resize(steps + 1);
  rot_[0].setIdentity();
  MarchGaussTangents(
      *e_, h_, steps, [this](int j, const Eigen::Vector2d& t1, const Eigen::Vector2d& t2, const Eigen::Vector2d& t3) {
        Eigen::Vector2d dx;
        rot_[j + 1] = MagnusFromTangents(t1, t2, t3, h_, &dx) * rot_[j];
        pos_[j + 1] = pos_[j] + dx;
      });
}

Eigen::Matrix3d PeriodRolling(const Elastica& e, int steps) {
  steps = std::max(steps, 1);
  const double h = e.Period() / steps;
  Eigen::Matrix3d q = Eigen::Matrix3d::Identity();
  MarchGaussTangents(
      e, h, steps, [&q, h](int, const Eigen::Vector2d& t1, const Eigen::Vector2d& t2, const Eigen::Vector2d& t3) {
        q = MagnusFromTangents(t1, t2, t3, h, nullptr) * q;
      });
  return q;
}

void ElasticaRollingTable::RequireRotations(const char* what) const {
  if (rotations_ == TableRotations::kNone)
    throw std::logic_error(std::string("ElasticaRollingTable::") + what + ": a table of positions only");
  if (rotations_ == TableRotations::kQuaternions)
    throw std::logic_error(std::string("ElasticaRollingTable::") + what + ": a table of quaternions");
}

void ElasticaRollingTable::RequireQuaternions(const char* what) const {
  if (rotations_ != TableRotations::kQuaternions)
    throw std::logic_error(std::string("ElasticaRollingTable::") + what + ": not a table of quaternions");
}

Eigen::Matrix3d ElasticaRollingTable::Rolling(double s) const {
  RequireRotations("Rolling");
  if (straight_) return ExpSO3(s * Omega(e_->Tangent(0.0)));
  double n = 0.0, r = s;
  if (std::isfinite(period_)) {
    n = std::floor(s / period_);
    r = s - n * period_;
  }
  int j = static_cast<int>(std::floor(r / h_));
  j = std::clamp(j, 0, steps_ - 1);
  const double sj = j * h_;
  Eigen::Matrix3d q = MagnusRollingStep(*e_, sj, r) * rot_[j];
  Eigen::Matrix3d p = Eigen::Matrix3d::Identity();
  for (int i = 0; i < static_cast<int>(n); ++i) p = monodromy_ * p;
  return q * p;
}

Eigen::Vector2d ElasticaRollingTable::NodePosition(long global_index) const {
  if (!std::isfinite(period_)) return pos_[std::min<long>(global_index, steps_)];
  const long n = global_index / steps_;
  const int j = static_cast<int>(global_index % steps_);
  return static_cast<double>(n) * drift_ + pos_[j];
}

bool ElasticaRollingTable::Refine(double radius, double sa, double sb, double* s) const {
  const double r2 = radius * radius;
  auto f = [&](double t) { return e_->Position(t).squaredNorm() - r2; };
  double fa = f(sa), fb = f(sb);
  // Node positions are exact up to round-off; a crossing within round-off of a node can land on
  // the wrong side: widen once.
  if (fa * fb > 0) {
    sa = std::max(0.0, sa - h_);
    sb = sb + h_;
    fa = f(sa);
    fb = f(sb);
    if (fa * fb > 0) return false;
  }
  double t = 0.5 * (sa + sb);
  for (int it = 0; it < 60; ++it) {
    const Eigen::Vector2d x = e_->Position(t);
    const double ft = x.squaredNorm() - r2;
    if (ft == 0.0) break;
    if ((ft < 0) == (fa < 0)) {
      sa = t;
      fa = ft;
    } else {
      sb = t;
      fb = ft;
    }
    const double df = 2.0 * x.dot(e_->Tangent(t));
    double next = df != 0.0 ? t - ft / df : 0.5 * (sa + sb);
    if (!(next > std::min(sa, sb) && next < std::max(sa, sb))) next = 0.5 * (sa + sb);
    const double step = std::abs(next - t);
    t = next;
    if (step <= 1e-15 * (1.0 + std::abs(t))) break;
  }
  *s = t;
  return true;
}

long ElasticaRollingTable::NodeCount() const {
  if (!valid_) return 0;
  return straight_ ? 1 : static_cast<long>(std::ceil(s_limit_ / h_));
}

std::vector<Eigen::Matrix3d> ElasticaRollingTable::MonodromyPowers() const {
  RequireRotations("MonodromyPowers");
  std::vector<Eigen::Matrix3d> powers{Eigen::Matrix3d::Identity()};
  if (straight_ || !std::isfinite(period_)) return powers;
  const long count = NodeCount() / steps_;
  for (long n = 1; n <= count; ++n) powers.push_back(monodromy_ * powers.back());
  return powers;
}

std::vector<Eigen::Quaterniond> ElasticaRollingTable::MonodromyQuaternionPowers() const {
  RequireQuaternions("MonodromyQuaternionPowers");
  std::vector<Eigen::Quaterniond> powers{Eigen::Quaterniond::Identity()};
  if (straight_ || !std::isfinite(period_)) return powers;
  const long count = NodeCount() / steps_;
  powers.reserve(count + 1);
  for (long n = 1; n <= count; ++n) powers.push_back(monodromy_quat_ * powers.back());
  return powers;
}

void ElasticaRollingTable::NodePositions(std::vector<Eigen::Vector2d>* position) const {
  const long count = NodeCount();
  position->resize(count + 1);
  if (straight_ || !std::isfinite(period_)) {
    const long last = straight_ ? 1 : steps_;
    for (long i = 0; i <= count; ++i) (*position)[i] = pos_[std::min(i, last)];
    return;
  }
  // NodePosition(i) = n D + x_j (i = n N + j) period by period: the same bits, no division per node.
  for (long start = 0, n = 0; start <= count; start += steps_, ++n) {
    const Eigen::Vector2d shift = static_cast<double>(n) * drift_;
    const long end = std::min<long>(steps_, count - start + 1);
    for (long j = 0; j < end; ++j) (*position)[start + j] = shift + pos_[j];
  }
}

void ElasticaRollingTable::Nodes(std::vector<Eigen::Matrix3d>* rolling, std::vector<Eigen::Vector2d>* position) const {
  RequireRotations("Nodes");
  const std::vector<Eigen::Matrix3d> powers = MonodromyPowers();
  const long count = NodeCount();
  rolling->resize(count + 1);
  for (long i = 0; i <= count; ++i) (*rolling)[i] = NodeRolling(i, powers);
  NodePositions(position);
}

template <class Pred>
int ElasticaRollingTable::ScanCrossings(double radius,
                                        int max_count,
                                        Pred&& refine,
                                        std::vector<std::pair<int, double>>* out) const {
  if (!valid_) return 0;
  const double r2 = radius * radius;
  double prev_f = -r2;  // x(0) = 0
  double prev_s = 0.0;
  int count = 0;
  const long total = NodeCount();
  for (long i = 1; i <= total && count < max_count; ++i) {
    double s = i * h_;
    Eigen::Vector2d x;
    if (s >= s_limit_) {
      s = s_limit_;
      x = e_->Position(s);
    } else {
      x = NodePosition(i);
    }
    const double f = x.squaredNorm() - r2;
    if ((f > 0) != (prev_f > 0)) {
      ++count;
      if (refine(count, prev_s, s)) {
        double root;
        if (Refine(radius, prev_s, s, &root) && root <= s_limit_ && root > 0) {
          out->push_back({count, root});
        } else {
          return -1;  // a bracket that does not refine: treat as missing
        }
      }
    }
    prev_f = f;
    prev_s = s;
    if (s >= s_limit_) break;
  }
  return count;
}

std::vector<double> ElasticaRollingTable::Crossings(double radius, int max_count) const {
  std::vector<std::pair<int, double>> found;
  ScanCrossings(
      radius, max_count, [](int, double, double) { return true; }, &found);
  std::vector<double> out;
  for (const auto& c : found) out.push_back(c.second);
  return out;
}

bool ElasticaRollingTable::FindCrossing(double radius, int n, double* s) const {
  std::vector<std::pair<int, double>> c;
  if (ScanCrossings(
          radius, n, [n](int count, double, double) { return count == n; }, &c) != n ||
      c.empty())
    return false;
  *s = c.back().second;
  return true;
}

bool ElasticaRollingTable::NearestCrossing(
    double radius, double s, double tol, int max_count, int* n, double* root) const {
  std::vector<std::pair<int, double>> c;
  // A root within tol of s lies in a bracket that reaches into [s - tol, s + tol].
  const auto near = [s, tol](int, double sa, double sb) { return sb >= s - tol && sa <= s + tol; };
  ScanCrossings(radius, max_count, near, &c);
  bool found = false;
  for (const auto& [count, r] : c) {
    if (std::abs(r - s) > tol || (found && std::abs(r - s) >= std::abs(*root - s))) continue;
    *n = count;
    *root = r;
    found = true;
  }
  return found;
}

std::vector<double> ChordReach(const std::vector<Eigen::Vector2d>& x, long period_nodes, long count, double h) {
  const long n = period_nodes;
  const bool periodic = n >= 1 && n * 8 <= count && static_cast<long>(x.size()) >= 2 * n;
  std::vector<double> longest(periodic ? n + 1 : 0, 0.0);  // M[r]
  for (long r = 1; r < static_cast<long>(longest.size()); ++r) {
    for (long j = 0; j < n; ++j) longest[r] = std::max(longest[r], (x[j + r] - x[j]).squaredNorm());
    longest[r] = std::sqrt(longest[r]);
  }
  std::vector<double> reach(count + 1);
  double running = 0.0;
  for (long k = 0, m = 0, r = 0; k <= count; ++k, ++r) {  // k = m n + r
    if (periodic && r == n) {
      ++m;
      r = 0;
    }
    double b = k * h;
    if (periodic) b = std::min(b, static_cast<double>(m) * longest[n] + longest[r]);
    running = std::max(running, b * (1 + 1e-9) + 1e-12);  // the margin covers the nodes' round-off
    reach[k] = running;
  }
  return reach;
}

}  // namespace plateball::internal
