#include "certify/separatrix.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "certify/bisection.h"
#include "certify/tails.h"
#include "check.h"

namespace plateball::internal {

namespace {

// The largest |v| a box reaches: its start phase plus rate times length.
double MaxAbsV(const CertifyBox& box) {
  const double phase = std::max(std::abs(box.lo[kCertifyPhase]), std::abs(box.hi[kCertifyPhase]));
  const double rate = std::max(std::abs(box.lo[kCertifyRate]), std::abs(box.hi[kCertifyRate]));
  return phase + rate * box.hi[kCertifyLength];
}

}  // namespace

double SeparatrixRunHeadingSpread(PendulumRegime regime, double w) {
  const double spread = std::asin(1.0 / std::cosh(std::min(std::abs(w), 350.0)));
  return regime == PendulumRegime::kRotating ? 2.0 * spread : spread;
}

double SeparatrixRunDistance(const CertifyTarget& target, PendulumRegime regime, double cap, double margin) {
  const double delta = StraightResidual(target) - margin;
  if (!(delta > 0.0)) return kInfinity;
  const auto excluded = [&](double w) {
    return StraightRunDeviationBound(SeparatrixRunHeadingSpread(regime, w), cap, target.radius) < delta;
  };
  double lo = 0.0, hi = 1.0;
  while (!excluded(hi)) {
    hi *= 2.0;
    if (hi > 700.0) return kInfinity;  // sech underflows: the bound cannot get below delta
  }
  for (int i = 0; i < 200 && hi - lo > 1e-9 * hi; ++i) {
    const double mid = 0.5 * (lo + hi);
    (excluded(mid) ? hi : lo) = mid;
  }
  return hi;  // excluded(hi) holds, and the spread decreases in w: every w >= hi is excluded
}

double SeparatrixDeviationBound(PendulumRegime regime, const CertifyBox& box, CertifyPoint* contributions) {
  const double mk = HeadingModulusBoundNearSeparatrix(regime, box.hi[kCertifyModulus], MaxAbsV(box));
  return RollingDeviationBoundFor(regime, box, mk, contributions);
}

std::string SeparatrixTailOptions::Validate() const {
  if (!(k_lo >= 0.5 && k_lo < 1.0)) return InvalidValueMessage("k_lo", k_lo, "expected a modulus in [0.5, 1)");
  if (!(rate_max > 0.0 && rate_max <= 1e3)) return InvalidValueMessage("rate_max", rate_max, "expected (0, 1000]");
  if (!(cap > 0.0 && cap <= 1e3)) return InvalidValueMessage("cap", cap, "expected a length in (0, 1000]");
  if (!(length_lo >= 0.0 && length_lo < cap))
    return InvalidValueMessage("length_lo", length_lo, "expected a length in [0, cap)");
  const std::string budget = ValidateBisectionBudget(max_boxes, accept_deviation, keep_undecided, margin);
  if (!budget.empty()) return budget;
  if (!(max_step > 0.0 && max_step <= 1.0)) return InvalidValueMessage("max_step", max_step, "expected (0, 1]");
  return "";
}

SeparatrixTailResult CertifySeparatrixTail(const CertifyTarget& target, const SeparatrixTailOptions& options) {
  SeparatrixTailResult result;
  result.message = options.Validate();
  if (!result.message.empty()) {
    result.status = SeparatrixTailStatus::kInvalidInput;
    return result;
  }
  result.run_distance = SeparatrixRunDistance(target, options.regime, options.cap, options.margin);
  if (!std::isfinite(result.run_distance)) {
    result.status = SeparatrixTailStatus::kUndecided;
    result.message = "the straight residual is not above the margin: runs are not excluded";
    return result;
  }
  const double phase = result.run_distance + options.rate_max * options.cap;
  result.window.lo = {-options.rate_max, options.k_lo, -phase, options.length_lo};
  result.window.hi = {options.rate_max, 1.0, phase, options.cap};
  BisectionTally tally;
  const auto decide = [&](const CertifyBox& box) {
    CertifyPoint share;
    const double deviation = SeparatrixDeviationBound(options.regime, box, &share);
    CertifyResidual centre;
    BoxVerdict verdict = BoxVerdict::kUndecided;
    if (EvaluateCertifyResidual(target, options.regime, box.Centre(), options.max_step, &centre))
      verdict = TestBox(centre, deviation, options.margin);
    return DecideByVerdict(verdict, deviation, options.accept_deviation, share);
  };
  const auto keep = [&](const CertifyBox& box) {
    if (static_cast<int>(result.undecided_boxes.size()) < options.keep_undecided) result.undecided_boxes.push_back(box);
  };
  Bisect(result.window, 1.0, options.max_boxes, decide, keep, options.interrupted, &tally);
  result.boxes = tally.boxes;
  result.excluded_by_chord = tally.excluded_by_chord;
  result.excluded_by_rotation = tally.excluded_by_rotation;
  result.undecided = tally.undecided;
  result.resolved_volume = tally.resolved_volume;
  result.status = tally.Status();
  return result;
}

}  // namespace plateball::internal
