#include "certify/loops.h"

#include <algorithm>
#include <cmath>

#include "certify/separatrix.h"
#include "certify/tails.h"
#include "check.h"
#include "elastica_closed_rolling.h"
#include "jacobi_elliptic.h"
#include "plateball/so3.h"
#include "rotation_trick.h"

namespace plateball::internal {

namespace {

// The sense of core j: rotating sigma_0 in every cell, oscillating mirrored in every other one.
int CoreSense(PendulumRegime regime, int sense, long j) {
  return regime == PendulumRegime::kRotating || std::abs(j) % 2 == 0 ? sense : -sense;
}

// A straight run of length l in the run direction pi: chord (-l, 0), rolling exp(hat(e3 x chord)).
void AppendRun(double l, LoopModelRolling* out) {
  out->rolling = ExpSO3(Eigen::Vector3d(0.0, -l, 0.0)) * out->rolling;
  out->chord += Eigen::Vector2d(-l, 0.0);
}

// The core piece v' = b (s - c) in [v1, v1 + b l] of a core of sense `sense`: the rotating
// elastica at kLoopCoreModulus (heading 2 am(v) = 2 gd(v) within its gap) with rate sense * b.
void AppendCore(int sense, double b, double v1, double l, LoopModelRolling* out) {
  ElasticaParameters p;
  p.regime = PendulumRegime::kRotating;
  p.modulus = kLoopCoreModulus;
  p.rate = sense * b;
  p.phase = sense * v1;
  p.heading_w = M_PI / 2;  // heading = pendulum angle
  const Elastica e(p);
  out->rolling = ElasticaClosedRolling(e).Rolling(l) * out->rolling;
  out->chord += e.Position(l);
}

// sum_{j = lo}^{hi} |j - m| over integers (lo <= hi).
double SumAbsDistance(double lo, double hi, double m) {
  const auto tri = [](double n) { return n > 0.0 ? 0.5 * n * (n + 1.0) : 0.0; };
  if (m <= lo) return (hi - lo + 1.0) * (0.5 * (lo + hi) - m);
  if (m >= hi) return (hi - lo + 1.0) * (m - 0.5 * (lo + hi));
  return tri(m - lo) + tri(hi - m);
}

// The cores j (core 0 at the phase) that can meet [0, L_max] for some point of the box, the phase
// range widened by `widen`: [lo, hi], empty when lo > hi.
void RelevantCores(double w_max, double p_min, const CertifyBox& box, double widen, double* lo, double* hi) {
  const double t_lo = box.lo[kLoopPhase] - widen, t_hi = box.hi[kLoopPhase] + widen;
  // j >= 0: c_j >= t0 + j P_min must satisfy c_j - w <= L_max; j < 0: c_j <= t0 + j P_min, c_j + w >= 0.
  *hi = std::floor((box.hi[kLoopLength] + w_max - t_lo) / p_min);
  *lo = std::ceil(-(t_hi + w_max) / p_min);
}

}  // namespace

bool LoopBoxOutsideDomain(double core_half_width, double run_min_k, double run_cap, const CertifyBox& box) {
  // Every path's (capped) model point has t0 in [-W2/b, r + W2/b] and r >= min(2 (K_t - W2)/b, run_cap)
  // (run_min_k = 2 (K_t - W2); a run longer than run_cap is written as run_cap, CapLoopRun).
  const double w_max = core_half_width / box.lo[kLoopRate];
  return box.lo[kLoopPhase] > box.hi[kLoopRun] + w_max || box.hi[kLoopPhase] < -w_max ||
         box.hi[kLoopRun] < std::min(run_min_k / box.hi[kLoopRate], run_cap);
}

LoopModelPoint CapLoopRun(const LoopModelPoint& point, double run_cap, double core_half_width) {
  LoopModelPoint out = point;
  if (point.x[kLoopRun] <= run_cap) return out;
  // At most one core meets [0, L] (run_cap >= L): keep it where it is, or put it just after L.
  out.x[kLoopRun] = run_cap;
  out.x[kLoopPhase] = std::min(point.x[kLoopPhase], point.x[kLoopLength] + core_half_width / point.x[kLoopRate]);
  return out;
}

double LoopModelHeadingError(PendulumRegime regime, double k_t, double core_half_width) {
  // 2 asin(sech W2) = pi - 2 gd(W2): the separatrix's distance to its limit direction beyond W2
  // (the rotating run spread's formula; it is the same in both regimes).
  return SeparatrixHeadingGapSup(regime, k_t) + SeparatrixRunHeadingSpread(PendulumRegime::kRotating, core_half_width);
}

LoopHeadingError::LoopHeadingError(PendulumRegime regime, double k_t, double core_half_width)
    : regime_(regime),
      k_t_(k_t),
      v_one_core_(std::min(core_half_width, CompleteEllipticK(k_t))),
      gap_sup_(SeparatrixHeadingGapSup(regime, k_t)),
      core_gap_(SeparatrixHeadingGapSup(PendulumRegime::kRotating, kLoopCoreModulus)),
      family_(LoopModelHeadingError(regime, k_t, core_half_width) + core_gap_) {}

double LoopHeadingError::ForBox(const CertifyBox& box) const {
  const double t_lo = box.lo[kLoopPhase], t_hi = box.hi[kLoopPhase];
  const double reach =
      std::max({std::abs(t_lo), std::abs(t_hi), box.hi[kLoopLength] - t_lo, t_hi - box.lo[kLoopLength]});
  const double v_max = box.hi[kLoopRate] * reach;
  if (!(v_max <= v_one_core_)) return family_;
  return std::min(SeparatrixHeadingGapGrowing(regime_, k_t_, v_max), gap_sup_) + core_gap_;
}

double LoopCoreHalfWidthFor(PendulumRegime regime, double k_t) {
  const double gap = SeparatrixHeadingGapSup(regime, k_t);
  const double w = gap > 0.0 ? std::acosh(1.0 / std::sin(0.5 * std::min(gap, 1.0))) : 700.0;
  return std::min(w, CompleteEllipticK(k_t));
}

LoopModelRolling RollLoopModel(PendulumRegime regime, int sense, double core_half_width, const CertifyPoint& x) {
  const double b = x[kLoopRate], length = x[kLoopLength], t0 = x[kLoopPhase];
  const double w = core_half_width / b, period = x[kLoopRun] + 2.0 * w;
  LoopModelRolling out;
  double s = 0.0;
  // The first core whose end c_j + w is not before the start.
  for (long j = static_cast<long>(std::ceil((-w - t0) / period)); s < length; ++j) {
    const double c = t0 + static_cast<double>(j) * period;
    const double start = std::max(s, c - w);
    if (start > s) AppendRun(std::min(start, length) - s, &out);
    if (start >= length) break;
    const double end = std::min(length, c + w);
    if (end > start) AppendCore(CoreSense(regime, sense, j), b, b * (start - c), end - start, &out);
    s = std::max(s, end);  // (a first core ending a rounding error before 0 is skipped)
  }
  return out;
}

bool EvaluateLoopModelResidual(const CertifyTarget& target,
                               PendulumRegime regime,
                               int sense,
                               double core_half_width,
                               const CertifyPoint& x,
                               CertifyResidual* out) {
  if (!(x[kLoopRate] > 0.0) || !(x[kLoopRun] >= 0.0) || !(x[kLoopLength] > 0.0) || !std::isfinite(x[kLoopPhase]) ||
      !std::isfinite(x[kLoopRate] * x[kLoopLength]) || !std::isfinite(x[kLoopRun] + x[kLoopLength]))
    return false;
  const LoopModelRolling m = RollLoopModel(regime, sense, core_half_width, x);
  out->chord_norm = m.chord.norm();
  out->chord_miss = out->chord_norm - target.radius;
  out->rotation = RotationTrickResidual(target.target, ChordTurn(target.goal_angle, m.chord), m.rolling).norm();
  return std::isfinite(out->rotation) && std::isfinite(out->chord_norm);
}

double LoopModelDeviationBound(double core_half_width, const CertifyBox& box, CertifyPoint* shares) {
  const CertifyPoint c = box.Centre();
  const double w2 = core_half_width, b_lo = box.lo[kLoopRate], b_hi = box.hi[kLoopRate];
  const double length_max = box.hi[kLoopLength];
  // |d(1/b)| from the centre, and the period's change dP = dr + 2 W2 d(1/b).
  const double dq = std::max(1.0 / b_lo - 1.0 / c[kLoopRate], 1.0 / c[kLoopRate] - 1.0 / b_hi);
  const double dr = box.HalfWidth(kLoopRun), dt = box.HalfWidth(kLoopPhase), dl = box.HalfWidth(kLoopLength);
  const double dp = dr + 2.0 * w2 * dq;
  const double w_max = w2 / b_lo, p_min = box.lo[kLoopRun] + 2.0 * w2 / b_hi;
  const double p_max = box.hi[kLoopRun] + 2.0 * w2 / b_lo;
  // Step A: (b, r) change with core m's centre fixed (cores j move by (j - m) dP, each also changes
  // shape by 2 kLoopCoreRateIntegral |d(1/b)|); step B: a shift by dt0 + m dP, 2 |shift|.
  double best = 0.0, best_rate = 0.0, best_run = 0.0;
  bool first = true;
  double j_lo = 0.0, j_hi = 0.0;
  RelevantCores(w_max, p_min, box, 0.0, &j_lo, &j_hi);
  const double mid = j_lo <= j_hi ? std::round(0.5 * (j_lo + j_hi)) : 0.0;
  for (const double m : {0.0, mid}) {
    double lo = 0.0, hi = 0.0;
    RelevantCores(w_max, p_min, box, std::abs(m) * (p_max - p_min), &lo, &hi);
    const double n = lo <= hi ? hi - lo + 1.0 : 0.0;
    const double spread = n > 0.0 ? 2.0 * M_PI * SumAbsDistance(lo, hi, m) : 0.0;
    const double step_a = std::min(spread * dp + n * 2.0 * kLoopCoreRateIntegral * dq, 2.0 * length_max);
    const double total = step_a + 2.0 * std::abs(m) * dp;
    if (first || total < best) {
      best = total;
      best_rate = (n * 2.0 * kLoopCoreRateIntegral + (spread + 2.0 * std::abs(m)) * 2.0 * w2) * dq;
      best_run = (spread + 2.0 * std::abs(m)) * dr;
      first = false;
    }
  }
  if (shares != nullptr) *shares = {best_rate, best_run, 2.0 * dt, dl};
  return best + 2.0 * dt + dl;
}

LoopModelPoint LoopModelOf(const Elastica& e, double length, double core_half_width) {
  const ElasticaParameters& p = e.parameters();
  const double a = p.rate, b = std::abs(a), kk = CompleteEllipticK(p.modulus), w = core_half_width / b;
  // Core centres s_j = (2 j K - u0) / a; the first along s with s_j >= -w.
  const double m = (p.phase - a * w) / (2.0 * kk);
  const double j = a > 0.0 ? std::ceil(m) : std::floor(m);
  LoopModelPoint out;
  const int sign = a > 0.0 ? 1 : -1;
  out.sense = p.regime == PendulumRegime::kRotating || std::fmod(std::abs(j), 2.0) == 0.0 ? sign : -sign;
  out.x = {b, (2.0 * kk - 2.0 * core_half_width) / b, (2.0 * j * kk - p.phase) / a, length};
  return out;
}

std::string LoopFamilyOptions::Validate() const {
  if (!(k_t >= 0.9 && k_t < 1.0)) return InvalidValueMessage("k_t", k_t, "expected a modulus in [0.9, 1)");
  const double kk = CompleteEllipticK(k_t);
  if (!(core_half_width >= 0.0 && core_half_width <= kk))
    return InvalidValueMessage("core_half_width", core_half_width, "expected [0, K(k_t)] (0: automatic)");
  if (!(rate_lo > 0.0 && rate_lo <= 1e3)) return InvalidValueMessage("rate_lo", rate_lo, "expected (0, 1000]");
  if (!(rate_max > rate_lo && rate_max <= 1e3))
    return InvalidValueMessage("rate_max", rate_max, "expected (rate_lo, 1000]");
  if (!(cap > 0.0 && cap <= 1e3)) return InvalidValueMessage("cap", cap, "expected a length in (0, 1000]");
  if (!(length_lo >= 0.0 && length_lo < cap))
    return InvalidValueMessage("length_lo", length_lo, "expected a length in [0, cap)");
  return ValidateBisectionBudget(max_boxes, accept_deviation, keep_undecided, margin);
}

LoopFamilyResult CertifyLoopFamily(const CertifyTarget& target, const LoopFamilyOptions& options) {
  LoopFamilyResult result;
  result.message = options.Validate();
  if (!result.message.empty()) {
    result.status = LoopFamilyStatus::kInvalidInput;
    return result;
  }
  const double w2 =
      options.core_half_width > 0.0 ? options.core_half_width : LoopCoreHalfWidthFor(options.regime, options.k_t);
  result.core_half_width = w2;
  const LoopHeadingError heading_error(options.regime, options.k_t, w2);
  result.heading_error = heading_error.Family();
  const double run_min_k = 2.0 * (CompleteEllipticK(options.k_t) - w2);
  const double run_lo = std::max(0.0, run_min_k / options.rate_max);
  const double w_max = w2 / options.rate_lo;
  result.window.lo = {options.rate_lo, run_lo, -w_max, options.length_lo};
  result.window.hi = {options.rate_max, std::max(options.cap, run_lo), options.cap + w_max, options.cap};
  BisectionTally tally;
  for (const int sense : {1, -1}) {
    const auto decide = [&](const CertifyBox& box) {
      if (LoopBoxOutsideDomain(w2, run_min_k, result.window.hi[kLoopRun], box))
        return BoxDecision{BoxFate::kOutsideDomain};
      CertifyPoint share;
      const double model = LoopModelDeviationBound(w2, box, &share);
      const double deviation = model + heading_error.ForBox(box) * box.hi[kLoopLength];
      CertifyResidual centre;
      BoxVerdict verdict = BoxVerdict::kUndecided;
      if (EvaluateLoopModelResidual(target, options.regime, sense, w2, box.Centre(), &centre))
        verdict = TestBox(centre, deviation, options.margin);
      return DecideByVerdict(verdict, model, options.accept_deviation, share);
    };
    const auto keep = [&](const CertifyBox& box) {
      if (static_cast<int>(result.undecided_boxes.size()) >= options.keep_undecided) return;
      result.undecided_boxes.push_back(box);
      result.undecided_senses.push_back(sense);
    };
    Bisect(result.window, 0.5, options.max_boxes, decide, keep, options.interrupted, &tally);
  }
  result.boxes = tally.boxes;
  result.excluded_by_chord = tally.excluded_by_chord;
  result.excluded_by_rotation = tally.excluded_by_rotation;
  result.outside_domain = tally.outside_domain;
  result.undecided = tally.undecided;
  result.resolved_volume = tally.resolved_volume;
  result.status = tally.Status();
  return result;
}

}  // namespace plateball::internal
