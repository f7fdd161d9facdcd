// The error-bound formulas of section 2.3 as pure functions, against values computed by hand
// from the paper's formulas (Lemma 2.4, Theorems 2.5 and 2.6, Corollaries 2 and 3) with the
// correction of docs/paper_notes.md: Theorem 2.6's Ktilde_p = Ktilde (K^1 D_p)^3.
#include "plateball/error_bounds.h"

#include <gtest/gtest.h>

#include <cmath>

namespace plateball {
namespace {

constexpr double kRoundOff = 1e-14;  // relative: a few products of exact decimal inputs

void ExpectRel(double actual, double expected) { EXPECT_NEAR(actual, expected, kRoundOff * std::abs(expected)); }

TEST(ErrorBounds, ConstantsAreThePapersProducts) {
  ExpectRel(KBarP(2.0, 3.0), 6.0);     // Kbar_p = K_p M'_p
  ExpectRel(KTilde(0.25, 1.5), 0.75);  // Ktilde = 2 K_(1,0) M'
  // Ktilde_p = Ktilde (K^1 D_p)^3 = 0.75 (2 * 3)^3 = 162; the printed Ktilde K^1 D_p would be 4.5.
  ExpectRel(KTildeP(0.75, 2.0, 3.0), 162.0);
  EXPECT_GT(std::abs(KTildeP(0.75, 2.0, 3.0) - 0.75 * 2.0 * 3.0), 100.0);
}

TEST(ErrorBounds, TheoremsAndCorollariesByHand) {
  // Kbar_p = 6, Ktilde_p = 162, sum dtau^3 = 1e-3, n = 10, ||P|| = 0.1.
  ExpectRel(Theorem25Bound(6.0, 1e-3), 6e-3);
  ExpectRel(Corollary2Bound(6.0, 10, 0.1), 6.0 * 10 * 1e-3);           // 0.06
  ExpectRel(Theorem26Bound(6.0, 162.0, 1e-3), 168.0 * 1e-3);           // 0.168
  ExpectRel(Corollary3Bound(6.0, 162.0, 10, 0.1), 168.0 * 10 * 1e-3);  // 1.68
  // A uniform partition has sum dtau^3 = n ||P||^3: the corollaries equal the theorems.
  ExpectRel(Corollary2Bound(6.0, 10, 0.1), Theorem25Bound(6.0, 10 * 1e-3));
  ExpectRel(Corollary3Bound(6.0, 162.0, 10, 0.1), Theorem26Bound(6.0, 162.0, 10 * 1e-3));
  // Lemma 2.4's sharper per-segment form: max|p'| max|p''| h^3 / 12.
  ExpectRel(SegmentBound(2.0, 4.0, 0.1), 2.0 * 4.0 * 1e-3 / 12.0);
}

TEST(ErrorBounds, TwoSegmentsAccumulateToTheHandComputedBounds) {
  // Segment 1: h = 0.1, chord 0.05, max|p'| 2, max|p''| 4, arc t = 0.2, max|x'| 1, max|x''| 3.
  // Segment 2: h = 0.2, chord 0.1,  max|p'| 1, max|p''| 6, arc t = 0.1, max|x'| 2, max|x''| 1.
  SegmentMeasures a, b;
  a.h = 0.1, a.chord = 0.05, a.path = {2.0, 4.0}, a.arc_time = 0.2, a.arc_max_speed = 1.0, a.arc_max_acceleration = 3.0;
  b.h = 0.2, b.chord = 0.1, b.path = {1.0, 6.0}, b.arc_time = 0.1, b.arc_max_speed = 2.0, b.arc_max_acceleration = 1.0;
  ErrorBounds e;
  AccumulateSegment(a, &e);
  AccumulateSegment(b, &e);
  CompleteBounds(2, &e);
  const ErrorBoundConstants& c = e.constants;
  ExpectRel(c.K_p, 6.0);        // max |p''|
  ExpectRel(c.M_prime_p, 2.0);  // max |p'|
  ExpectRel(c.D_p, 2.0);
  ExpectRel(c.C_p, 2.0);      // max h / chord = max(2, 2)
  ExpectRel(c.M_prime, 2.0);  // max |x'|
  ExpectRel(c.K_10, 1.5);     // max |x''| / 2
  ExpectRel(c.K1, 4.0);       // max t / chord = max(4, 1)
  ExpectRel(c.K_bar_p, 12.0);
  ExpectRel(c.K_tilde, 6.0);            // 2 * 1.5 * 2
  ExpectRel(c.K_tilde_p, 6.0 * 512.0);  // 6 (4 * 2)^3 = 3072
  EXPECT_EQ(e.segments, 2);
  ExpectRel(e.sum_dtau_cubed, 0.009);
  ExpectRel(e.parameter_norm, 0.2);
  ExpectRel(e.theorem_2_5, 12.0 * 0.009);        // 0.108
  ExpectRel(e.corollary_2, 12.0 * 2 * 0.008);    // 0.192
  ExpectRel(e.theorem_2_6, 3084.0 * 0.009);      // 27.756
  ExpectRel(e.corollary_3, 3084.0 * 2 * 0.008);  // 49.344
  // a-posteriori: (2*4*0.001 + 1*6*0.008)/12 for the path, (1*3*0.008 + 2*1*0.001)/12 for the arcs.
  ExpectRel(e.a_posteriori_path, 0.056 / 12.0);
  ExpectRel(e.a_posteriori_arcs, 0.026 / 12.0);
  ExpectRel(e.a_posteriori, 0.082 / 12.0);
  // The corollaries never undercut the theorems (||P|| is the largest step).
  EXPECT_GE(e.corollary_2, e.theorem_2_5);
  EXPECT_GE(e.corollary_3, e.theorem_2_6);
}

TEST(ErrorBounds, NoSegmentsGiveZeroBounds) {
  ErrorBounds e;
  CompleteBounds(0, &e);
  EXPECT_EQ(e.theorem_2_6, 0.0);
  EXPECT_EQ(e.corollary_3, 0.0);
  EXPECT_EQ(e.a_posteriori, 0.0);
}

}  // namespace
}  // namespace plateball
