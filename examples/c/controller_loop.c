/* plateball from C (plateball_c.h): load a problem, plan it, steer exactly between two states, and
 * run the controller tick by tick. This dry run has no rig: it "measures" the contact point only,
 * as the controller's estimate moved on by one tick at the contact velocity x' = (omega_2, -omega_1)
 * (a rig gives its camera's measurement instead), so the controller dead-reckons the rest and
 * follows the plan to the end.
 *
 *   controller_loop problems/circle.json
 */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "plateball/plateball_c.h"

static int check(pb_status status, const char* what) {
  if (status != PB_OK) fprintf(stderr, "%s: status %d: %s\n", what, (int)status, pb_last_error());
  return status == PB_OK;
}

int main(int argc, char** argv) {
  pb_problem* problem = NULL;
  pb_plan* plan = NULL;
  pb_controller* controller = NULL;
  pb_controller_options options;
  pb_measurement measurement;
  pb_command command;
  pb_ball_state start;
  pb_impulse steer[4];
  const double identity[9] = {1, 0, 0, 0, 1, 0, 0, 0, 1};
  const double goal_x[2] = {1.0, 0.5};
  long tick, impulses = 0;
  int code = 1, k;

  if (argc != 2) {
    fprintf(stderr, "usage: controller_loop PROBLEM.json\n");
    return 2;
  }
  if (!check(pb_problem_load(argv[1], &problem), "load")) return 5;
  if (!check(pb_plan_create(problem, 32, &plan), "plan")) goto done;
  printf("plan: %d impulses, total time %.6f\n", pb_plan_impulse_count(plan), pb_plan_total_time(plan));

  /* Four impulses from (pi/3, 0.4, 0.1) at the origin to (1, 0.5) with the orientation I. */
  memset(&start, 0, sizeof start);
  start.theta = M_PI / 3;
  start.phi = 0.4;
  start.psi = 0.1;
  start.mu = 1.0;
  memcpy(start.A, identity, sizeof identity);
  if (!check(pb_steer(2.0, &start, goal_x, identity, 4, steer, 4), "steer")) goto done;
  for (k = 0; k < 4; ++k)
    printf("steer impulse %d: t %.6f, delta psi %.6f, flight %.6f\n",
           k,
           steer[k].t_impulse,
           steer[k].delta_psi,
           steer[k].duration);

  pb_controller_options_default(&options);
  options.tick_period = 1e-3;
  if (!check(pb_controller_create(plan, &options, &controller), "controller")) goto done;
  memset(&measurement, 0, sizeof measurement);
  measurement.has_orientation = 0;
  for (tick = 0; tick < 100000; ++tick) {
    check(pb_controller_update(controller, tick * options.tick_period, &measurement, &command), "update");
    if (command.impulse) ++impulses;
    if (command.status != PB_CONTROLLER_OK) break;
    /* The next tick's "measurement": one Euler step of the contact point (error ~ dt^2). */
    measurement.x[0] = command.x_now[0] + options.tick_period * command.omega_now[1];
    measurement.x[1] = command.x_now[1] - options.tick_period * command.omega_now[0];
  }
  printf("controller: %ld impulses, status %d after %ld ticks\n", impulses, (int)command.status, tick + 1);
  code = command.status == PB_CONTROLLER_DONE ? 0 : 4;
done:
  pb_controller_destroy(controller);
  pb_plan_destroy(plan);
  pb_problem_destroy(problem);
  return code;
}
