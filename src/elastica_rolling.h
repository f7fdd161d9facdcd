// Internal: rolling the ball along an elastica, fast, for the isoparallel shooting.
//
// A' = hat(e3 x x') A (section 2.1) is integrated over ONE curvature period only, with a
// sixth-order Magnus method (three Gauss nodes, Blanes-Casas-Ros 2000) driven by the closed-form
// tangent; the tangent is periodic, so Q(0, N T + r) = Q(0, r) P^N with P = Q(0, T) gives the
// reorientation at any arc length. The result is exactly a rotation (products of exponentials).
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <utility>
#include <vector>

#include "plateball/elastica.h"

namespace plateball::internal {

/// One Magnus step of order 6 of A' = hat(e3 x x'(s)) A from s0 to s1: returns Q(s0, s1);
/// optionally x(s1) - x(s0) by Gauss quadrature on the same nodes.
Eigen::Matrix3d MagnusRollingStep(const Elastica& e, double s0, double s1, Eigen::Vector2d* displacement = nullptr);

/// P = Q(0, T): rolling over one curvature period T from the elastica's phase, by `steps`
/// uniform sixth-order Magnus steps (no table kept). Not for straight lines (infinite period).
Eigen::Matrix3d PeriodRolling(const Elastica& e, int steps);

/// What an ElasticaRollingTable keeps of the rolling at its nodes: rotation matrices, nothing
/// (positions only), or unit quaternions (for scans that compose many node rotations: a product
/// of two costs 16 multiplications instead of 27, and the trace and logarithm the scan needs come
/// straight from the quaternion).
enum class TableRotations { kMatrices, kNone, kQuaternions };

/// exp(hat(w)) as a unit quaternion (cos(|w| / 2), sin(|w| / 2) w / |w|): ExpSO3(w)'s rotation
/// (Taylor series below 1e-18 for small |w|).
Eigen::Quaterniond QuaternionExp(const Eigen::Vector3d& w);

/// Rolling along an elastica on [0, s_limit], from a table over one curvature period.
class ElasticaRollingTable {
 public:
  /// steps_per_period >= 4 Magnus steps per period, and no step longer than max_step.
  /// Valid() is false when the table would need more than max_total_steps steps. A table of
  /// positions only (positions_only) has the same nodes and positions (bit for bit: the crossings
  /// are the same) without the Magnus rotations: Rolling and Nodes throw std::logic_error on it
  /// (the rolling then comes from ElasticaClosedRolling, elastica_closed_rolling.h).
  ElasticaRollingTable(const Elastica& e,
                       double s_limit,
                       int steps_per_period,
                       double max_step,
                       int max_total_steps = 200000,
                       bool positions_only = false);
  /// The same table keeping `rotations` (kNone: positions_only; kQuaternions: the same Magnus steps
  /// composed as unit quaternions, read by NodeQuaternion only: Rolling, Nodes, MonodromyPowers
  /// throw std::logic_error on it). Nodes and positions are the same bit for bit in every form.
  ElasticaRollingTable(const Elastica& e,
                       double s_limit,
                       int steps_per_period,
                       double max_step,
                       int max_total_steps,
                       TableRotations rotations);
  bool Valid() const { return valid_; }
  bool PositionsOnly() const { return rotations_ == TableRotations::kNone; }
  /// Whether a table of the same elastica and accuracy over [0, s_limit] (s_limit >= this one's)
  /// would be this one: a periodic table (one period tabulated) is the same for every length, so
  /// it serves Rolling(s) for any s up to s_limit as it stands.
  bool ServesLength(double s_limit) const {
    return valid_ && !straight_ && std::isfinite(period_) && s_limit >= s_limit_ &&
           s_limit / period_ <= max_total_steps_;
  }
  int Steps() const { return steps_; }
  /// Q(0, s) = A(s) A(0)^-1 for s in [0, s_limit].
  Eigen::Matrix3d Rolling(double s) const;
  /// The n-th (n >= 1) arc length s in (0, s_limit] where |x(s)| crosses `radius` (sign changes
  /// of |x|^2 - radius^2 on the table's nodes, refined in closed form). False if fewer.
  bool FindCrossing(double radius, int n, double* s) const;
  /// All crossings in (0, s_limit] (node brackets, refined).
  std::vector<double> Crossings(double radius, int max_count) const;
  /// The crossing nearest to s among those within tol of it (only their node brackets are
  /// refined) and its number n (1 .. max_count) counted from s = 0; false if there is none.
  bool NearestCrossing(double radius, double s, double tol, int max_count, int* n, double* root) const;
  /// Node spacing h: the table's nodes are s = i h, i = 0 .. NodeCount() (the last one may lie
  /// past s_limit by less than h).
  double Step() const { return h_; }
  long NodeCount() const;
  /// Q(0, i h) and x(i h) at every node i = 0 .. NodeCount(), from the one-period table and the
  /// monodromy (no Magnus step, no closed form): for scans over many (s0, s0 + L) node pairs.
  void Nodes(std::vector<Eigen::Matrix3d>* rolling, std::vector<Eigen::Vector2d>* position) const;
  /// Nodes' positions alone, x(i h) for i = 0 .. NodeCount().
  void NodePositions(std::vector<Eigen::Vector2d>* position) const;
  /// The monodromy's powers P^n, n = 0 .. NodeCount() / Steps() (just the identity for a table
  /// that does not repeat), for NodeRolling.
  std::vector<Eigen::Matrix3d> MonodromyPowers() const;
  /// Q(0, i h) of one node, 0 <= i <= NodeCount(), bit for bit Nodes' value, with `powers` from
  /// MonodromyPowers(): for scans that need the rolling at a few of the nodes only (a table of
  /// matrices; NodeQuaternion reads a table of quaternions).
  Eigen::Matrix3d NodeRolling(long i, const std::vector<Eigen::Matrix3d>& powers) const {
    if (straight_ || !std::isfinite(period_)) return rot_[std::min<long>(i, steps_)];
    const long n = i / steps_;
    return n == 0 ? rot_[i] : Eigen::Matrix3d(rot_[i % steps_] * powers[n]);  // P^0 = I: no product
  }
  /// A table of quaternions (TableRotations::kQuaternions): the monodromy's powers p^n, n = 0 ..
  /// NodeCount() / Steps(), and the unit quaternion of Q(0, i h) at node i, 0 <= i <= NodeCount()
  /// (q_j p^n, i = n N + j, as NodeRolling), with `powers` from MonodromyQuaternionPowers(). The
  /// rotations agree with a matrix table's NodeRolling to round-off (about 1e-15 per step).
  std::vector<Eigen::Quaterniond> MonodromyQuaternionPowers() const;
  Eigen::Quaterniond NodeQuaternion(long i, const std::vector<Eigen::Quaterniond>& powers) const {
    if (straight_ || !std::isfinite(period_)) return quat_[std::min<long>(i, steps_)];
    const long n = i / steps_;
    return n == 0 ? quat_[i] : Eigen::Quaterniond(quat_[i % steps_] * powers[n]);
  }

 private:
  void Build(int steps);
  void RequireRotations(const char* what) const;
  void RequireQuaternions(const char* what) const;
  // Counts node brackets up to max_count and refines those for which refine(count, sa, sb) holds
  // (count from 1; bracket [sa, sb]), appending (count, root) to out; -1 on failure.
  template <class Pred>
  int ScanCrossings(double radius, int max_count, Pred&& refine, std::vector<std::pair<int, double>>* out) const;
  Eigen::Vector2d NodePosition(long global_index) const;
  bool Refine(double radius, double sa, double sb, double* s) const;
  const Elastica* e_;
  double s_limit_;
  int max_total_steps_;
  bool valid_ = true;
  TableRotations rotations_ = TableRotations::kMatrices;
  bool straight_ = false;
  double period_ = 0.0;
  double h_ = 0.0;
  int steps_ = 0;
  Eigen::Vector2d drift_;
  Eigen::Matrix3d monodromy_;
  Eigen::Quaterniond monodromy_quat_;
  std::vector<Eigen::Matrix3d> rot_;      // Q(0, j h), j = 0..steps_ (kMatrices)
  std::vector<Eigen::Quaterniond> quat_;  // the same as unit quaternions (kQuaternions)
  std::vector<Eigen::Vector2d> pos_;      // x(j h)
};

/// How far the chord between two nodes of a table can move over k nodes, for scans that skip
/// nodes (isoparallel/shape_scan.cc, ScanShape): reach[k] >= |x[j + k'] - x[j]| for every node j and every
/// k' <= k, k = 0 .. count, given the nodes' positions x (ElasticaRollingTable::NodePositions),
/// the nodes per period N and the spacing h. From the unit speed, k h; for a table of many periods
/// (N <= count / 8, x holding at least 2 N nodes), also m |D| + M[r] (k = m N + r:
/// x[j + k] - x[j] = m D + x[j + r] - x[j], D the drift per period, M[r] the longest chord over r
/// nodes of one period, measured on the nodes), much less for curled shapes. Non-decreasing, with a
/// margin (1e-9 relative, 1e-12 absolute) for the nodes' round-off.
std::vector<double> ChordReach(const std::vector<Eigen::Vector2d>& x, long period_nodes, long count, double h);

/// std::lower_bound(reach.begin(), reach.end(), gap) - reach.begin() (reach non-decreasing), found
/// by a galloping search up from the guess gap / h (ChordReach's reach[k] is at most about k h,
/// and close to it on the scan's long-period shapes): the same index for any guess, in a few
/// comparisons where the answer lies near the guess.
inline long FirstReachAtLeast(const std::vector<double>& reach, double gap, double h) {
  const long n = static_cast<long>(reach.size());
  const double guess = gap / h;
  long lo = guess >= 0.0 && guess < static_cast<double>(n) ? static_cast<long>(guess) : (guess >= 0.0 ? n : 0);
  if (lo > 0 && !(reach[lo - 1] < gap))  // the answer lies below the guess
    return std::lower_bound(reach.begin(), reach.begin() + lo, gap) - reach.begin();
  long hi = lo;  // every k < lo has reach[k] < gap; the answer lies in [lo, hi] once reach[hi] >= gap
  for (long step = 1; hi < n && reach[hi] < gap; step *= 2) {
    lo = hi + 1;
    hi = std::min(n, hi + step);
  }
  return std::lower_bound(reach.begin() + lo, reach.begin() + hi, gap) - reach.begin();
}

/// The nodes a scan may skip after node l whose chord |x[l] - x[j]| passes an edge (outward or
/// inward) by `gap`: the largest k with reach[k] < gap (-1: none, gap <= reach[0]). Nodes l - 1 ..
/// l + k then keep their chords beyond the edge (|x[l + d] - x[l]| <= reach[|d|] < gap for
/// |d| <= k) when k >= 1 (node l - 1 needs reach[1] < gap).
inline long ReachSkip(const std::vector<double>& reach, double gap, double h) {
  return FirstReachAtLeast(reach, gap, h) - 1;
}

}  // namespace plateball::internal
