#include "rig/rig_plan.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <stdexcept>

#include "common/input_file.h"
#include "common/invalid_input.h"
#include "plateball/problem_io.h"
#include "plateball/so3.h"

namespace plateball::tools::rig {
namespace {

using nlohmann::json;

[[noreturn]] void Fail(const std::string& field, const std::string& value, const std::string& what) {
  ThrowInvalidInput(field, value, what);
}

std::string Text(const json& j) {
  std::string s = j.dump(-1, ' ', false, json::error_handler_t::replace);
  return s.size() > 80 ? s.substr(0, 80) + "..." : s;
}

const json& Get(const json& at, const std::string& where, const std::string& key) {
  if (!at.is_object() || !at.contains(key)) Fail(where + key, "(missing)", "required field of the result is missing");
  return at.at(key);
}

double Number(const json& at, const std::string& where, const std::string& key) {
  const json& j = Get(at, where, key);
  if (!j.is_number() || !std::isfinite(j.get<double>())) Fail(where + key, Text(j), "must be a finite number");
  return j.get<double>();
}

template <int N>
Eigen::Matrix<double, N, 1> VectorOf(const json& j, const std::string& field) {
  Eigen::Matrix<double, N, 1> v;
  if (!j.is_array() || j.size() != N) Fail(field, Text(j), "must be an array of " + std::to_string(N) + " numbers");
  for (int i = 0; i < N; ++i) {
    if (!j[i].is_number() || !std::isfinite(j[i].get<double>())) Fail(field, Text(j), "must hold finite numbers");
    v(i) = j[i].get<double>();
  }
  return v;
}

template <int N>
Eigen::Matrix<double, N, 1> Vector(const json& at, const std::string& where, const std::string& key) {
  return VectorOf<N>(Get(at, where, key), where + key);
}

Eigen::Matrix3d Rotation(const json& at, const std::string& where, const std::string& key) {
  const json& j = Get(at, where, key);
  if (!j.is_array() || j.size() != 3) Fail(where + key, Text(j), "must be a 3x3 matrix (rows)");
  Eigen::Matrix3d m;
  for (int i = 0; i < 3; ++i) m.row(i) = VectorOf<3>(j[i], where + key).transpose();
  if (!IsRotation(m, 1e-9)) Fail(where + key, Text(j), "not a rotation matrix to 1e-9");
  return m;
}

AngleState Angles(const json& at, const std::string& where, const std::string& key) {
  const json& j = Get(at, where, key);
  const std::string w = where + key + ".";
  return AngleState{Number(j, w, "theta"), Number(j, w, "phi"), Number(j, w, "psi")};
}

// (z, omega) of angles at energy mu >= 0 (omega = 0 at rest; z does not depend on mu).
BallState StateOf(const AngleState& a, double mu, const BallModel& model) {
  BallState s = StateFromAngles(a, mu > 0 ? mu : 1.0, model);
  if (!(mu > 0)) s.omega.setZero();
  return s;
}

// The problem file the result names: as given, else beside the result (as `plateball view`).
Problem LoadProblemOf(const json& doc, const std::string& result_file) {
  const json& problem = Get(doc, "", "problem");
  const json& f = Get(problem, "problem.", "file");
  if (!f.is_string()) Fail("problem.file", Text(f), "the result does not name its problem file");
  std::string file = f.get<std::string>();
  const std::filesystem::path beside = std::filesystem::path(result_file).parent_path() / file;
  if (!std::filesystem::exists(file) && std::filesystem::exists(beside)) file = beside.string();
  return ReadProblemFile(file);
}

RigImpulse ImpulseOf(
    const json& step, const std::string& where, const BallModel& model, bool plan, BallState* before_state) {
  RigImpulse k;
  k.t = Number(step, where, "t_impulse");
  k.delta_omega = Vector<3>(step, where, "delta_omega");
  const AngleState before = Angles(step, where, "angles_before");
  const double mu_before = plan ? Number(step, where, "mu") : Number(step, where, "mu_before");
  const BallState state = StateOf(before, mu_before, model);
  *before_state = state;
  k.z = state.z;
  k.omega_after = plan ? Vector<3>(step, where, "omega_after_impulse") : Eigen::Vector3d(state.omega + k.delta_omega);
  return k;
}

}  // namespace

RigPlan ReadRigPlan(const std::string& result_file) {
  json doc;
  try {
    doc = json::parse(ReadInputText(result_file));
  } catch (const json::parse_error& e) {
    Fail("RESULT.json", "\"" + result_file + "\"", std::string("not JSON: ") + e.what());
  }
  RigPlan out;
  const json& command = Get(doc, "", "command");
  if (command != "plan" && command != "steer" && command != "isoparallel")
    Fail("command", Text(command), "the rig replays results of `plateball plan`, `steer` and `isoparallel`");
  out.command = command.get<std::string>();
  out.problem = LoadProblemOf(doc, result_file);
  const Problem& p = out.problem;
  if (!p.physical)
    Fail("ball.physical", "(missing)", "the rig needs the ball's physical parameters (problem " + p.source + ")");
  const double lambda = Number(Get(doc, "", "model"), "model.", "lambda");
  if (std::abs(lambda - p.model.lambda()) > 1e-12 * p.model.lambda())
    Fail("model.lambda",
         Text(Get(doc, "", "model").at("lambda")),
         "the result was planned for another ball than its problem file's now (lambda " + Text(json(p.model.lambda())) +
             ")");
  out.physical = *p.physical;
  out.model = p.model;
  out.integration = p.integration;
  // isoparallel results hold a plan in the layout of `plateball plan` under "plan".
  const bool plan = out.command != "steer";
  const bool nested = out.command == "isoparallel";
  const json& body = nested ? Get(doc, "", "plan") : doc;
  const std::string prefix = nested ? "plan." : "";
  const json& initial = Get(doc, "", "initial");
  out.start = StateOf(Angles(initial, "initial.", "angles"), Number(initial, "initial.", "mu"), out.model);
  out.x0 = Vector<2>(initial, "initial.", "x0");
  out.t_end = Number(body, prefix, "total_time");
  const std::string list = prefix + (plan ? "steps" : "impulses");
  const json& steps = Get(body, prefix, plan ? "steps" : "impulses");
  if (!steps.is_array() || steps.empty())
    Fail(list, Text(steps), "the rig needs the per-impulse records (run without --summary-only)");
  double previous = 0.0;
  for (std::size_t i = 0; i < steps.size(); ++i) {
    const std::string where = list + "[" + std::to_string(i) + "].";
    BallState before;
    RigImpulse k = ImpulseOf(steps[i], where, out.model, plan, &before);
    if (k.t < previous || k.t > out.t_end * (1 + 1e-12) + 1e-12)
      Fail(where + "t_impulse", std::to_string(k.t), "impulse times must increase within [0, total_time]");
    // The first impulse (at t = 0) starts from its record's state and position: steer starts at rest
    // with --start-at-rest and from the isoparallel start without a plan section.
    if (i == 0 && k.t == 0.0) {
      out.start = before;
      if (!plan) out.x0 = Vector<2>(steps[i], where, "x");
    }
    previous = k.t;
    out.impulses.push_back(k);
  }
  if (plan) {
    out.A0 = Rotation(initial, "initial.", "orientation");
  } else {
    // steer's start orientation (task_adapters.cc): the isoparallel start without a plan section.
    const bool iso = !p.plan && p.isoparallel;
    out.A0 = AlignOrientationToAxis(iso ? p.isoparallel->start_orientation : p.A0, out.start.z);
  }
  if ((out.A0.col(2) - out.start.z).norm() > 1e-9)
    Fail("initial.orientation", "(matrix)", "its third column is not the symmetry axis of the first impulse's state");
  return out;
}

PlannedTrajectory::PlannedTrajectory(const RigPlan& plan) : plan_(plan) {
  MotionSample at;
  at.t = 0.0;
  at.state = plan.start;
  at.x = plan.x0;
  at.A = plan.A0;
  auto add_arc = [&](double t0, const BallState& state) {
    Arc arc;
    arc.t0 = t0;
    if (Energy(state, plan.model) > 0) {
      arc.motion = std::make_shared<const FreeMotion>(plan.model, FreeMotionStart{state, at.x, at.A}, plan.integration);
    }
    arc.rest = at;
    arc.rest.state = state;
    arc.rest.energy = Energy(state, plan.model);
    arcs_.push_back(arc);
    max_energy_ = std::max(max_energy_, EnergyAt(t0));
  };
  add_arc(0.0, plan.start);
  for (const RigImpulse& k : plan.impulses) {
    at = At(k.t);
    BallState after{at.state.z, k.omega_after};
    after.omega.z() = 0.0;  // no spin: the records' omega_3 is 0 to rounding
    add_arc(k.t, after);
  }
}

const PlannedTrajectory::Arc& PlannedTrajectory::ArcAt(double t) const {
  std::size_t i = 0;
  while (i + 1 < arcs_.size() && arcs_[i + 1].t0 <= t) ++i;
  return arcs_[i];
}

MotionSample PlannedTrajectory::At(double t) const {
  const Arc& arc = ArcAt(t);
  MotionSample s = arc.motion ? arc.motion->At(t - arc.t0) : arc.rest;
  s.t = t;
  return s;
}

double PlannedTrajectory::EnergyAt(double t) const {
  const PhysicalParameters& p = plan_.physical;
  return 0.5 * At(t).energy * (p.inertia_1 + p.EffectiveMass() * p.radius * p.radius);
}

}  // namespace plateball::tools::rig
