/* plateball's stable C API: load a problem file, plan the impulses along its path, steer exactly
 * between two states, and run the real-time controller (controller.h) from C, Rust, Julia, MATLAB
 * MEX files or a ros2_control hardware interface. Objects are opaque handles created and destroyed
 * by the functions below; every function returns a pb_status (no C++ exception crosses this
 * interface) and, when it is not PB_OK, pb_last_error() gives the message of this thread's last
 * failure ("FIELD: value V: what is wrong" for invalid input). Units are the library's normalised
 * ones (docs/units.md): lengths in ball radii, time in seconds. Matrices are 3x3 row-major. */
#ifndef PLATEBALL_PLATEBALL_C_H
#define PLATEBALL_PLATEBALL_C_H

#if defined(__GNUC__) || defined(__clang__)
#define PB_API __attribute__((visibility("default")))
#else
#define PB_API
#endif

#ifdef __cplusplus
extern "C" {
#endif

/** Status codes: the command-line tools' exit codes for the same failures. */
typedef enum pb_status {
  PB_OK = 0,
  PB_INVALID_INPUT = 3, /**< an argument or the problem file is invalid (the message names the field) */
  PB_NO_SOLUTION = 4,   /**< the plan or the steer found no solution (the message says why) */
  PB_IO_ERROR = 5,      /**< a file could not be read */
  PB_INTERNAL_ERROR = 6 /**< anything else (out of memory, a bug) */
} pb_status;

/** The message of this thread's last failed call ("" when none); valid until the next call. */
PB_API const char* pb_last_error(void);

/* ------------------------------------------------------------------ problems */
typedef struct pb_problem pb_problem;
/** Reads a problem file (the JSON of schemas/input). */
PB_API pb_status pb_problem_load(const char* path, pb_problem** out);
/** Frees a problem (null: nothing). */
PB_API void pb_problem_destroy(pb_problem* problem);

/* ------------------------------------------------------------------ plans */
/** One impulse: at t_impulse the ball's angular velocity jumps by delta_omega (psi -> psi + delta_psi),
 * then it rolls freely for `duration` from `position`. */
typedef struct pb_impulse {
  double t_impulse;
  double duration;
  double delta_psi;
  double delta_omega[3];
  double position[2];
} pb_impulse;

typedef struct pb_plan pb_plan;
/** Plans the problem's `plan` section with n impulses (n = 0: the file's partition). */
PB_API pb_status pb_plan_create(const pb_problem* problem, int n, pb_plan** out);
/** Frees a plan (null: nothing); controllers made from it keep working. */
PB_API void pb_plan_destroy(pb_plan* plan);
/** The plan's impulses n (0 for null). */
PB_API int pb_plan_impulse_count(const pb_plan* plan);
/** The plan's duration from the first impulse to the arrival (0 for null). */
PB_API double pb_plan_total_time(const pb_plan* plan);
/** Impulse k, 0 <= k < pb_plan_impulse_count. */
PB_API pb_status pb_plan_impulse(const pb_plan* plan, int k, pb_impulse* out);

/* ------------------------------------------------------------------ exact steer */
/** A ball state: contact point, angles (theta, phi, psi), energy mu > 0 and orientation A (R_WB). */
typedef struct pb_ball_state {
  double x[2];
  double theta, phi, psi;
  double mu;
  double A[9];
} pb_ball_state;

/** The `impulses` (>= 3) energy-preserving impulses that take a ball of the given lambda from
 * `start` to the contact point goal_x with orientation goal_A exactly (exact_arrival.h, along the
 * segment start.x -> goal_x as reference). Writes min(impulses, capacity) impulses to `out`.
 * PB_NO_SOLUTION when the solver does not arrive. */
PB_API pb_status pb_steer(double lambda,
                          const pb_ball_state* start,
                          const double goal_x[2],
                          const double goal_A[9],
                          int impulses,
                          pb_impulse* out,
                          int capacity);

/* ------------------------------------------------------------------ controller */
typedef enum pb_strategy { PB_FEEDBACK = 0, PB_FEEDBACK_EXACT = 1 } pb_strategy;

typedef struct pb_controller_options {
  double tick_period; /**< the loop's tick (s) */
  pb_strategy strategy;
  double time_budget;                /**< wall-clock seconds per update */
  double jump_tolerance;             /**< radii */
  double orientation_jump_tolerance; /**< rad */
  double rotation_tolerance;
  int exact_window;  /**< feedback_exact: exact re-plans while 3..exact_window impulses remain */
  int plate_impulse; /**< 1: report J (the problem file must give physical parameters) */
} pb_controller_options;
/** The defaults of ControllerOptions. */
PB_API void pb_controller_options_default(pb_controller_options* options);

typedef enum pb_controller_status {
  PB_CONTROLLER_NOT_RUN = 0,
  PB_CONTROLLER_OK = 1,
  PB_CONTROLLER_MEASUREMENT_REJECTED = 2,
  PB_CONTROLLER_TIME_OUT_OF_ORDER = 3,
  PB_CONTROLLER_DONE = 4,
  PB_CONTROLLER_LOST = 5,
  PB_CONTROLLER_INTEGRATION_FAILURE = 6
} pb_controller_status;

typedef struct pb_measurement {
  double x[2];         /**< contact point (required) */
  int has_orientation; /**< 1: A and omega are given */
  double A[9];
  double omega[3];
} pb_measurement;

typedef struct pb_command {
  pb_controller_status status;
  const char* reason; /**< static text: why a measurement was rejected or the tick failed */
  long tick;
  int impulse; /**< 1: an impulse is due at `tick` */
  int impulse_index;
  double delta_psi;
  double delta_omega[3];
  double plate_velocity_change[3];
  int has_plate_impulse;
  double plate_impulse[3]; /**< J (N s for SI parameters) */
  int exact_replan;
  long next_impulse_tick; /**< -1: none left */
  int late;
  int budget_exhausted;
  int measurement_used;
  double x_now[2];
  double A_now[9];
  double omega_now[3];
  double x_next[2]; /**< predicted just before the next impulse */
  double A_next[9];
  double omega_next[3];
} pb_command;

typedef struct pb_controller pb_controller;
/** A controller for the plan (it shares the plan: the plan handle may be destroyed first). */
PB_API pb_status pb_controller_create(const pb_plan* plan, const pb_controller_options* options, pb_controller** out);
/** One tick; allocates nothing on ticks without a new exact re-plan. PB_OK whatever the
 * controller's status (see command->status); PB_INVALID_INPUT only for null pointers. */
PB_API pb_status pb_controller_update(pb_controller* controller,
                                      double time,
                                      const pb_measurement* measurement,
                                      pb_command* command);
/** Frees a controller (null: nothing). */
PB_API void pb_controller_destroy(pb_controller* controller);

#ifdef __cplusplus
}
#endif

#endif /* PLATEBALL_PLATEBALL_C_H */
