// Carlson's symmetric integrals of src/carlson.h against an independent reference, Boost.Math's
// ellint_rf / ellint_rd / ellint_rj / ellint_rc evaluated in 50-digit arithmetic
// (boost::multiprecision::cpp_bin_float_50), over the argument ranges of the closed-form elastica
// and rolling (x = cn^2, y = dn^2 = cn^2 + k'^2 sn^2, z = 1, p = cn^2 + (1 - N) sn^2, with k' down
// to 1e-12 and 1 - N down to ~1e-324, the characteristic n down to -1e300 near G = 1), and against closed forms
// (DLMF 19.20) and Legendre's relation. Errors are measured in units of eps = 2^-52 relative to the reference.
#include "carlson.h"

#include <gtest/gtest.h>

#include <boost/math/special_functions/ellint_rc.hpp>
#include <boost/math/special_functions/ellint_rd.hpp>
#include <boost/math/special_functions/ellint_rf.hpp>
#include <boost/math/special_functions/ellint_rj.hpp>
#include <boost/math/special_functions/gamma.hpp>
#include <boost/multiprecision/cpp_bin_float.hpp>
#include <cmath>
#include <limits>
#include <vector>

namespace {

using plateball::internal::CarlsonRC1p;
using plateball::internal::CarlsonRD;
using plateball::internal::CarlsonRF;
using plateball::internal::CarlsonRFRJ;
using plateball::internal::CarlsonRJ;
using plateball::internal::CompleteEllipticKD;
using Big = boost::multiprecision::cpp_bin_float_50;

constexpr double kEps = std::numeric_limits<double>::epsilon();

// |value - ref| / |ref| in units of eps (ref in 50 digits).
double Ulps(double value, const Big& ref) { return static_cast<double>(abs((Big(value) - ref) / ref)) / kEps; }

// The arguments the closed forms pass: for the modulus complement kc (k'), the amplitude phi and
// the characteristic n < 0 of Pi(n; phi, k) (elastica_closed_rolling.cc reduces it to
// N = (k^2 - n) / (1 - n), 1 - N = k'^2 / (1 - n)): x = cos^2, y = cos^2 + k'^2 sin^2, z = 1,
// p = cos^2 + (1 - N) sin^2. The 50-digit arguments are the double ones, exactly.
struct Args {
  double x, y, p;
};
std::vector<Args> LibraryArgs() {
  std::vector<Args> out;
  for (double kc : {1.0, 0.9, 0.6, 0.3, 1e-2, 1e-4, 1e-6, 1e-9, 1e-12}) {
    const double kc2 = kc * kc;
    for (double phi : {1e-9, 1e-4, 0.01, 0.3, 0.8, 1.2, 1.5, 1.5707, 1.5707963, M_PI / 2}) {
      const double s = std::sin(phi), c = phi == M_PI / 2 ? 0.0 : std::cos(phi);
      for (double n : {-1e-12, -1e-3, -0.5, -3.0, -40.0, -1e4, -1e8, -1e30, -1e200, -1e300}) {
        // The library's k'^2 >= 1.1e-16 and n >= -4e300 (|1 - G| >= 1e-150) keep 1 - N > 0.
        const double one_minus_big_n = kc2 / (1.0 - n);
        if (one_minus_big_n == 0.0) continue;
        out.push_back({c * c, c * c + kc2 * s * s, c * c + one_minus_big_n * s * s});
      }
    }
  }
  return out;
}

TEST(Carlson, RfRdRjMatchFiftyDigitBoostOverTheLibrarysRanges) {
  double worst_f = 0, worst_d = 0, worst_j = 0, worst_fj = 0;
  for (const Args& a : LibraryArgs()) {
    const Big x = a.x, y = a.y, p = a.p;
    const Big rf = boost::math::ellint_rf(x, y, Big(1)), rd = boost::math::ellint_rd(x, y, Big(1));
    const Big rj = boost::math::ellint_rj(x, y, Big(1), p);
    const plateball::internal::CarlsonFJ fj = CarlsonRFRJ(a.x, a.y, 1.0, a.p);
    worst_f = std::max(worst_f, Ulps(CarlsonRF(a.x, a.y, 1.0), rf));
    worst_d = std::max(worst_d, Ulps(CarlsonRD(a.x, a.y, 1.0), rd));
    worst_j = std::max(worst_j, Ulps(fj.rj, rj));
    worst_fj = std::max(worst_fj, Ulps(fj.rf, rf));
    // The argument orders other callers could pass (the integrals are symmetric in x, y, z).
    worst_f = std::max(worst_f, Ulps(CarlsonRF(1.0, a.x, a.y), rf));
    worst_d = std::max(worst_d, Ulps(CarlsonRD(a.y, a.x, 1.0), rd));
    worst_j = std::max(worst_j, Ulps(CarlsonRJ(1.0, a.y, a.x, a.p), rj));
  }
  EXPECT_LE(worst_f, 3.0);
  EXPECT_LE(worst_fj, 3.0);
  EXPECT_LE(worst_d, 4.0);
  EXPECT_LE(worst_j, 6.0);
  std::printf("worst relative error in eps: R_F %.2f, R_F (with R_J) %.2f, R_D %.2f, R_J %.2f\n",
              worst_f,
              worst_fj,
              worst_d,
              worst_j);
}

TEST(Carlson, GeneralArgumentsMatchFiftyDigitBoost) {
  // Scattered arguments over 1e-30..1e30 (one zero allowed), p above, between and below them
  // (e_0 >= -1/2: see CarlsonRFRJ), beyond the library's ranges.
  const std::vector<double> values = {0.0, 1e-30, 1e-8, 0.1, 0.7, 1.0, 2.5, 40.0, 1e7, 1e30};
  double worst_f = 0, worst_d = 0, worst_j = 0;
  for (double x : values) {
    for (double y : values) {
      for (double z : values) {
        if (y == 0.0 || z == 0.0) continue;  // x carries the zero
        const Big bx = x, by = y, bz = z;
        worst_f = std::max(worst_f, Ulps(CarlsonRF(x, y, z), boost::math::ellint_rf(bx, by, bz)));
        worst_d = std::max(worst_d, Ulps(CarlsonRD(x, y, z), boost::math::ellint_rd(bx, by, bz)));
        for (double p : {0.5 * (y + z), 3.0 * std::max({x, y, z}), std::max(y, z)}) {
          worst_j = std::max(worst_j, Ulps(CarlsonRJ(x, y, z, p), boost::math::ellint_rj(bx, by, bz, Big(p))));
        }
      }
    }
  }
  EXPECT_LE(worst_f, 3.0);
  EXPECT_LE(worst_d, 4.0);
  EXPECT_LE(worst_j, 6.0);
  std::printf("worst relative error in eps: R_F %.2f, R_D %.2f, R_J %.2f\n", worst_f, worst_d, worst_j);
}

TEST(Carlson, RcOnePlusMatchesFiftyDigitBoostOnBothSidesOfTheSeriesSwitch) {
  double worst = 0;
  for (double e : {-0.6, -0.1, -2.1e-3, -1.9e-3, -1e-6, 0.0, 1e-9, 1e-4, 1.99e-3, 2.01e-3, 0.3, 0.99, 50.0}) {
    worst = std::max(worst, Ulps(CarlsonRC1p(e), boost::math::ellint_rc(Big(1), Big(1) + Big(e))));
  }
  EXPECT_LE(worst, 2.0);
}

TEST(Carlson, ClosedForms) {
  const double pi = M_PI;
  for (double x : {1e-20, 0.3, 1.0, 7.0, 1e20}) {
    EXPECT_NEAR(CarlsonRF(x, x, x), 1.0 / std::sqrt(x), 2 * kEps / std::sqrt(x)) << x;              // 19.20.1
    EXPECT_NEAR(CarlsonRF(0.0, x, x), pi / (2 * std::sqrt(x)), 2 * kEps * pi / std::sqrt(x)) << x;  // 19.20.1
    EXPECT_NEAR(CarlsonRD(x, x, x), std::pow(x, -1.5), 2 * kEps * std::pow(x, -1.5)) << x;          // 19.20.18
    EXPECT_NEAR(CarlsonRD(0.0, x, x), 3 * pi / (4 * std::pow(x, 1.5)), 3 * kEps * std::pow(x, -1.5)) << x;
    EXPECT_NEAR(CarlsonRJ(x, x, x, x), std::pow(x, -1.5), 2 * kEps * std::pow(x, -1.5)) << x;  // 19.20.5
  }
  // R_J(0, y, y, p) = 3 pi / (2 (y sqrt p + p sqrt y)) (DLMF 19.20.7).
  for (double y : {1e-12, 0.5, 1.0, 30.0}) {
    for (double p : {1e-9, 0.2, 1.0, 4e3}) {
      const double expected = 3 * pi / (2 * (y * std::sqrt(p) + p * std::sqrt(y)));
      EXPECT_NEAR(CarlsonRJ(0.0, y, y, p), expected, 4 * kEps * expected) << y << " " << p;
    }
  }
  // R_F(0, 1, 2) = Gamma(1/4)^2 / (4 sqrt(2 pi)) (DLMF 19.20.2); the lemniscate constants
  // R_D(0, 2, 1) = 3 Gamma(3/4)^2 / sqrt(2 pi) and R_D(0, 1, 2) = Gamma(1/4)^2 / (4 sqrt(2 pi)) ... by
  // Legendre's relation at k = k' = 1/sqrt(2) below; R_C(1, 1 + e) = atan(sqrt e) / sqrt e.
  const double g14 = std::tgamma(0.25);
  EXPECT_NEAR(CarlsonRF(0.0, 1.0, 2.0), g14 * g14 / (4 * std::sqrt(2 * pi)), 4 * kEps);
  EXPECT_NEAR(CarlsonRC1p(1.0), pi / 4, kEps);
  EXPECT_NEAR(CarlsonRC1p(3.0), pi / (3 * std::sqrt(3.0)), kEps);
}

TEST(Carlson, CompleteKAndDSatisfyLegendresRelationAndMatchCarlson) {
  // E K' + E' K - K K' = pi / 2 (DLMF 19.7.1) with E = K - k^2 D, from the double K, D at k and at
  // k' (each passed with its complement), down to k' = 1e-12 and k = 1e-12; and K = R_F(0, k'^2, 1),
  // D = R_D(0, k'^2, 1) / 3 from the 50-digit reference.
  double worst_k = 0, worst_d = 0, worst_legendre = 0;
  for (double kc : {1e-12, 1e-9, 1e-6, 1e-3, 0.1, 0.5, M_SQRT1_2, 0.9, 0.999, 1.0 - 1e-9}) {
    const double k = std::sqrt((1.0 - kc) * (1.0 + kc));
    const auto a = CompleteEllipticKD(k, kc), b = CompleteEllipticKD(kc, k);
    const double e = a.k - k * k * a.d, ec = b.k - kc * kc * b.d;
    // Each term is accurate to a few ulps of K K' (up to ~45 at k' = 1e-12), not of pi / 2.
    worst_legendre = std::max(worst_legendre, std::abs(e * b.k + ec * a.k - a.k * b.k - M_PI / 2) / (kEps * a.k * b.k));
    // The reference at y = k'^2 of the double k' exactly; k = sqrt(1 - k'^2) rounded once.
    const Big kc2 = Big(kc) * Big(kc);
    const double k_rounded = static_cast<double>(sqrt(1 - kc2));
    const Big rf = boost::math::ellint_rf(Big(0), kc2, Big(1));
    const Big rd = boost::math::ellint_rd(Big(0), kc2, Big(1)) / 3;
    const auto exact = CompleteEllipticKD(k_rounded, kc);
    worst_k = std::max(worst_k, Ulps(exact.k, rf));
    worst_d = std::max(worst_d, Ulps(exact.d, rd));
  }
  EXPECT_LE(worst_legendre, 4.0);
  EXPECT_LE(worst_k, 3.0);
  EXPECT_LE(worst_d, 4.0);
  std::printf("worst: K %.2f eps, D %.2f eps, Legendre's relation %.2f eps K K'\n", worst_k, worst_d, worst_legendre);
  // k = 0: K = pi/2, D = pi/4; k = k' = 1/sqrt(2): K = Gamma(1/4)^2 / (4 sqrt pi) (DLMF 19.6.1, 19.20.2).
  const auto zero = CompleteEllipticKD(0.0, 1.0);
  EXPECT_DOUBLE_EQ(zero.k, M_PI / 2);
  EXPECT_DOUBLE_EQ(zero.d, M_PI / 4);
  const double g14 = std::tgamma(0.25);
  EXPECT_NEAR(CompleteEllipticKD(M_SQRT1_2, M_SQRT1_2).k, g14 * g14 / (4 * std::sqrt(M_PI)), 4 * kEps);
  // The separatrix k' = 0: both infinite (not a finite value from a truncated AGM).
  EXPECT_EQ(CompleteEllipticKD(1.0, 0.0).k, HUGE_VAL);
  EXPECT_EQ(CompleteEllipticKD(1.0, 0.0).d, HUGE_VAL);
}

}  // namespace
