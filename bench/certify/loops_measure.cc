// Not a timing benchmark: the cost of the loop-by-loop certificate of the fast separatrix tail
// (CertifyLoopFamily, src/certify/loops.h) on an isoparallel problem file
// (docs/paper_notes.md, "General targets: the separatrix tail loop by loop"). Run with `nice -n 10`.
//
//   loops_measure [FILE [CAP_FACTOR [KP_T [RATE_LO [RATE_MAX [BUDGET [REGIME [W2]]]]]]]]
//
// Defaults: problems/isoparallel_rotation.json, cap 1.0 x the solver's shortest length x 1.0001,
// k'_t = 1e-4 (k_t = sqrt(1 - k'_t^2)), rates [0.5, 30], budget 2,000,000 boxes, both regimes
// (REGIME: oscillating, rotating, both), W2 = 0 (LoopCoreHalfWidthFor). Prints the family's
// heading error, window, box counts, CPU seconds and the undecided boxes.
#include <chrono>
#include <cmath>
#include <cstdio>
#include <ctime>
#include <stdexcept>
#include <string>

#include "certify/loops.h"
#include "certify/tails.h"
#include "jacobi_elliptic.h"
#include "plateball/isoparallel.h"
#include "plateball/problem_io.h"
#include "plateball/task_adapters.h"
#include "positional_argument.h"

namespace {

using namespace plateball;
using namespace plateball::internal;

using bench::PositionalNumber;

void Print(PendulumRegime regime, const LoopFamilyOptions& o, const LoopFamilyResult& r, double cpu) {
  const CertifyBox& w = r.window;
  std::printf("%s: k_t %.12g (K_t %.6g), W2 %.6g, eps L_max %.3g (heading error %.3g)\n",
              ToString(regime).c_str(),
              o.k_t,
              CompleteEllipticK(o.k_t),
              r.core_half_width,
              r.heading_error * o.cap,
              r.heading_error);
  std::printf("  window rate [%g, %g] run [%g, %g] phase [%g, %g] L [%g, %g], both senses\n",
              w.lo[0],
              w.hi[0],
              w.lo[1],
              w.hi[1],
              w.lo[2],
              w.hi[2],
              w.lo[3],
              w.hi[3]);
  std::printf(
      "  %s; boxes %ld (chord %ld, rotation %ld, outside the domain %ld), undecided %ld, resolved volume %.6f; %.1f s "
      "CPU\n",
      ToString(r.status).c_str(),
      r.boxes,
      r.excluded_by_chord,
      r.excluded_by_rotation,
      r.outside_domain,
      r.undecided,
      r.resolved_volume,
      cpu);
  for (std::size_t i = 0; i < r.undecided_boxes.size(); ++i) {
    const CertifyPoint c = r.undecided_boxes[i].Centre();
    std::printf(
        "  undecided sense %+d centre {%.9g, %.9g, %.9g, %.9g}\n", r.undecided_senses[i], c[0], c[1], c[2], c[3]);
  }
}

int Run(int argc, char** argv) {
  const std::string file = argc > 1 ? argv[1] : "problems/isoparallel_rotation.json";
  const IsoparallelSetup setup = IsoparallelSetupFor(ReadProblemFile(file));
  const IsoparallelSummary solved = SolveIsoparallel(setup.problem, setup.options);
  if (!solved.IsSolutionUsable()) throw std::runtime_error("the solver found no solution: " + solved.message);
  const CertifyTarget target = CertifyTargetOf(setup.problem);
  LoopFamilyOptions o;
  o.cap = PositionalNumber(argc, argv, 2, 1.0, 10.0, 1.0) * solved.Shortest().length * 1.0001;
  const double kp = PositionalNumber(argc, argv, 3, 1e-8, 0.4, 1e-4);
  o.k_t = std::sqrt((1.0 - kp) * (1.0 + kp));
  o.rate_lo = PositionalNumber(argc, argv, 4, 1e-3, 1e3, 0.5);
  o.rate_max = PositionalNumber(argc, argv, 5, 1e-3, 1e3, 30.0);
  o.max_boxes = static_cast<long>(PositionalNumber(argc, argv, 6, 1.0, 1e10, 2e6));
  const std::string which = argc > 7 ? argv[7] : "both";
  o.core_half_width = PositionalNumber(argc, argv, 8, 0.0, 1e3, 0.0);
  o.length_lo = target.radius;
  std::printf(
      "%s: cap %.9g, |x1 - x0| %.9g, delta0 %.9g\n", file.c_str(), o.cap, target.radius, StraightResidual(target));
  for (PendulumRegime regime : {PendulumRegime::kOscillating, PendulumRegime::kRotating}) {
    if (which != "both" && which != ToString(regime)) continue;
    o.regime = regime;
    const std::clock_t cpu_start = std::clock();
    const LoopFamilyResult r = CertifyLoopFamily(target, o);
    if (r.status == LoopFamilyStatus::kInvalidInput) throw std::invalid_argument(r.message);
    Print(regime, o, r, static_cast<double>(std::clock() - cpu_start) / CLOCKS_PER_SEC);
  }
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  std::setvbuf(stdout, nullptr, _IOLBF, 0);  // a run cut by `timeout` keeps its finished lines
  try {
    return Run(argc, argv);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "loops_measure: %s\n", e.what());
    return 2;
  }
}
