// Not a timing benchmark: the cost of the separatrix-tail certificate (CertifySeparatrixTail,
// src/certify/separatrix.h) on an isoparallel problem file
// (docs/paper_notes.md, "General targets: the separatrix tail"). Run with `nice -n 10`.
//
//   separatrix_measure [FILE [CAP_FACTOR [RATE_MAX [K_LO [BUDGET [REGIME]]]]]]
//
// Defaults: problems/isoparallel_rotation.json, cap 1.0 x the solver's shortest length,
// rate_max 0.5, k_lo 0.95, budget 2,000,000 boxes, both regimes (REGIME: oscillating, rotating,
// both). Prints W (the run distance), the near-loop window, the box counts and the undecided boxes.
#include <boost/math/special_functions/ellint_1.hpp>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <stdexcept>
#include <string>
#include <vector>

#include "certify/separatrix.h"
#include "certify/tails.h"
#include "plateball/isoparallel.h"
#include "plateball/problem_io.h"
#include "plateball/task_adapters.h"
#include "positional_argument.h"

namespace {

using namespace plateball;
using namespace plateball::internal;

using bench::PositionalNumber;

void Print(PendulumRegime regime, const SeparatrixTailResult& r, double seconds) {
  const CertifyBox& w = r.window;
  std::printf("%s: W %.6g; window rate [%g, %g] k [%g, 1] phase [%g, %g] L [%g, %g]\n",
              ToString(regime).c_str(),
              r.run_distance,
              w.lo[0],
              w.hi[0],
              w.lo[1],
              w.lo[2],
              w.hi[2],
              w.lo[3],
              w.hi[3]);
  std::printf("  %s; boxes %ld (chord %ld, rotation %ld), undecided %ld, resolved volume %.6f; %.1f s\n",
              ToString(r.status).c_str(),
              r.boxes,
              r.excluded_by_chord,
              r.excluded_by_rotation,
              r.undecided,
              r.resolved_volume,
              seconds);
  for (const CertifyBox& b : r.undecided_boxes) {
    const CertifyPoint c = b.Centre();
    std::printf("  undecided centre {%.9g, %.9g, %.9g, %.9g}\n", c[0], c[1], c[2], c[3]);
  }
}

int Run(int argc, char** argv) {
  const std::string file = argc > 1 ? argv[1] : "problems/isoparallel_rotation.json";
  const IsoparallelSetup setup = IsoparallelSetupFor(ReadProblemFile(file));
  const IsoparallelSummary solved = SolveIsoparallel(setup.problem, setup.options);
  if (!solved.IsSolutionUsable()) throw std::runtime_error("the solver found no solution: " + solved.message);
  const CertifyTarget target = CertifyTargetOf(setup.problem);
  SeparatrixTailOptions o;
  o.cap = PositionalNumber(argc, argv, 2, 1.0, 10.0, 1.0) * solved.Shortest().length;
  o.rate_max = PositionalNumber(argc, argv, 3, 1e-6, 1e3, 0.5);
  o.k_lo = PositionalNumber(argc, argv, 4, 0.5, 0.999999, 0.95);
  o.max_boxes = static_cast<long>(PositionalNumber(argc, argv, 5, 1.0, 1e10, 2e6));
  o.length_lo = target.radius;
  const std::string which = argc > 6 ? argv[6] : "both";
  std::printf(
      "%s: cap %.9g, |x1 - x0| %.9g, delta0 %.9g\n", file.c_str(), o.cap, target.radius, StraightResidual(target));
  for (const IsoparallelSolution& sol : solved.solutions) {
    const CertifyPoint c = CanonicalSolution(sol.parameters, sol.length);
    if (c[kCertifyModulus] < o.k_lo || sol.length > o.cap) continue;
    // The phase from the nearest loop centre (rotating: period 2K; oscillating: loops at 0, 2K).
    const double half = 2.0 * boost::math::ellint_1(c[kCertifyModulus]);
    const double from_loop = c[kCertifyPhase] - half * std::round(c[kCertifyPhase] / half);
    std::printf("tail solution (%s) {rate %.9g, k %.9g, phase %.9g (%.9g from a loop), L %.9g}\n",
                ToString(sol.parameters.regime).c_str(),
                c[0],
                c[1],
                c[2],
                from_loop,
                c[3]);
  }
  for (PendulumRegime regime : {PendulumRegime::kOscillating, PendulumRegime::kRotating}) {
    if (which != "both" && which != ToString(regime)) continue;
    o.regime = regime;
    const auto start = std::chrono::steady_clock::now();
    const SeparatrixTailResult r = CertifySeparatrixTail(target, o);
    Print(regime, r, std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
  }
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  std::setvbuf(stdout, nullptr, _IOLBF, 0);  // a run cut by `timeout` keeps its finished lines
  try {
    return Run(argc, argv);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "separatrix_measure: %s\n", e.what());
    return 2;
  }
}
