// The shape scan of a general target: for each shape (rate, modulus; phase 0), one rolling table
// and a scan of its (start phase, length) plane for crossings of the circle and near-tangencies
// with a small rotation residual; the local minima start the free-length search (search.cc).
// The shapes run in batches, each merged (merge.cc) before the next.
#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>

#include "chord_residual.h"
#include "isoparallel/stages.h"
#include "quaternion_log.h"

namespace plateball::internal::isoparallel {
namespace {

// A shape's table in the form the scan reads it: the node positions, and the rolling at a node
// on demand as a unit quaternion (Q(0, i h) = Q(0, j h) P^n, i = n N + j, a table of quaternions:
// ElasticaRollingTable::NodeQuaternion).
struct ShapeNodes {
  const internal::ElasticaRollingTable* table;
  std::vector<Eigen::Quaterniond> powers;
  std::vector<Eigen::Vector2d> x;
  Eigen::Quaterniond target_conj;
  internal::GoalDirection goal;
  internal::LogNormBound bound{kScanResidual};
};

// The rotation (a quaternion) whose log is the residual of the path from node i0 to node i of a
// shape's table (the rotation trick with B from the chord's direction; q0c = Q(0, s0)'s conjugate,
// Q(s0, s) = Q(0, s) Q(0, s0)^T).
Eigen::Quaterniond NodeResidualRotation(const ShapeNodes& nodes, const Eigen::Quaterniond& q0c, long i0, long i) {
  return internal::ChordQuaternion(
      nodes.target_conj, nodes.goal, nodes.x[i] - nodes.x[i0], nodes.table->NodeQuaternion(i, nodes.powers) * q0c);
}

// |residual| of a crossing between nodes i0 + l - 1 and i0 + l (interpolated with weight t on the
// later node; node i0 + 1's alone for l = 1), +infinity where LogNormBound proves it above
// kScanResidual (SearchShape reads no residual beyond it, and such a neighbour never undercuts one
// below it), without the logarithms.
double CrossingResidual(const ShapeNodes& nodes, const Eigen::Quaterniond& q0c, long i0, long l, double t) {
  const Eigen::Quaterniond a = NodeResidualRotation(nodes, q0c, i0, i0 + l);
  if (l == 1) return nodes.bound.Exceeds(a) ? kAboveScanResidual : internal::QuaternionLog(a).norm();
  const Eigen::Quaterniond b = NodeResidualRotation(nodes, q0c, i0, i0 + l - 1);
  if (nodes.bound.InterpolationExceeds(a, b)) return kAboveScanResidual;
  return (t * internal::QuaternionLog(a) + (1 - t) * internal::QuaternionLog(b)).norm();
}

// A point of a shape's (s0, L) scan where the chord |x(s0 + L) - x(s0)| crosses the radius
// |x1 - x0| (or comes within kTangencyMiss of it at a node, a near-tangency).
struct ScanPoint {
  double length = 0.0;
  double residual = 0.0;  // |rotation residual| (interpolated between nodes), with the chord miss
};

// A shape's scan: the points of row i0 (start node s0 = i0 h) are points[row_end[i0 - 1] ..
// row_end[i0]) (row_end[-1] = 0), in order of L.
struct ShapeScan {
  std::vector<ScanPoint> points;
  std::vector<std::size_t> row_end;
  double step = 0.0;
  std::size_t RowBegin(long i0) const { return i0 == 0 ? 0 : row_end[i0 - 1]; }
  std::size_t RowSize(long i0) const { return row_end[i0] - RowBegin(i0); }
};

// One row of the scan: start node i0, lengths up to node l_end; `limit` is the search length.
// While |chord| at node l exceeds the near-tangency band's outer edge (radius + kTangencyMiss,
// loosened as the band test is by 1e-9) by more than reach[k] (ChordReach), or falls below its
// inner edge by more, nodes l - 1 .. l + k lie outside the band on the same side of the radius:
// no crossing between them and no near-tangency at them, and the k nodes after l are skipped (the
// row resumes with the crossing between nodes l + k and l + k + 1 and the extremum test at l + k).
// Elsewhere the squared chord against precomputed bounds decides, with a square root only where a
// skip or an event is possible.
// Not inlined: ScanShape's loop over rows would crowd its registers (the node loop spills).
[[gnu::noinline]] void ScanRow(const Context& ctx,
                               const ShapeNodes& nodes,
                               const std::vector<double>& reach,
                               double h,
                               long i0,
                               long l_end,
                               double limit,
                               std::vector<ScanPoint>* row) {
  const std::vector<Eigen::Vector2d>& x = nodes.x;
  const Eigen::Quaterniond q0c = nodes.table->NodeQuaternion(i0, nodes.powers).conjugate();
  const Eigen::Vector2d x0 = x[i0];
  const double r2 = ctx.radius * ctx.radius, far = ctx.radius + kTangencyMiss, near = ctx.radius - kTangencyMiss;
  // The band (loosened by 1e-9) where an extremum is a near-tangency; chords beyond its edges
  // (loosened by 1e-9 more) by more than reach[k] stay out of it for k nodes; squared chords beyond
  // which a skip of kMinSkip nodes is possible.
  const double band_lo = near > 0 ? near * near * (1 - 1e-9) : -1.0, band_hi = far * far * (1 + 1e-9);
  const double out_edge = far * (1 + 1e-9), in_edge = near * (1 - 1e-9);
  const double skip_out = (out_edge + reach[kMinSkip]) * (out_edge + reach[kMinSkip]);
  const double skip_in =
      in_edge - reach[kMinSkip] > 0 ? (in_edge - reach[kMinSkip]) * (in_edge - reach[kMinSkip]) : -1.0;
  const std::size_t first = row->size();
  double f_prev = -r2, f_prev2 = -r2;  // |chord|^2 - radius^2 at the two previous nodes
  for (long l = 1; l <= l_end; ++l) {
    double f = (x[i0 + l] - x0).squaredNorm() - r2;
    if ((f + r2 > skip_out && f_prev > 0) || (f + r2 < skip_in && f_prev < 0)) {
      const double c = std::sqrt(f + r2), gap = f > 0 ? c - out_edge : in_edge - c;
      // reach[k] < gap for k <= skip, and the row's end not passed.
      const long skip = std::min(internal::ReachSkip(reach, gap, h), l_end - l - 2);
      if (skip > 0) {  // resume with the two nodes before the next one
        l += skip;
        f_prev2 = (x[i0 + l - 1] - x0).squaredNorm() - r2;
        f_prev = (x[i0 + l] - x0).squaredNorm() - r2;
        ++l;
        f = (x[i0 + l] - x0).squaredNorm() - r2;
      }
    }
    if ((f > 0) != (f_prev > 0)) {
      const double t = f_prev / (f_prev - f);  // linear interpolation between the nodes
      if ((l - 1 + t) * h > limit) break;
      row->push_back({(l - 1 + t) * h, CrossingResidual(nodes, q0c, i0, l, t)});
      if (row->size() - first >= static_cast<std::size_t>(kMaxCrossingsPerStart)) break;
    } else if (l >= 2 && f_prev + r2 > band_lo && f_prev + r2 < band_hi &&
               ((f_prev > f_prev2 && f_prev >= f && f_prev < 0) || (f_prev < f_prev2 && f_prev <= f && f_prev > 0))) {
      const double miss = std::sqrt(f_prev + r2) - ctx.radius;  // an extremum at node l - 1
      if (std::abs(miss) < kTangencyMiss) {
        const Eigen::Quaterniond a = NodeResidualRotation(nodes, q0c, i0, i0 + l - 1);
        const double r = nodes.bound.Exceeds(a) ? kAboveScanResidual : internal::QuaternionLog(a).norm();
        row->push_back({(l - 1) * h, std::hypot(miss, r)});
      }
    }
    f_prev2 = f_prev;
    f_prev = f;
  }
}

// The (s0, L) scan of one shape (rate, k; phase 0): ONE rolling table over [0, T + s_limit], and
// for every start node s0 = i0 h of one period (a whole-period shift gives the same path) the
// crossings and near-tangencies of the chord along L <= s_limit, from the table's nodes only
// (Q(s0, s0 + L) = Q(0, s0 + L) Q(0, s0)^-1).
ShapeScan ScanShape(const Context& ctx, const Elastica& e) {
  ShapeScan scan;
  if (e.IsStraight() || !std::isfinite(e.Period())) return scan;
  const internal::ElasticaRollingTable table(e,
                                             ctx.s_limit + e.Period(),
                                             kSearch.steps_per_period,
                                             kSearch.max_step,
                                             kTableMaxSteps,
                                             internal::TableRotations::kQuaternions);
  if (!table.Valid()) return scan;
  ShapeNodes nodes{&table,
                   table.MonodromyQuaternionPowers(),
                   {},
                   Eigen::Quaterniond(ctx.target).conjugate(),
                   {std::cos(ctx.goal_angle), std::sin(ctx.goal_angle)}};
  table.NodePositions(&nodes.x);
  const double h = table.Step();
  scan.step = h;
  const long last = static_cast<long>(nodes.x.size()) - 1;
  // The rows' last node: the first l with (l - 1) h >= s_limit, less one.
  long l_limit = std::max(1L, static_cast<long>(ctx.s_limit / h) - 2);
  while ((l_limit - 1) * h < ctx.s_limit) ++l_limit;
  --l_limit;
  const std::vector<double> reach = internal::ChordReach(nodes.x, table.Steps(), l_limit + 3, h);
  scan.row_end.reserve(table.Steps());
  scan.points.reserve(2 * table.Steps());  // about two points a row on the rotation problem
  for (long i0 = 0; i0 < table.Steps(); ++i0) {
    ScanRow(ctx, nodes, reach, h, i0, std::min(last - i0, l_limit), ctx.s_limit, &scan.points);
    scan.row_end.push_back(scan.points.size());
  }
  return scan;
}

// Search from one shape: every scan point with a residual below kScanResidual that is a local
// minimum over s0 (against the point of the same index in the two neighbouring rows, cyclic)
// starts the free-length search with phase rate s0 and length L.
std::vector<LocalResult> SearchShape(const Context& ctx,
                                     const Start& shape,
                                     const IsoparallelOptions& options,
                                     double covered,
                                     const std::vector<SearchRoot>& known) {
  std::vector<LocalResult> out;
  const ShapeScan scan = ScanShape(ctx, Elastica(ToParameters(shape.regime, shape.x)));
  const long n_rows = static_cast<long>(scan.row_end.size());
  for (long i0 = 0; i0 < n_rows; ++i0) {
    for (std::size_t n = 0; n < scan.RowSize(i0); ++n) {
      const ScanPoint& p = scan.points[scan.RowBegin(i0) + n];
      if (p.residual > kScanResidual || p.length <= covered) continue;
      bool minimum = true;
      for (long d : {-1L, 1L}) {
        const long nb = (i0 + d + n_rows) % n_rows;
        if (n < scan.RowSize(nb) && scan.points[scan.RowBegin(nb) + n].residual < p.residual) minimum = false;
      }
      if (!minimum) continue;
      const double x[3] = {shape.x[0], shape.x[1], shape.x[0] * i0 * scan.step};
      out.push_back(SearchLocalFreeLength(ctx, shape.regime, x, p.length, options, &known));
    }
  }
  return out;
}

}  // namespace

// General targets: the shapes are the first options.starts Halton points (regime and sense, log
// period, modulus; the phase is scanned), unshifted: the same for every seed. They are searched
// in batches (kFirstShapeBatch, then kShapeBatch); after each batch the search length shrinks to
// the cap of the solutions found so far (nothing longer is reported), deterministically for any
// thread count.
void SearchShapes(Context* ctx,
                  const IsoparallelProblem& problem,
                  const IsoparallelOptions& options,
                  double covered,
                  std::vector<Candidate>* found,
                  IsoparallelSummary* summary) {
  const std::vector<Start> shapes = MakeStarts(options, ctx->s_limit, ctx->radius, false, true);
  const int total = static_cast<int>(shapes.size());
  for (int first = 0, count = 0; first < total; first += count) {
    count = std::min(first == 0 ? kFirstShapeBatch : kShapeBatch, total - first);
    const std::vector<SearchRoot> known = SearchRoots(*found);  // fixed for the batch: any thread count
    MergeResults(
        *ctx,
        problem,
        options,
        SearchAll(
            first, count, total, options, [&](int i) { return SearchShape(*ctx, shapes[i], options, covered, known); }),
        found,
        summary);
    if (!found->empty()) ctx->s_limit = std::min(ctx->s_limit, CapLength(options, *found) * (1 + kCapMargin));
  }
}

}  // namespace plateball::internal::isoparallel
