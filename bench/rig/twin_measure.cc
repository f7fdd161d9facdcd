// Not a timing benchmark: the agreement tables of docs/mujoco_twin.md. Prints, as Markdown, how far
// the MuJoCo twin ends from the library for the free motion of a physical problem over two periods
// (against the timestep, the contact impedance and the paper's lambda) and for a plan result (ideal
// jumps against the timestep, centred pulses against their duration).
//   twin_measure problems/physical_units.json PLAN_RESULT.json
#include <cstdio>
#include <exception>
#include <string>

#include "plateball/free_motion.h"
#include "plateball/problem_io.h"
#include "rig/mujoco_twin.h"

namespace {

using namespace plateball;
using namespace plateball::tools::rig;

RigPlan FreeRigPlan(const Problem& p, const BallModel& model) {
  RigPlan plan;
  plan.physical = *p.physical;
  plan.model = model;
  plan.integration = p.integration;
  const FreeMotion fm = FreeMotion::FromAngles(model, p.initial, p.mu, p.x0, p.A0, p.integration);
  plan.start = fm.start().state;
  plan.x0 = fm.start().x0;
  plan.A0 = fm.start().A0;
  plan.t_end = 2 * fm.Period();
  return plan;
}

void Row(const std::string& label, const RigPlan& plan, const ReplayOptions& o) {
  const ReplayReport r = ReplayInTwin(plan, PlannedTrajectory(plan), o);
  std::printf("| %s | %d | %.2e | %.2e | %.2e | %.2e | %.2e |\n",
              label.c_str(),
              r.steps,
              r.position_error,
              r.orientation_error,
              r.energy_error,
              r.max_slip_speed,
              r.max_spin_rate);
}

void Header(const char* first) {
  std::printf(
      "\n| %s | steps | position (r) | orientation (rad) | energy (rel.) | max slip (m/s) | max spin (rad/s) |\n"
      "|---|---|---|---|---|---|---|\n",
      first);
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 3) {
    std::fprintf(stderr, "usage: twin_measure PHYSICAL_PROBLEM.json PLAN_RESULT.json\n");
    return 2;
  }
  try {
    const Problem p = ReadProblemFile(argv[1]);
    const PhysicalParameters& ph = *p.physical;
    const BallModel paper = BallModel::FromAlphaBeta(
        ph.inertia_3 / ph.inertia_1, (ph.ball_mass + 2 * ph.plate_mass) * ph.radius * ph.radius / ph.inertia_1);
    std::printf("Free motion of %s over two periods (lambda %.9f; the paper's %.9f)\n",
                argv[1],
                p.model.lambda(),
                paper.lambda());
    Header("dt (s), lambda");
    for (const double dt : {2e-3, 1e-3, 5e-4, 2e-4, 1e-4}) {
      ReplayOptions o;
      o.settings.timestep = dt;
      char label[64];
      std::snprintf(label, sizeof(label), "%.0e, corrected", dt);
      Row(label, FreeRigPlan(p, p.model), o);
      if (dt == 1e-3 || dt == 1e-4) {
        std::snprintf(label, sizeof(label), "%.0e, paper's", dt);
        Row(label, FreeRigPlan(p, paper), o);
      }
    }
    Header("impedance (dt 1e-3)");
    for (const double d : {0.9, 0.95, 0.99, 0.999, 0.9999}) {
      ReplayOptions o;
      o.settings.impedance = d;
      Row(std::to_string(d).substr(0, 6), FreeRigPlan(p, p.model), o);
    }
    const RigPlan plan = ReadRigPlan(argv[2]);
    std::printf("\nPlan %s (%zu impulses, %.3f s), ideal velocity jumps\n", argv[2], plan.impulses.size(), plan.t_end);
    Header("dt (s)");
    for (const double dt : {2e-3, 1e-3, 5e-4, 1e-4}) {
      ReplayOptions o;
      o.settings.timestep = dt;
      char label[32];
      std::snprintf(label, sizeof(label), "%.0e", dt);
      Row(label, plan, o);
    }
    std::printf("\nThe same plan, centred pulses of duration D (force J/D on the plate), dt 1e-3\n");
    Header("D (s)");
    for (const double D : {1e-3, 2e-3, 5e-3, 1e-2, 2e-2, 5e-2, 1e-1}) {
      ReplayOptions o;
      o.pulse_duration = D;
      char label[32];
      std::snprintf(label, sizeof(label), "%.0e", D);
      Row(label, plan, o);
    }
  } catch (const std::exception& e) {
    std::fprintf(stderr, "twin_measure: %s\n", e.what());
    return 1;
  }
  return 0;
}
