#include "rig/mujoco_twin.h"

#include <mujoco/mujoco.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <cstring>
#include <sstream>
#include <stdexcept>

#include "common/number_format.h"
#include "plateball/actuator_command.h"
#include "plateball/plate_impulse.h"
#include "plateball/so3.h"

namespace plateball::tools::rig {
namespace {

// Shortest round-trip text: the MJCF carries the exact parameters.
std::string Num(double v) { return FormatNumber(v); }

std::string Bad(const std::string& field, double value, const std::string& what) {
  return field + ": value " + Num(value) + ": " + what;
}

void ThrowIf(const std::string& message) {
  if (!message.empty()) throw std::invalid_argument(message);
}

// MuJoCo's warnings (for instance a diverging acceleration) would go to MUJOCO_LOG.TXT and standard
// output, where the tools write their JSON; the twin reads its data's warning counters instead.
void QuietWarning(const char*) {}

constexpr double kSettleTimeConstants = 60.0;   // vertical settling: e^-60 of the initial transient
constexpr double kMaxReplaySteps = 1e8;         // about 10 minutes of RK4 on one core
constexpr double kMaxPlateHalfSizeRadii = 1e6;  // the largest upper plate, in ball radii
const char* const kXmlName = "plateball_twin.xml";

}  // namespace

std::string TwinSettings::Validate() const {
  if (!(std::isfinite(timestep) && timestep > 0 && timestep <= 0.1))
    return Bad("timestep", timestep, "must be in (0, 0.1] s");
  if (!(std::isfinite(time_constant_steps) && time_constant_steps >= 2 && time_constant_steps <= 1e3))
    return Bad("time_constant_steps", time_constant_steps, "must be in [2, 1000] (MuJoCo clamps below 2)");
  if (!(std::isfinite(sliding_friction) && sliding_friction > 0))
    return Bad("sliding_friction", sliding_friction, "must be finite and > 0");
  if (!(std::isfinite(torsional_friction) && torsional_friction > 0))
    return Bad("torsional_friction", torsional_friction, "must be finite and > 0");
  if (!(std::isfinite(impedance) && impedance >= 0.5 && impedance <= 0.9999))
    return Bad("impedance", impedance, "must be in [0.5, 0.9999] (MuJoCo clamps above 0.9999)");
  if (noslip_iterations < 0 || noslip_iterations > 10000)
    return Bad("noslip_iterations", noslip_iterations, "must be in [0, 10000]");
  if (!(std::isfinite(gravity) && gravity > 0))
    return Bad("gravity", gravity, "must be finite and > 0 (it presses the plate)");
  if (!(std::isfinite(plate_half_size_radii) && plate_half_size_radii >= 2 &&
        plate_half_size_radii <= kMaxPlateHalfSizeRadii))
    return Bad("plate_half_size_radii", plate_half_size_radii, "must be in [2, 1e6]");
  return {};
}

std::string TwinBuildableMessage(const PhysicalParameters& p) {
  if (std::string m = p.Validate(); !m.empty()) return m;
  if (p.inertia_3 > 2.0 * p.inertia_1)
    return Bad("physical.inertia_3",
               p.inertia_3,
               "MuJoCo's compiler rejects principal moments that break the triangle inequality, I3 <= 2 I1 (I1 = " +
                   Num(p.inertia_1) + ")");
  if (!(p.plate_mass > 0))
    return Bad("physical.plate_mass",
               p.plate_mass,
               "the twin's upper plate is a moving body pressed by its weight: MuJoCo needs a mass > 0");
  return {};
}

std::string TwinMjcf(const PhysicalParameters& p,
                     const Eigen::Vector2d& x0,
                     const Eigen::Matrix3d& A0,
                     const TwinSettings& settings,
                     const Eigen::Vector3d& omega0) {
  ThrowIf(TwinBuildableMessage(p));
  ThrowIf(settings.Validate());
  const double r = p.radius;
  const double half = settings.plate_half_size_radii * r, thick = 0.25 * r;
  const Eigen::Quaterniond q(A0);
  const double plate_moment = p.plate_mass * (half * half + thick * thick) / 3.0;
  const Eigen::Vector3d omega(omega0.x(), omega0.y(), 0.0);
  const Eigen::Vector3d v = r * omega.cross(Eigen::Vector3d::UnitZ());  // rolling on the lower plate
  const Eigen::Vector3d w_body = A0.transpose() * omega;
  std::ostringstream x;
  x << "<mujoco model=\"plateball\">\n"
    << "  <!-- SI units. Lower plate fixed, upper plate on slide joints pressed by its weight; condim 4\n"
    << "       (sliding and torsional friction) holds the ball to rolling without slip or spin. -->\n"
    << "  <compiler angle=\"radian\" inertiafromgeom=\"false\"/>\n"
    << "  <option timestep=\"" << Num(settings.timestep) << "\" integrator=\"RK4\" cone=\"elliptic\""
    << " noslip_iterations=\"" << settings.noslip_iterations << "\" noslip_tolerance=\"1e-14\""
    << " solver=\"Newton\" iterations=\"100\" tolerance=\"1e-14\" gravity=\"0 0 " << Num(-settings.gravity) << "\"/>\n"
    << "  <default>\n"
    << "    <geom condim=\"4\" friction=\"" << Num(settings.sliding_friction) << " " << Num(settings.torsional_friction)
    << " 0\" solref=\"" << Num(settings.time_constant_steps * settings.timestep) << " 1\" solimp=\""
    << Num(settings.impedance) << " " << Num(settings.impedance) << " 0.001 0.5 2\"/>\n"
    << "  </default>\n"
    << "  <worldbody>\n"
    << "    <geom name=\"lower_plate\" type=\"plane\" size=\"" << Num(half) << " " << Num(half) << " " << Num(thick)
    << "\"/>\n"
    << "    <body name=\"ball\" pos=\"" << Num(x0.x() * r) << " " << Num(x0.y() * r) << " " << Num(r) << "\" quat=\""
    << Num(q.w()) << " " << Num(q.x()) << " " << Num(q.y()) << " " << Num(q.z()) << "\">\n"
    << "      <freejoint name=\"ball\"/>\n"
    << "      <inertial pos=\"0 0 0\" mass=\"" << Num(p.ball_mass) << "\" diaginertia=\"" << Num(p.inertia_1) << " "
    << Num(p.inertia_1) << " " << Num(p.inertia_3) << "\"/>\n"
    << "      <geom name=\"ball\" type=\"sphere\" size=\"" << Num(r) << "\"/>\n"
    << "    </body>\n"
    << "    <body name=\"upper_plate\" pos=\"" << Num(x0.x() * r) << " " << Num(x0.y() * r) << " " << Num(2 * r + thick)
    << "\">\n"
    << "      <joint name=\"plate_x\" type=\"slide\" axis=\"1 0 0\"/>\n"
    << "      <joint name=\"plate_y\" type=\"slide\" axis=\"0 1 0\"/>\n"
    << "      <joint name=\"plate_z\" type=\"slide\" axis=\"0 0 1\"/>\n"
    << "      <inertial pos=\"0 0 0\" mass=\"" << Num(p.plate_mass) << "\" diaginertia=\"" << Num(plate_moment) << " "
    << Num(plate_moment) << " " << Num(2 * plate_moment) << "\"/>\n"
    << "      <geom name=\"upper_plate\" type=\"box\" size=\"" << Num(half) << " " << Num(half) << " " << Num(thick)
    << "\"/>\n"
    << "    </body>\n"
    << "  </worldbody>\n"
    << "  <keyframe>\n"
    << "    <!-- the plan's start: qpos = ball (x y z, quat w x y z), plate slides (x y z); qvel = ball\n"
    << "         (linear velocity, world frame; angular velocity, body frame), plate (x y z) -->\n"
    << "    <key name=\"start\" qpos=\"" << Num(x0.x() * r) << " " << Num(x0.y() * r) << " " << Num(r) << " "
    << Num(q.w()) << " " << Num(q.x()) << " " << Num(q.y()) << " " << Num(q.z()) << " 0 0 0\" qvel=\"" << Num(v.x())
    << " " << Num(v.y()) << " 0 " << Num(w_body.x()) << " " << Num(w_body.y()) << " " << Num(w_body.z()) << " "
    << Num(2 * v.x()) << " " << Num(2 * v.y()) << " 0\"/>\n"
    << "  </keyframe>\n"
    << "</mujoco>\n";
  return x.str();
}

// ---------------------------------------------------------------- the engine

struct MujocoTwin::Engine {
  mjModel* m = nullptr;
  mjData* d = nullptr;
  int ball_q = 0, ball_v = 0;    // qpos / qvel addresses of the ball's free joint
  int plate_q = 0, plate_v = 0;  // of plate_x (plate_y, plate_z follow)
  ~Engine() {
    if (d) mj_deleteData(d);
    if (m) mj_deleteModel(m);
  }
};

MujocoTwin::MujocoTwin(const PhysicalParameters& p, const TwinSettings& settings)
    : engine_(std::make_unique<Engine>()), physical_(p), settings_(settings) {
  const std::string xml = TwinMjcf(p, Eigen::Vector2d::Zero(), Eigen::Matrix3d::Identity(), settings);
  mju_user_warning = QuietWarning;
  auto vfs = std::make_unique<mjVFS>();
  mj_defaultVFS(vfs.get());
  if (mj_makeEmptyFileVFS(vfs.get(), kXmlName, static_cast<int>(xml.size())) != 0)
    throw std::runtime_error("MuJoCo: cannot create the model's in-memory file");
  const int file = mj_findFileVFS(vfs.get(), kXmlName);
  std::memcpy(vfs->filedata[file], xml.data(), xml.size());
  char error[1000] = "";
  engine_->m = mj_loadXML(kXmlName, vfs.get(), error, sizeof(error));
  mj_deleteVFS(vfs.get());
  if (!engine_->m) throw std::runtime_error(std::string("MuJoCo rejected the twin's model: ") + error);
  engine_->d = mj_makeData(engine_->m);
  const mjModel* m = engine_->m;
  const int ball = mj_name2id(m, mjOBJ_JOINT, "ball"), plate = mj_name2id(m, mjOBJ_JOINT, "plate_x");
  engine_->ball_q = m->jnt_qposadr[ball];
  engine_->ball_v = m->jnt_dofadr[ball];
  engine_->plate_q = m->jnt_qposadr[plate];
  engine_->plate_v = m->jnt_dofadr[plate];
  // Let the heights settle (ball on the lower plate, plate on the ball), then stop every motion.
  const int settle = static_cast<int>(std::ceil(kSettleTimeConstants * settings.time_constant_steps));
  for (int i = 0; i < settle; ++i) mj_step(engine_->m, engine_->d);
  mju_zero(engine_->d->qvel, m->nv);
  mju_zero(engine_->d->qacc_warmstart, m->nv);
  engine_->d->time = 0.0;
}

MujocoTwin::~MujocoTwin() = default;

void MujocoTwin::SetState(double t, const Eigen::Vector2d& x, const Eigen::Matrix3d& A, const Eigen::Vector3d& omega) {
  mjData* d = engine_->d;
  const double r = physical_.radius;
  double* q = d->qpos + engine_->ball_q;
  q[0] = x.x() * r;
  q[1] = x.y() * r;
  const Eigen::Quaterniond quat(A);
  q[3] = quat.w();
  q[4] = quat.x();
  q[5] = quat.y();
  q[6] = quat.z();
  // The plate's slide joints measure from its body position above the model's origin.
  d->qpos[engine_->plate_q] = x.x() * r;
  d->qpos[engine_->plate_q + 1] = x.y() * r;
  d->time = t;
  SetAngularVelocity(omega);
}

void MujocoTwin::SetAngularVelocity(const Eigen::Vector3d& omega_in) {
  mjData* d = engine_->d;
  const double r = physical_.radius;
  const Eigen::Vector3d omega(omega_in.x(), omega_in.y(), 0.0);
  const double* q = d->qpos + engine_->ball_q;
  const Eigen::Quaterniond quat(q[3], q[4], q[5], q[6]);
  // Free joint: linear velocity in the world frame, angular velocity in the body frame.
  const Eigen::Vector3d local = quat.normalized().toRotationMatrix().transpose() * omega;
  const Eigen::Vector3d v = r * omega.cross(Eigen::Vector3d::UnitZ());  // rolling on the lower plate
  double* qv = d->qvel + engine_->ball_v;
  for (int i = 0; i < 3; ++i) {
    qv[i] = i < 2 ? v(i) : 0.0;
    qv[3 + i] = local(i);
  }
  d->qvel[engine_->plate_v] = 2 * v.x();  // the top point moves at twice the centre's velocity
  d->qvel[engine_->plate_v + 1] = 2 * v.y();
  d->qvel[engine_->plate_v + 2] = 0.0;
}

void MujocoTwin::Step(double h, const Eigen::Vector2d& plate_force) {
  mjModel* m = engine_->m;
  mjData* d = engine_->d;
  m->opt.timestep = h;
  d->qfrc_applied[engine_->plate_v] = plate_force.x();
  d->qfrc_applied[engine_->plate_v + 1] = plate_force.y();
  mj_step(m, d);
  if (d->warning[mjWARN_BADQACC].number > 0)
    throw std::runtime_error("MuJoCo: the simulation diverged (bad acceleration) at t = " + Num(d->time) + " s");
}

TwinState MujocoTwin::State() const {
  const mjData* d = engine_->d;
  const PhysicalParameters& p = physical_;
  const double r = p.radius;
  const double* q = d->qpos + engine_->ball_q;
  const double* qv = d->qvel + engine_->ball_v;
  TwinState s;
  s.t = d->time;
  s.x = Eigen::Vector2d(q[0], q[1]) / r;
  s.A = Eigen::Quaterniond(q[3], q[4], q[5], q[6]).normalized().toRotationMatrix();
  s.omega = s.A * Eigen::Vector3d(qv[3], qv[4], qv[5]);
  s.v = Eigen::Vector3d(qv[0], qv[1], qv[2]);
  s.plate_velocity =
      Eigen::Vector3d(d->qvel[engine_->plate_v], d->qvel[engine_->plate_v + 1], d->qvel[engine_->plate_v + 2]);
  const Eigen::Vector3d body_moments(p.inertia_1, p.inertia_1, p.inertia_3);
  const Eigen::Vector3d w_body = s.A.transpose() * s.omega;
  s.energy = 0.5 * p.ball_mass * s.v.head<2>().squaredNorm() + 0.5 * w_body.dot(body_moments.cwiseProduct(w_body)) +
             0.5 * p.plate_mass * s.plate_velocity.head<2>().squaredNorm();
  const Eigen::Vector3d e3 = Eigen::Vector3d::UnitZ();
  const Eigen::Vector3d bottom = s.v - r * s.omega.cross(e3);
  const Eigen::Vector3d top = s.v + r * s.omega.cross(e3) - s.plate_velocity;
  s.slip_speed = std::max(bottom.head<2>().norm(), top.head<2>().norm());
  s.spin_rate = std::abs(s.omega.z());
  s.contacts = d->ncon;
  return s;
}

// ---------------------------------------------------------------- replay

std::string ReplayOptions::Validate() const {
  if (!(std::isfinite(pulse_duration) && pulse_duration >= 0))
    return Bad("pulse_duration", pulse_duration, "must be finite and >= 0 s (0: ideal velocity jumps)");
  return settings.Validate();
}

void CheckPulseWindows(const RigPlan& plan, double duration, const std::string& field) {
  const std::vector<RigImpulse>& k = plan.impulses;
  for (std::size_t i = 0; i < k.size(); ++i) {
    const bool last = i + 1 == k.size();
    const double flight = (last ? plan.t_end : k[i + 1].t) - k[i].t;
    if (last && flight <= 0) continue;  // a stop at the end: its pulse runs past t_end
    if (duration > flight)
      throw std::invalid_argument(Bad(
          field,
          duration,
          "longer than the flight of " + Num(flight) + " s after impulse " + std::to_string(i) +
              (last ? " (the last: its pulse would run past the plan's end)"
                    : ": the pulses of impulses " + std::to_string(i) + " and " + std::to_string(i + 1) + " overlap")));
  }
}

void CheckPulseFriction(const RigPlan& plan, double duration, const TwinSettings& s, const std::string& field) {
  // The contacts' loads under the engine's gravity and friction coefficients (actuator_command.h).
  PulseOptions pulse;
  pulse.duration = duration;
  pulse.gravity = s.gravity;
  pulse.static_friction = s.sliding_friction;
  pulse.torsional_friction = s.torsional_friction;
  for (std::size_t i = 0; i < plan.impulses.size(); ++i) {
    const PlateImpulse imp = PlateImpulseFor(plan.physical, plan.impulses[i].z, plan.impulses[i].delta_omega);
    const PulseForces f = PulseForcesFor(plan.physical, imp, pulse);
    std::string what;
    if (f.slides)
      what = "the contacts need mu_s >= " + Num(f.sliding_friction_needed) + " (top " + Num(f.top_tangential_force) +
             " N on " + Num(f.top_normal_load) + " N, bottom " + Num(f.bottom_tangential_force) + " N on " +
             Num(f.bottom_normal_load) + " N), more than the engine's " + Num(s.sliding_friction);
    else if (f.spins)
      what = "the contacts need a torsional torque of " + Num(f.torsional_torque) + " N m, more than mu_t " +
             Num(s.torsional_friction) + " m times their loads";
    if (!what.empty())
      throw std::invalid_argument(
          Bad(field, duration, "too short: impulse " + std::to_string(i) + " would slip: " + what));
  }
}

double PlateHalfSizeFor(const RigPlan& plan, const PlannedTrajectory& reference, const TwinSettings& settings) {
  // The plate starts centred over the ball and moves twice as far: the contact moves on it as far as
  // the ball moves. The impulse points and the end bound the path up to a flight's length.
  double extent = 0.0, longest_flight = 0.0, previous = 0.0;
  for (const RigImpulse& k : plan.impulses) {
    extent = std::max(extent, (reference.At(k.t).x - plan.x0).norm());
    longest_flight = std::max(longest_flight, k.t - previous);
    previous = k.t;
  }
  longest_flight = std::max(longest_flight, plan.t_end - previous);
  extent = std::max(extent, (reference.At(plan.t_end).x - plan.x0).norm());
  // |x'| = |omega_h| <= sqrt(mu / min(1, lambda)) (eq. (9)) bounds a flight's path in radii.
  const double speed =
      std::sqrt(reference.MaxEnergy() * 2 /
                (plan.physical.inertia_1 + plan.physical.EffectiveMass() * std::pow(plan.physical.radius, 2)) /
                std::min(1.0, plan.model.lambda()));
  const double half = std::max(settings.plate_half_size_radii, 2 * (extent + speed * longest_flight) + 10);
  if (!(half <= kMaxPlateHalfSizeRadii))
    throw std::invalid_argument(Bad("total_time",
                                    plan.t_end,
                                    "the plan travels up to " + Num(half / 2) + " radii, more than the twin's plate (" +
                                        Num(kMaxPlateHalfSizeRadii) + " radii) holds"));
  return half;
}

namespace {

// The times where the force or the velocity changes, sorted, ending with the replay's end: the
// impulse times for ideal jumps, the window edges for pulses of duration D.
// Where impulse time t's pulse starts: t - D/2 (centred) or t (causal).
double PulseStart(double t, double D, bool causal) { return causal ? t : t - D / 2; }

std::vector<double> BreakTimes(const RigPlan& plan, double D, bool causal) {
  std::vector<double> breaks{plan.t_end};
  for (const RigImpulse& k : plan.impulses) {
    if (D > 0) {
      breaks.push_back(PulseStart(k.t, D, causal));
      breaks.push_back(PulseStart(k.t, D, causal) + D);
    } else {
      breaks.push_back(k.t);
    }
  }
  std::sort(breaks.begin(), breaks.end());
  return breaks;
}

void CheckStepCount(const RigPlan& plan, double span, double dt) {
  const double steps = span / dt;
  if (steps > kMaxReplaySteps)
    throw std::invalid_argument(Bad("total_time",
                                    plan.t_end,
                                    "the replay would take " + Num(std::ceil(steps)) + " steps of " + Num(dt) +
                                        " s, more than " + Num(kMaxReplaySteps)));
}

// Equal substeps <= dt from a to b.
int Substeps(double a, double b, double dt) { return std::max(1, static_cast<int>(std::ceil((b - a) / dt - 1e-9))); }

}  // namespace

ReplayReport ReplayInTwin(const RigPlan& plan, const PlannedTrajectory& reference, const ReplayOptions& options) {
  ThrowIf(options.Validate());
  const double D = options.pulse_duration;
  const std::vector<RigImpulse>& impulses = plan.impulses;
  ReplayReport out;
  std::vector<Eigen::Vector2d> force(impulses.size(), Eigen::Vector2d::Zero());
  for (std::size_t i = 0; i < impulses.size(); ++i) {
    out.pulse_impulse.push_back(PlateImpulseFor(plan.physical, impulses[i].z, impulses[i].delta_omega).plate);
    if (D > 0) force[i] = out.pulse_impulse[i].head<2>() / D;
  }
  if (D > 0) {
    CheckPulseWindows(plan, D, "pulse_duration");
    CheckPulseFriction(plan, D, options.settings, "pulse_duration");
  }
  const std::vector<double> breaks = BreakTimes(plan, D, options.causal);
  out.t_begin = std::min(0.0, breaks.front());
  out.t_end = breaks.back();
  CheckStepCount(plan, out.t_end - out.t_begin, options.settings.timestep);

  TwinSettings settings = options.settings;
  settings.plate_half_size_radii = PlateHalfSizeFor(plan, reference, settings);
  MujocoTwin twin(plan.physical, settings);
  // The planned state at t_begin is the one after an impulse there; a pulse starting at t_begin (causal,
  // an impulse at t = 0) starts from the state before it.
  MotionSample start = reference.At(out.t_begin);
  if (D > 0 && out.t_begin == 0.0) {
    start.state = plan.start;
    start.x = plan.x0;
    start.A = plan.A0;
  }
  twin.SetState(out.t_begin, start.x, start.A, start.state.omega);
  std::size_t next_jump = 0;
  auto apply_jumps = [&](double t) {
    while (D == 0 && next_jump < impulses.size() && impulses[next_jump].t <= t) {
      twin.SetAngularVelocity(impulses[next_jump].omega_after);
      ++next_jump;
    }
  };
  apply_jumps(out.t_begin);
  double a = out.t_begin;
  for (const double b : breaks) {
    if (b <= a) continue;
    Eigen::Vector2d f = Eigen::Vector2d::Zero();
    const double mid = 0.5 * (a + b);
    for (std::size_t i = 0; D > 0 && i < impulses.size(); ++i)
      if (std::abs(mid - (PulseStart(impulses[i].t, D, options.causal) + D / 2)) < D / 2) f += force[i];
    const int n = Substeps(a, b, options.settings.timestep);
    for (int i = 0; i < n; ++i) {
      twin.Step((b - a) / n, f);
      const TwinState s = twin.State();
      if (s.contacts < 2)
        throw std::runtime_error("the ball left the plates in the engine at t = " + Num(s.t) + " s (" +
                                 std::to_string(s.contacts) + " contacts)");
      out.max_slip_speed = std::max(out.max_slip_speed, s.slip_speed);
      out.max_spin_rate = std::max(out.max_spin_rate, s.spin_rate);
    }
    out.steps += n;
    a = b;
    apply_jumps(a);
  }
  const TwinState end = twin.State();
  const MotionSample planned = reference.At(out.t_end);
  out.position_error = (end.x - planned.x).norm();
  out.orientation_error = LogSO3(planned.A.transpose() * end.A).norm();
  out.energy_planned = reference.EnergyAt(out.t_end);
  out.energy_engine = end.energy;
  const double diff = std::abs(out.energy_engine - out.energy_planned);
  out.energy_error = reference.MaxEnergy() > 0 ? diff / reference.MaxEnergy() : diff;
  return out;
}

}  // namespace plateball::tools::rig
