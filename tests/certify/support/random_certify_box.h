// Test support: random parameter boxes for the certificate's bound tests (the centre drawn in given
// ranges, each half-width a log-uniform fraction of its axis' scale); each test then adapts the
// box to its bound's domain (k range, rate sign, G = 1).
#pragma once

#include <cmath>
#include <random>

#include "certify/vocabulary.h"

namespace plateball::testing {

/// lo * (hi / lo)^U, U uniform in [0, 1).
inline double LogUniform(double lo, double hi, std::mt19937* rng) {
  return std::exp(std::log(lo) + std::uniform_real_distribution<double>(0.0, 1.0)(*rng) * std::log(hi / lo));
}

struct RandomBoxRanges {
  double rate_lo, rate_hi;      // |rate| of the centre, log-uniform (either sign when rotating)
  double k_lo, k_hi;            // k of the centre, uniform
  double length_lo, length_hi;  // L of the centre, uniform (the phase: uniform in [-6, 6])
  double length_scale;          // the length axis' scale (rate: |rate|, k: 0.3, phase: 1)
  double half_lo, half_hi;      // half-widths: log-uniform fractions of each axis' scale
};

/// A box around a random centre (not clipped to any domain).
inline internal::CertifyBox RandomCertifyBox(PendulumRegime regime, const RandomBoxRanges& r, std::mt19937* rng) {
  using internal::CertifyPoint;
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  const double sign = regime == PendulumRegime::kRotating && unit(*rng) < 0.5 ? -1.0 : 1.0;
  const CertifyPoint c = {sign * LogUniform(r.rate_lo, r.rate_hi, rng),
                          r.k_lo + (r.k_hi - r.k_lo) * unit(*rng),
                          -6.0 + 12.0 * unit(*rng),
                          r.length_lo + (r.length_hi - r.length_lo) * unit(*rng)};
  const CertifyPoint scale = {std::abs(c[internal::kCertifyRate]), 0.3, 1.0, r.length_scale};
  internal::CertifyBox box;
  for (int i = 0; i < 4; ++i) {
    const double h = scale[i] * LogUniform(r.half_lo, r.half_hi, rng);
    box.lo[i] = c[i] - h;
    box.hi[i] = c[i] + h;
  }
  return box;
}

}  // namespace plateball::testing
