// The C API (plateball_c.h): thin wrappers that catch every exception and turn it into a status.
#include "plateball/plateball_c.h"

#include <exception>
#include <memory>
#include <new>
#include <optional>
#include <stdexcept>
#include <string>

#include "plateball/controller.h"
#include "plateball/exact_arrival.h"
#include "plateball/execution.h"
#include "plateball/problem_io.h"
#include "plateball/task_adapters.h"

struct pb_problem {
  plateball::Problem problem;
};
struct pb_plan {
  std::shared_ptr<const plateball::NominalPlan> nominal;
  std::optional<plateball::PhysicalParameters> physical;
};
struct pb_controller {
  std::unique_ptr<plateball::Controller> controller;
};

namespace {

thread_local std::string last_error;

pb_status Fail(pb_status status, const std::string& message) noexcept {
  try {
    last_error = message;
  } catch (...) {
    last_error.clear();  // out of memory: the status still says what failed
  }
  return status;
}

// Runs f, mapping the library's exceptions to the tools' codes.
template <typename F>
pb_status Guard(F&& f) {
  try {
    last_error.clear();
    return f();
  } catch (const plateball::ProblemFileReadError& e) {
    return Fail(PB_IO_ERROR, e.what());
  } catch (const std::invalid_argument& e) {
    return Fail(PB_INVALID_INPUT, e.what());
  } catch (const std::bad_alloc&) {
    return Fail(PB_INTERNAL_ERROR, "out of memory");
  } catch (const std::exception& e) {
    return Fail(PB_INTERNAL_ERROR, e.what());
  } catch (...) {
    return Fail(PB_INTERNAL_ERROR, "unknown exception");
  }
}

pb_status Null(const char* what) noexcept {
  try {
    return Fail(PB_INVALID_INPUT, std::string(what) + ": value null: required");
  } catch (...) {
    return PB_INVALID_INPUT;
  }
}

Eigen::Matrix3d Matrix(const double* m) {
  Eigen::Matrix3d a;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) a(i, j) = m[3 * i + j];
  return a;
}
void Store(const Eigen::Matrix3d& a, double* m) {
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) m[3 * i + j] = a(i, j);
}
template <typename V>
void Store(const V& v, double* out) {
  for (int i = 0; i < v.size(); ++i) out[i] = v[i];
}

pb_impulse ToC(double t_impulse,
               double duration,
               double delta_psi,
               const Eigen::Vector3d& delta_omega,
               const Eigen::Vector2d& position) {
  pb_impulse c{};
  c.t_impulse = t_impulse;
  c.duration = duration;
  c.delta_psi = delta_psi;
  Store(delta_omega, c.delta_omega);
  Store(position, c.position);
  return c;
}

}  // namespace

extern "C" {

const char* pb_last_error(void) { return last_error.c_str(); }

pb_status pb_problem_load(const char* path, pb_problem** out) {
  if (path == nullptr) return Null("path");
  if (out == nullptr) return Null("out");
  *out = nullptr;
  return Guard([&] {
    auto p = std::make_unique<pb_problem>();
    p->problem = plateball::ReadProblemFile(path);
    *out = p.release();
    return PB_OK;
  });
}

void pb_problem_destroy(pb_problem* problem) { delete problem; }

pb_status pb_plan_create(const pb_problem* problem, int n, pb_plan** out) {
  if (problem == nullptr) return Null("problem");
  if (out == nullptr) return Null("out");
  *out = nullptr;
  return Guard([&] {
    if (n < 0)
      return Fail(PB_INVALID_INPUT, "n: value " + std::to_string(n) + ": must be >= 0 (0: the file's partition)");
    const plateball::PlanSetup setup = plateball::PlanSetupFor(problem->problem, n);
    auto nominal = std::make_shared<plateball::NominalPlan>(plateball::MakeNominalPlan(setup.problem, setup.options));
    if (!nominal->plan.IsSolutionUsable()) return Fail(PB_NO_SOLUTION, nominal->plan.BriefReport());
    auto p = std::make_unique<pb_plan>();
    p->nominal = std::move(nominal);
    p->physical = problem->problem.physical;
    *out = p.release();
    return PB_OK;
  });
}

void pb_plan_destroy(pb_plan* plan) { delete plan; }

int pb_plan_impulse_count(const pb_plan* plan) {
  return plan == nullptr ? 0 : static_cast<int>(plan->nominal->plan.steps.size());
}

double pb_plan_total_time(const pb_plan* plan) { return plan == nullptr ? 0.0 : plan->nominal->plan.total_time; }

pb_status pb_plan_impulse(const pb_plan* plan, int k, pb_impulse* out) {
  if (plan == nullptr) return Null("plan");
  if (out == nullptr) return Null("out");
  return Guard([&] {
    if (k < 0 || k >= pb_plan_impulse_count(plan))
      return Fail(
          PB_INVALID_INPUT,
          "k: value " + std::to_string(k) + ": must be in [0, " + std::to_string(pb_plan_impulse_count(plan)) + ")");
    const plateball::PlanStep& s = plan->nominal->plan.steps[static_cast<std::size_t>(k)];
    *out = ToC(s.t_impulse, s.duration, s.delta_psi, s.delta_omega, s.p_begin);
    return PB_OK;
  });
}

pb_status pb_steer(double lambda,
                   const pb_ball_state* start,
                   const double goal_x[2],
                   const double goal_A[9],
                   int impulses,
                   pb_impulse* out,
                   int capacity) {
  if (start == nullptr) return Null("start");
  if (goal_x == nullptr) return Null("goal_x");
  if (goal_A == nullptr) return Null("goal_A");
  if (out == nullptr && capacity > 0) return Null("out");
  return Guard([&] {
    plateball::ExactArrivalProblem p;
    p.model = plateball::BallModel::FromLambda(lambda);
    p.initial = {start->theta, start->phi, start->psi};
    p.mu = start->mu;
    p.A0 = Matrix(start->A);
    p.x0 = {start->x[0], start->x[1]};
    p.x1 = {goal_x[0], goal_x[1]};
    p.A1 = Matrix(goal_A);
    p.impulses = impulses;
    if ((p.x1 - p.x0).norm() == 0.0)
      return Fail(PB_INVALID_INPUT, "goal_x: value equal to start.x: the reference segment needs two points");
    p.reference = plateball::Path({plateball::SmoothCurve::Line(p.x0, p.x1)});
    const plateball::ExactArrivalSummary s = plateball::SolveExactArrival(p);
    if (!s.IsSolutionUsable()) return Fail(PB_NO_SOLUTION, s.BriefReport());
    for (int k = 0; k < capacity && k < static_cast<int>(s.impulses.size()); ++k) {
      const plateball::ExactImpulse& e = s.impulses[static_cast<std::size_t>(k)];
      out[k] = ToC(e.t_impulse, e.duration, e.delta_psi, e.delta_omega, e.position);
    }
    return PB_OK;
  });
}

void pb_controller_options_default(pb_controller_options* options) {
  if (options == nullptr) return;
  const plateball::ControllerOptions d;
  options->tick_period = d.tick_period;
  options->strategy = PB_FEEDBACK;
  options->time_budget = d.time_budget;
  options->jump_tolerance = d.jump_tolerance;
  options->orientation_jump_tolerance = d.orientation_jump_tolerance;
  options->rotation_tolerance = d.rotation_tolerance;
  options->exact_window = d.execution.exact_window;
  options->plate_impulse = 0;
}

pb_status pb_controller_create(const pb_plan* plan, const pb_controller_options* options, pb_controller** out) {
  if (plan == nullptr) return Null("plan");
  if (options == nullptr) return Null("options");
  if (out == nullptr) return Null("out");
  *out = nullptr;
  return Guard([&] {
    plateball::ControllerOptions o;
    o.tick_period = options->tick_period;
    if (options->strategy != PB_FEEDBACK && options->strategy != PB_FEEDBACK_EXACT)
      return Fail(PB_INVALID_INPUT,
                  "strategy: value " + std::to_string(static_cast<int>(options->strategy)) +
                      ": must be PB_FEEDBACK or PB_FEEDBACK_EXACT");
    o.strategy = options->strategy == PB_FEEDBACK ? plateball::ExecutionStrategy::kFeedback
                                                  : plateball::ExecutionStrategy::kFeedbackExact;
    o.time_budget = options->time_budget;
    o.jump_tolerance = options->jump_tolerance;
    o.orientation_jump_tolerance = options->orientation_jump_tolerance;
    o.rotation_tolerance = options->rotation_tolerance;
    o.execution.exact_window = options->exact_window;
    if (options->plate_impulse != 0) {
      if (!plan->physical)
        return Fail(PB_INVALID_INPUT, "plate_impulse: value 1: the problem file gives no physical parameters");
      o.physical = plan->physical;
    }
    auto c = std::make_unique<pb_controller>();
    c->controller = std::make_unique<plateball::Controller>(plan->nominal, o);
    *out = c.release();
    return PB_OK;
  });
}

pb_status pb_controller_update(pb_controller* controller,
                               double time,
                               const pb_measurement* measurement,
                               pb_command* command) {
  if (controller == nullptr) return Null("controller");
  if (measurement == nullptr) return Null("measurement");
  if (command == nullptr) return Null("command");
  plateball::ControllerMeasurement m;
  m.x = {measurement->x[0], measurement->x[1]};
  m.has_orientation = measurement->has_orientation != 0;
  m.A = Matrix(measurement->A);
  m.omega = {measurement->omega[0], measurement->omega[1], measurement->omega[2]};
  const plateball::ControllerOutput& o = controller->controller->Update(time, m);  // never throws
  pb_command& c = *command;
  c.status = static_cast<pb_controller_status>(static_cast<int>(o.status));
  c.reason = o.reason;
  c.tick = o.tick;
  c.impulse = o.impulse ? 1 : 0;
  c.impulse_index = o.impulse_index;
  c.delta_psi = o.delta_psi;
  Store(o.delta_omega, c.delta_omega);
  Store(o.plate_velocity_change, c.plate_velocity_change);
  c.has_plate_impulse = o.has_plate_impulse ? 1 : 0;
  Store(o.plate_impulse.plate, c.plate_impulse);
  c.exact_replan = o.exact_replan ? 1 : 0;
  c.next_impulse_tick = o.next_impulse_tick;
  c.late = o.late ? 1 : 0;
  c.budget_exhausted = o.budget_exhausted ? 1 : 0;
  c.measurement_used = o.measurement_used ? 1 : 0;
  Store(o.now.x, c.x_now);
  Store(o.now.A, c.A_now);
  Store(o.now.state.omega, c.omega_now);
  Store(o.at_next_impulse.x, c.x_next);
  Store(o.at_next_impulse.A, c.A_next);
  Store(o.at_next_impulse.state.omega, c.omega_next);
  return PB_OK;
}

void pb_controller_destroy(pb_controller* controller) { delete controller; }

}  // extern "C"
