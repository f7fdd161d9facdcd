// What a certified branch and bound over the shape parameters costs (docs/paper_notes.md,
// "General targets: certified exclusion over parameter boxes"). Not a timing benchmark: it solves
// an isoparallel problem file with the default solver, then runs CertifyWindow over the window
//   rate [0, rate_max] (oscillating) or [-rate_max, rate_max] (rotating), k [0, k_max],
//   phase [0, one period of the Jacobi argument at k_max), length [|x1 - x0|, cap x shortest]
// for each cap factor and regime, and prints the solver's solutions (canonical form), the box
// counts and the verdicts.
//
//   certify_measure [PROBLEM.json] [--caps 1.0,1.2,1.5] [--regime oscillating|rotating|both]
//                   [--budget BOXES] [--k-min K] [--k-max K] [--rate-min R] [--rate-max A]
//                   [--log-modulus-split K] [--first-order 0|1] [--known 0|1]
//                   [--first-order-deviation D] [--costate 0|1] [--closed-rolling 0|1]
//                   [--chart-rolling 0|1] [--centred-rolling 0|1] [--centred-phase 0|1] [--fixed-periods 0|1]
//                   [--trace FILE]
//
// --first-order 1 adds the first-order tests (mean-value exclusion, Krawczyk) and prints the
// solutions they prove unique, each with the solver's solution it matches (or "new");
// --trace FILE writes one line per box split (left undecided): centre (4), half-widths (4), D,
// the per-axis shares of D (4), the per-axis Krawczyk contraction columns (4, zero without the
// first-order tests) and the split axis (diagnostics of where a window stalls);
// --costate 0 turns off the costate test (certify/costate.h; on by default);
// --closed-rolling 0 turns off the closed-form rolling bound of the rotation test
// (certify/rolling.h; on by default); --chart-rolling 0 the theta/2 chart's bound
// (same header, smooth through G = 1; on by default); --centred-rolling 0 the centred form's bound
// (certify/centred.h: vertex rollings plus a second-order remainder; on by default); the phase window is [-P/2, P/2] (P
// the period at k_max: |u0| and so the secular terms of the bounds halved), --centred-phase 0 takes [0, P] instead (the
// same paths; the figures of rounds before the tenth);
// --fixed-periods 0 turns off the bounds compared at a fixed number of periods and the split
// along their shares (certify/periods.h; on by default: the trace's shares are then
// those of the fixed-periods bound where it is below D);
// --known 0 runs without the solver's solutions (then only the first-order tests can finish);
// --k-min K starts the modulus range at K (default 0; k-max up to 1 - 1e-9); --rate-min R > 0
// keeps |rate| >= R: the oscillating window's rate is [R, A], the rotating one is run as two
// windows, [-A, -R] and [R, A]; --log-modulus-split K splits boxes with k_lo >= K in lambda =
// -ln k' (CertifyWindowOptions::log_modulus_split; default 1, never). Each regime and cap first
// prints MaxSolutionRateOver the k range (certify/tails.h: the rate a window needs).
//
// Default: problems/isoparallel_rotation.json (relative to the working directory), caps 1.0, 1.2,
// 1.5, both regimes, 2,000,000 boxes, k_max 0.95, rate_max 2.

#include <array>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "certify/tails.h"
#include "certify/window.h"
#include "plateball/problem_io.h"
#include "plateball/task_adapters.h"
#include "positional_argument.h"

namespace {

using namespace plateball;
using namespace plateball::internal;

struct Settings {
  std::string file = "problems/isoparallel_rotation.json";
  std::vector<double> caps = {1.0, 1.2, 1.5};
  std::vector<PendulumRegime> regimes = {PendulumRegime::kOscillating, PendulumRegime::kRotating};
  long budget = 2000000;
  double k_min = 0.0, k_max = 0.95, rate_min = 0.0, rate_max = 2.0, log_modulus_split = 1.0;
  bool first_order = false, known = true, costate = true, closed_rolling = true, chart_rolling = true;
  bool centred_phase = true, centred_rolling = true, fixed_periods = true;
  double first_order_deviation = 0.5;
  std::string trace;  // file of split boxes, or empty
};

using bench::ParseNumber;

std::vector<PendulumRegime> Regimes(const std::string& text) {
  if (text == "oscillating") return {PendulumRegime::kOscillating};
  if (text == "rotating") return {PendulumRegime::kRotating};
  if (text == "both") return {PendulumRegime::kOscillating, PendulumRegime::kRotating};
  throw std::invalid_argument("--regime: value " + text + ": expected oscillating, rotating or both");
}

Settings Parse(int argc, char** argv) {
  Settings s;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a.rfind("--", 0) != 0) {
      s.file = a;
      continue;
    }
    if (i + 1 >= argc) throw std::invalid_argument(a + ": a value is missing");
    const std::string v = argv[++i];
    if (a == "--caps") {
      s.caps.clear();
      std::stringstream list(v);
      for (std::string item; std::getline(list, item, ',');) s.caps.push_back(ParseNumber(a, item, 1.0, 10.0));
    } else if (a == "--regime") {
      s.regimes = Regimes(v);
    } else if (a == "--budget") {
      s.budget = static_cast<long>(ParseNumber(a, v, 1.0, 1e10));
    } else if (a == "--k-min") {
      s.k_min = ParseNumber(a, v, 0.0, kMaxWindowModulus);
    } else if (a == "--k-max") {
      s.k_max = ParseNumber(a, v, 0.0, kMaxWindowModulus);
    } else if (a == "--rate-min") {
      s.rate_min = ParseNumber(a, v, 0.0, 1e3);
    } else if (a == "--log-modulus-split") {
      s.log_modulus_split = ParseNumber(a, v, 0.0, 1.0);
    } else if (a == "--rate-max") {
      s.rate_max = ParseNumber(a, v, 1e-6, 1e3);
    } else if (a == "--first-order") {
      s.first_order = ParseNumber(a, v, 0.0, 1.0) != 0.0;
    } else if (a == "--first-order-deviation") {
      s.first_order_deviation = ParseNumber(a, v, 0.0, 10.0);
    } else if (a == "--trace") {
      s.trace = v;
    } else if (a == "--costate") {
      s.costate = ParseNumber(a, v, 0.0, 1.0) != 0.0;
    } else if (a == "--closed-rolling") {
      s.closed_rolling = ParseNumber(a, v, 0.0, 1.0) != 0.0;
    } else if (a == "--chart-rolling") {
      s.chart_rolling = ParseNumber(a, v, 0.0, 1.0) != 0.0;
    } else if (a == "--centred-rolling") {
      s.centred_rolling = ParseNumber(a, v, 0.0, 1.0) != 0.0;
    } else if (a == "--centred-phase") {
      s.centred_phase = ParseNumber(a, v, 0.0, 1.0) != 0.0;
    } else if (a == "--fixed-periods") {
      s.fixed_periods = ParseNumber(a, v, 0.0, 1.0) != 0.0;
    } else if (a == "--known") {
      s.known = ParseNumber(a, v, 0.0, 1.0) != 0.0;
    } else {
      throw std::invalid_argument(a + ": unknown option");
    }
  }
  if (!(s.k_min <= s.k_max))
    throw std::invalid_argument("--k-min: value " + std::to_string(s.k_min) + ": above --k-max");
  if (!(s.rate_min < s.rate_max))
    throw std::invalid_argument("--rate-min: value " + std::to_string(s.rate_min) + ": not below --rate-max");
  return s;
}

// The rate ranges of a regime's windows: [rate_min, A] oscillating; rotating [-A, A], or with
// rate_min > 0 the two windows [-A, -rate_min] and [rate_min, A].
std::vector<std::array<double, 2>> RateRanges(const Settings& s, PendulumRegime regime) {
  if (regime == PendulumRegime::kOscillating) return {{s.rate_min, s.rate_max}};
  if (s.rate_min == 0.0) return {{-s.rate_max, s.rate_max}};
  return {{-s.rate_max, -s.rate_min}, {s.rate_min, s.rate_max}};
}

CertifyWindowOptions WindowFor(
    const Settings& s, PendulumRegime regime, const std::array<double, 2>& rates, double radius, double cap) {
  CertifyWindowOptions o;
  o.regime = regime;
  o.max_boxes = s.budget;
  o.stop_at_unaccounted = false;
  o.first_order = s.first_order;
  o.costate = s.costate;
  o.closed_rolling = s.closed_rolling;
  o.chart_rolling = s.chart_rolling;
  o.centred_rolling = s.centred_rolling;
  o.fixed_periods = s.fixed_periods;
  o.log_modulus_split = s.log_modulus_split;
  o.first_order_deviation = s.first_order_deviation;
  // One period of the phase at k_max (>= the period at every smaller k): [-P/2, P/2], or [0, P]
  // with --centred-phase 0 (the same paths; centred, |u0| and so the secular terms are halved).
  const double period = PhasePeriod(regime, s.k_max), phase_lo = s.centred_phase ? -0.5 * period : 0.0;
  o.window.lo = {rates[0], s.k_min, phase_lo, radius};
  // With the first-order tests the length reaches 1e-4 past the cap: a solution exactly at the
  // cap (the shortest at 1.0x) would lie on the window's face, where Krawczyk cannot prove it.
  const double length_hi = s.first_order ? cap * (1.0 + 1e-4) : cap;
  o.window.hi = {rates[1], s.k_max, phase_lo + period, length_hi};
  return o;
}

void WriteTrace(std::FILE* f, const CertifyBoxTrace& t) {
  const CertifyPoint c = t.box.Centre();
  for (int i = 0; i < 4; ++i) std::fprintf(f, "%.10g ", c[i]);
  for (int i = 0; i < 4; ++i) std::fprintf(f, "%.4g ", t.box.HalfWidth(i));
  std::fprintf(f, "%.4g", t.deviation);
  for (double x : t.share) std::fprintf(f, " %.4g", x);
  for (double x : t.contraction) std::fprintf(f, " %.4g", x);
  std::fprintf(f, " %d\n", t.split_axis);
}

int Run(const Settings& s) {
  const IsoparallelSetup setup = IsoparallelSetupFor(ReadProblemFile(s.file));
  const IsoparallelSummary solved = SolveIsoparallel(setup.problem, setup.options);
  if (!solved.IsSolutionUsable()) {
    std::fprintf(stderr, "certify_measure: the solver found no solution: %s\n", solved.message.c_str());
    return 1;
  }
  const CertifyTarget target = CertifyTargetOf(setup.problem);
  const double shortest = solved.Shortest().length;
  for (PendulumRegime regime : s.regimes) {
    std::vector<CertifyPoint> known;
    for (const IsoparallelSolution& sol : solved.solutions) {
      if (sol.parameters.regime != regime) continue;
      known.push_back(CanonicalSolution(sol.parameters, sol.length));
      const CertifyPoint& c = known.back();
      std::printf("%s solution {%.17g, %.17g, %.17g, %.17g}\n", ToString(regime).c_str(), c[0], c[1], c[2], c[3]);
    }
    if (!s.known) known.clear();
    for (double factor : s.caps)
      std::printf("%s, cap %.2fx: MaxSolutionRateOver k [%.10g, %.10g] = %.6g (the rate beyond which no solution)\n",
                  ToString(regime).c_str(),
                  factor,
                  s.k_min,
                  s.k_max,
                  MaxSolutionRateOver(target, regime, s.k_min, s.k_max, factor * shortest, 1e-7));
    for (double factor : s.caps)
      for (const std::array<double, 2>& rates : RateRanges(s, regime)) {
        CertifyWindowOptions options = WindowFor(s, regime, rates, target.radius, factor * shortest);
        std::FILE* trace = s.trace.empty() ? nullptr : std::fopen(s.trace.c_str(), "w");
        if (!s.trace.empty() && !trace) throw std::invalid_argument("--trace: value " + s.trace + ": cannot write");
        if (trace) options.trace = [trace](const CertifyBoxTrace& t) { WriteTrace(trace, t); };
        const auto start = std::chrono::steady_clock::now();
        const std::clock_t cpu_start = std::clock();
        const CertifyWindowResult w = CertifyWindow(target, known, options);
        if (trace) std::fclose(trace);
        const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        const double cpu = static_cast<double>(std::clock() - cpu_start) / CLOCKS_PER_SEC;
        std::printf("cap %.2fx %s, rate [%g, %g], k [%.10g, %.10g]: %s; resolved volume %.6f; %.1f s (%.1f s CPU)\n",
                    factor,
                    ToString(regime).c_str(),
                    rates[0],
                    rates[1],
                    s.k_min,
                    s.k_max,
                    w.message.c_str(),
                    w.resolved_volume,
                    seconds,
                    cpu);
        std::printf(
            "  excluded by rotation %ld (%ld only with the closed-form rolling bound, %ld then only with the "
            "theta/2 chart's, %ld then only with the centred form)\n",
            w.excluded_by_rotation,
            w.excluded_by_closed_rolling,
            w.excluded_by_chart_rolling,
            w.excluded_by_centred_rolling);
        std::printf("  excluded only with the fixed-periods bounds %ld\n", w.excluded_by_fixed_periods);
        for (size_t i = 0; i < w.found.size(); ++i) {
          const CertifyPoint& f = w.found[i];
          const std::string match =
              w.found_known[i] >= 0 ? "solver's solution " + std::to_string(w.found_known[i]) : "new";
          std::printf("  proved unique {%.12g, %.12g, %.12g, %.12g}: %s\n", f[0], f[1], f[2], f[3], match.c_str());
        }
      }
  }
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  try {
    return Run(Parse(argc, argv));
  } catch (const std::exception& e) {
    std::fprintf(stderr, "certify_measure: %s\n", e.what());
    return 2;
  }
}
