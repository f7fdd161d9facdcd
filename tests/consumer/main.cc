// Uses the installed library through its public headers only (no Ceres, NLopt or nlohmann-json
// needed by the consumer): free motion and the problem-file reader.
#include <cmath>
#include <cstdio>

#include "plateball/free_motion.h"
#include "plateball/problem_io.h"

int main() {
  const plateball::Problem p = plateball::ParseProblem(
      R"({"ball": {"lambda": 2}, "initial": {"theta": 1.0471975511965976, "phi": 0.4, "psi": 0.1, "mu": 4}})",
      "consumer.json");
  const plateball::FreeMotion motion =
      plateball::FreeMotion::FromAngles(p.model, p.initial_angles, p.mu, p.x0, p.A0, p.integration);
  // T = 2 pi / sqrt(mu) = pi for mu = 4.
  std::printf("plateball %s consumer: period %.15f energy %.12f\n", PLATEBALL_VERSION_STRING, motion.Period(),
              motion.At(2.5).energy);
  return std::abs(motion.Period() - M_PI) < 1e-12 ? 0 : 1;
}
