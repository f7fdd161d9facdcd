#include "certify/window.h"

#include <Eigen/LU>
#include <algorithm>
#include <cmath>
#include <string>

#include "certify/centred.h"
#include "certify/costate.h"
#include "certify/jacobian.h"
#include "certify/periods.h"
#include "certify/rolling.h"

namespace plateball::internal {

namespace {

// Whether the box meets (inside = false) or lies inside (inside = true) the neighbourhood
// |x_i - known_i| <= match_i of a known solution, the phase taken modulo its period.
bool InNeighbourhood(
    const CertifyBox& box, PendulumRegime regime, const CertifyPoint& known, const CertifyPoint& match, bool inside) {
  const auto fits = [&](int axis, double centre) {
    const double lo = centre - match[axis], hi = centre + match[axis];
    return inside ? box.lo[axis] >= lo && box.hi[axis] <= hi : box.hi[axis] >= lo && box.lo[axis] <= hi;
  };
  for (int axis : {kCertifyRate, kCertifyModulus, kCertifyLength})
    if (!fits(axis, known[axis])) return false;
  const double period = PhasePeriod(regime, known[kCertifyModulus]);
  for (int j = -2; j <= 2; ++j)
    if (fits(kCertifyPhase, known[kCertifyPhase] + j * period)) return true;
  return false;
}

// Volume of a box (degenerate axes count as width 1).
double BoxVolume(const CertifyBox& box) {
  double v = 1.0;
  for (int i = 0; i < 4; ++i) v *= box.hi[i] > box.lo[i] ? box.hi[i] - box.lo[i] : 1.0;
  return v;
}

// Index of the known solution whose neighbourhood holds (inside) or meets the box, or -1.
int MatchKnown(const CertifyBox& box,
               const CertifyWindowOptions& options,
               const std::vector<CertifyPoint>& known,
               bool inside) {
  for (size_t i = 0; i < known.size(); ++i)
    if (InNeighbourhood(box, options.regime, known[i], options.match, inside)) return static_cast<int>(i);
  return -1;
}

// Whether the box lies inside one of `boxes`.
bool InsideAny(const CertifyBox& box, const std::vector<CertifyBox>& boxes) {
  for (const CertifyBox& b : boxes) {
    bool inside = true;
    for (int i = 0; i < 4; ++i) inside = inside && box.lo[i] >= b.lo[i] && box.hi[i] <= b.hi[i];
    if (inside) return true;
  }
  return false;
}

// A solution proved unique in its box, in canonical form: recorded with the known one whose
// neighbourhood holds it, unless the same path is already found (the phase window of one period
// at k_max holds a path twice for smaller k: boxes one period apart).
void RecordFound(const CertifyPoint& x,
                 const CertifyWindowOptions& options,
                 const std::vector<CertifyPoint>& known,
                 CertifyWindowResult* result) {
  ElasticaParameters parameters;
  parameters.regime = options.regime;
  parameters.rate = x[kCertifyRate];
  parameters.modulus = x[kCertifyModulus];
  parameters.phase = x[kCertifyPhase];
  const CertifyPoint canonical = CanonicalSolution(parameters, x[kCertifyLength]);
  for (const CertifyPoint& f : result->found)
    if (SamePath(options.regime, f, canonical, kSamePathTolerance)) {
      ++result->found_repeated;
      return;
    }
  CertifyBox point;
  point.lo = point.hi = canonical;
  result->found.push_back(canonical);
  result->found_known.push_back(MatchKnown(point, options, known, false));
}

// The error the first-order tests allow on each component of the centre's residual.
double FirstOrderMargin(const CertifyWindowOptions& options, const CertifyBox& box) {
  return options.first_order_margin + CertifyResidualError(box);
}

// The first-order verdict of a box the zeroth-order test left undecided, the axis to split when
// it stays undecided (the largest column of the Krawczyk contraction times the half-widths, or
// -1), and for a proved unique solution its Newton refinement (the box centre if Newton fails).
struct FirstOrderOutcome {
  FirstOrderVerdict verdict = FirstOrderVerdict::kNotRun;
  int split_axis = -1;
  CertifyPoint solution{};
  CertifyPoint contraction{};  // per axis: the column of the contraction times the half-width
  CertifyBox proved;           // the box proved to hold exactly one solution (kUnique, proved_nearby)
  bool proved_nearby = false;  // undecided, but a box around a Newton point in it is proved
};

FirstOrderOutcome FirstOrderBox(const CertifyTarget& target,
                                const CertifyWindowOptions& options,
                                const CertifyBox& box,
                                const std::vector<CertifyBox>& proved) {
  FirstOrderOutcome out;
  CertifyJacobian centre;
  Eigen::Matrix4d radius;
  const double margin = FirstOrderMargin(options, box);
  if (!EvaluateCertifyJacobian(target, options.regime, box.Centre(), options.max_step, &centre) ||
      !CertifyJacobianEnclosure(options.regime, box, centre, margin, &radius))
    return out;
  out.verdict = FirstOrderTest(box, centre, radius, margin);
  if (out.verdict == FirstOrderVerdict::kUnique) {
    out.solution = box.Centre();
    CertifyPoint x = out.solution;
    if (NewtonRefineCertify(target, options.regime, options.max_step, 1e-11, 30, &x)) {
      bool inside = true;
      for (int i = 0; i < 4; ++i) inside = inside && x[i] >= box.lo[i] && x[i] <= box.hi[i];
      if (inside) out.solution = x;
    }
    out.proved = box;
  } else if (out.verdict == FirstOrderVerdict::kUndecided) {
    const Eigen::FullPivLU<Eigen::Matrix4d> lu(centre.jacobian);
    const Eigen::Matrix4d a = lu.isInvertible() ? Eigen::Matrix4d(lu.inverse()) : Eigen::Matrix4d::Identity();
    const Eigen::Matrix4d spread =
        (Eigen::Matrix4d::Identity() - a * centre.jacobian).cwiseAbs() + a.cwiseAbs() * radius;
    double best = -1.0;
    for (int j = 0; j < 4; ++j) {
      const double share = spread.col(j).sum() * box.HalfWidth(j);
      out.contraction[j] = share;
      if (share > best) best = share, out.split_axis = j;
    }
    // A box of this size around a solution is proved only where the contraction is below one;
    // a Newton point inside a proved box is a found solution already.
    Eigen::Vector4d h;
    for (int i = 0; i < 4; ++i) h[i] = box.HalfWidth(i);
    const Eigen::Vector4d newton = a * centre.residual;
    CertifyBox target_point;
    for (int i = 0; i < 4; ++i) target_point.lo[i] = target_point.hi[i] = box.Centre()[i] - newton[i];
    if (((spread * h).array() < h.array()).all() && !InsideAny(target_point, proved))
      out.proved_nearby = ProveAroundNewtonPoint(
          target, options.regime, box, centre, options.max_step, margin, &out.proved, &out.solution);
  }
  return out;
}

// Counts a first-order outcome and records its proved solution and box; true when the box is
// resolved (excluded, or proved to hold exactly one solution).
bool RecordFirstOrder(const FirstOrderOutcome& first,
                      const CertifyWindowOptions& options,
                      const std::vector<CertifyPoint>& known,
                      std::vector<CertifyBox>* proved,
                      CertifyWindowResult* result) {
  if (first.verdict != FirstOrderVerdict::kNotRun) ++result->first_order_tried;
  if (first.verdict == FirstOrderVerdict::kUnique || first.proved_nearby) {
    RecordFound(first.solution, options, known, result);
    proved->push_back(first.proved);
  }
  if (first.verdict == FirstOrderVerdict::kExcluded) ++result->excluded_first_order;
  return first.verdict == FirstOrderVerdict::kExcluded || first.verdict == FirstOrderVerdict::kUnique;
}

// The one-line account of a window's branch and bound.
std::string CertifyMessage(const CertifyWindowResult& result, bool first_order) {
  std::string message = ToString(result.status) + ": " + std::to_string(result.boxes) + " boxes, " +
                        std::to_string(result.excluded_by_chord) + " excluded by the chord, " +
                        std::to_string(result.excluded_by_rotation) + " by the rotation, " +
                        std::to_string(result.excluded_by_costate) + " by the costate, " +
                        std::to_string(result.accounted) + " next to known solutions, " +
                        std::to_string(result.unaccounted) + " unaccounted";
  if (first_order)
    message += ", " + std::to_string(result.first_order_tried) + " given the first-order tests, " +
               std::to_string(result.excluded_first_order) + " excluded by them, " +
               std::to_string(result.found.size()) + " proved unique" +
               (result.found_repeated > 0 ? " (" + std::to_string(result.found_repeated) + " proved again)" : "") +
               (result.inside_found > 0 ? ", " + std::to_string(result.inside_found) + " inside their boxes" : "");
  return message;
}

}  // namespace

std::string ToString(CertifyStatus status) {
  switch (status) {
    case CertifyStatus::kNotRun:
      return "not run";
    case CertifyStatus::kCertified:
      return "certified";
    case CertifyStatus::kUnaccounted:
      return "unaccounted box";
    case CertifyStatus::kBudgetExhausted:
      return "budget exhausted";
    case CertifyStatus::kInvalidInput:
      return "invalid input";
    case CertifyStatus::kInterrupted:
      return "interrupted";
  }
  return "unknown";
}

namespace {

// The rotation test with min(D, R, Rt, Rc) (R: the costate chart, Rt: the theta/2 chart,
// certify/rolling.h; Rc: the centred form, certify/centred.h) on a box D
// leaves undecided; stop = min(D, slack).
BoxVerdict ClosedFormRotationTest(const CertifyWindowOptions& options,
                                  const CertifyBox& box,
                                  double stop,
                                  double slack,
                                  CertifyWindowResult* result) {
  if (options.closed_rolling && ClosedRollingDeviationBound(options.regime, box, options.margin, stop) < slack) {
    ++result->excluded_by_closed_rolling;
    return BoxVerdict::kExcludedByRotation;
  }
  if (options.chart_rolling && ChartRollingDeviationBound(options.regime, box, options.margin, stop) < slack) {
    ++result->excluded_by_chart_rolling;
    return BoxVerdict::kExcludedByRotation;
  }
  if (options.centred_rolling && CentredRollingDeviationBound(options.regime, box, options.margin, stop) < slack) {
    ++result->excluded_by_centred_rolling;
    return BoxVerdict::kExcludedByRotation;
  }
  return BoxVerdict::kUndecided;
}

}  // namespace

CertifyWindowResult CertifyWindow(const CertifyTarget& target,
                                  const std::vector<CertifyPoint>& known,
                                  const CertifyWindowOptions& options) {
  CertifyWindowResult result;
  result.matched.assign(known.size(), 0);
  if (const std::string error = options.Validate(); !error.empty()) {
    result.status = CertifyStatus::kInvalidInput;
    result.message = error;
    return result;
  }
  std::vector<CertifyBox> stack{options.window};  // depth first: memory ~ depth
  std::vector<CertifyBox> proved;                 // boxes proved to hold exactly one (found) solution
  const double window_volume = BoxVolume(options.window);
  bool interrupted = false;
  while (!stack.empty()) {
    if (result.boxes >= options.max_boxes) break;
    if ((interrupted = InterruptRequested(options.interrupted, result.boxes))) break;
    const CertifyBox box = stack.back();
    stack.pop_back();
    ++result.boxes;
    int hit = MatchKnown(box, options, known, true);
    if (hit < 0 && InsideAny(box, proved)) {  // its only solution is a found one
      ++result.inside_found;
      result.resolved_volume += BoxVolume(box) / window_volume;
      continue;
    }
    CertifyPoint share;
    const double deviation = RollingDeviationBound(options.regime, box, &share);
    BoxVerdict verdict = BoxVerdict::kUndecided;
    CertifyResidual centre;
    if (hit < 0 && EvaluateCertifyResidual(target, options.regime, box.Centre(), options.max_step, &centre)) {
      const double chord_deviation = std::min(deviation, ChordDeviationBound(options.regime, box));
      verdict = TestBox(centre, deviation, chord_deviation, options.margin);
      const double slack = RotationSlack(centre, chord_deviation, options.margin);
      if (verdict == BoxVerdict::kUndecided && slack > box.HalfWidth(kCertifyLength))
        verdict = ClosedFormRotationTest(options, box, std::min(deviation, slack), slack, &result);
      if (verdict == BoxVerdict::kUndecided && options.costate &&
          CostateExcludes(target, options.regime, box, chord_deviation, options.margin))
        verdict = BoxVerdict::kExcludedByCostate;
      if (verdict == BoxVerdict::kUndecided && options.fixed_periods &&
          (verdict = FixedPeriodsTest(options, box, centre, deviation, chord_deviation)) != BoxVerdict::kUndecided)
        ++result.excluded_by_fixed_periods;
    }
    if (verdict != BoxVerdict::kUndecided) {
      ++(verdict == BoxVerdict::kExcludedByChord      ? result.excluded_by_chord
         : verdict == BoxVerdict::kExcludedByRotation ? result.excluded_by_rotation
                                                      : result.excluded_by_costate);
      result.resolved_volume += BoxVolume(box) / window_volume;
      continue;
    }
    if (options.fixed_periods) {  // split as the fixed-periods bound sees the box, when it is the smaller
      CertifyPoint periods_share;
      if (FixedPeriodsDeviationBound(options.regime, box, &periods_share) < deviation) share = periods_share;
    }
    int axis = static_cast<int>(std::max_element(share.begin(), share.end()) - share.begin());
    FirstOrderOutcome first;
    if (hit < 0 && options.first_order && deviation <= options.first_order_deviation &&
        CertifyEnclosureAvailable(
            options.regime, box, centre.chord_norm, centre.rotation, FirstOrderMargin(options, box))) {
      first = FirstOrderBox(target, options, box, proved);
      if (RecordFirstOrder(first, options, known, &proved, &result)) {
        result.resolved_volume += BoxVolume(box) / window_volume;
        continue;
      }
      if (first.split_axis >= 0) axis = first.split_axis;
    }
    const double smallest = options.first_order ? options.first_order_min_deviation : options.accept_deviation;
    if (hit < 0 && deviation <= smallest) hit = MatchKnown(box, options, known, false);
    if (hit >= 0) {
      ++result.matched[hit];
      ++result.accounted;
      result.resolved_volume += BoxVolume(box) / window_volume;
      continue;
    }
    if (deviation <= smallest) {
      if (result.unaccounted++ == 0) result.first_unaccounted = box;
      if (options.stop_at_unaccounted) break;
      continue;
    }
    if (options.trace) options.trace({box, deviation, share, first.contraction, axis});
    CertifyBox left = box, right = box;
    const double mid = axis == kCertifyModulus
                           ? ModulusSplitPoint(box.lo[axis], box.hi[axis], options.log_modulus_split)
                           : 0.5 * (box.lo[axis] + box.hi[axis]);
    left.hi[axis] = mid;
    right.lo[axis] = mid;
    stack.push_back(right);
    stack.push_back(left);
  }
  result.status = interrupted              ? CertifyStatus::kInterrupted
                  : result.unaccounted > 0 ? CertifyStatus::kUnaccounted
                  : stack.empty()          ? CertifyStatus::kCertified
                                           : CertifyStatus::kBudgetExhausted;
  result.message = CertifyMessage(result, options.first_order);
  return result;
}

}  // namespace plateball::internal
