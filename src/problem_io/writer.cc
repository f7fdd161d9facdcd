// The problem writer: every field of a Problem, defaults included, in the reader's key order
// (WriteProblemJson). Orientations are written as matrices.
#include "problem_io/writer.h"

#include <cmath>
#include <stdexcept>
#include <variant>

#include "problem_io/field_archive.h"
#include "problem_io/value_text.h"

namespace plateball::internal::problem_io {
namespace {

class Writer {
 public:
  double Num(const std::string& path, double v) const { return WrittenNumber(path, v); }
  ojson Vec(const std::string& path, const Eigen::Vector2d& v) const {
    return ojson::array({Num(path, v.x()), Num(path, v.y())});
  }
  ojson Mat(const std::string& path, const Eigen::Matrix3d& m) const {
    ojson rows = ojson::array();
    for (int i = 0; i < 3; ++i)
      rows.push_back(ojson::array({Num(path, m(i, 0)), Num(path, m(i, 1)), Num(path, m(i, 2))}));
    return ojson{{"matrix", rows}};
  }
  ojson Points(const std::string& path, const std::vector<Eigen::Vector2d>& pts) const {
    ojson a = ojson::array();
    for (const auto& q : pts) a.push_back(Vec(path, q));
    return a;
  }

  ojson Path(const PathSpec& spec, const std::string& path) const {
    ojson o;
    o["type"] = ToString(spec);
    auto tau_range = [&](double begin, double end) {
      o["tau_begin"] = Num(path + ".tau_begin", begin);
      o["tau_end"] = Num(path + ".tau_end", end);
    };
    if (const auto* l = std::get_if<LineSpec>(&spec.shape)) {
      o["from"] = Vec(path + ".from", l->from);
      o["to"] = Vec(path + ".to", l->to);
    } else if (const auto* c = std::get_if<CircleSpec>(&spec.shape)) {
      o["center"] = Vec(path + ".center", c->center);
      o["radius"] = Num(path + ".radius", c->radius);
      tau_range(c->tau_begin, c->tau_end);
    } else if (const auto* e = std::get_if<EllipseSpec>(&spec.shape)) {
      o["center"] = Vec(path + ".center", e->center);
      o["semi_axes"] = Vec(path + ".semi_axes", e->semi_axes);
      o["rotation"] = Num(path + ".rotation", e->rotation);
      tau_range(e->tau_begin, e->tau_end);
    } else if (const auto* m = std::get_if<LemniscateSpec>(&spec.shape)) {
      o["center"] = Vec(path + ".center", m->center);
      o["scale"] = Num(path + ".scale", m->scale);
      o["rotation"] = Num(path + ".rotation", m->rotation);
      tau_range(m->tau_begin, m->tau_end);
    } else if (const auto* w = std::get_if<SineSpec>(&spec.shape)) {
      o["from"] = Vec(path + ".from", w->from);
      o["rotation"] = Num(path + ".rotation", w->rotation);
      o["length"] = Num(path + ".length", w->length);
      o["amplitude"] = Num(path + ".amplitude", w->amplitude);
      o["wavelength"] = Num(path + ".wavelength", w->wavelength);
    } else if (const auto* sm = std::get_if<SamplesSpec>(&spec.shape)) {
      o["points"] = Points(path + ".points", sm->points);
    } else {
      const PiecewiseSpec& pw = std::get<PiecewiseSpec>(spec.shape);
      ojson pieces = ojson::array();
      for (std::size_t i = 0; i < pw.pieces.size(); ++i)
        pieces.push_back(Path(pw.pieces[i], path + ".pieces[" + std::to_string(i) + "]"));
      o["pieces"] = pieces;
    }
    return o;
  }

  // The model in the form it was given: physical parameters, {alpha, beta} or lambda.
  ojson Ball(const Problem& p) const {
    if (p.physical) {
      const PhysicalParameters& q = *p.physical;
      return ojson{{"physical",
                    ojson{{"inertia_1", Num("ball.physical.inertia_1", q.inertia_1)},
                          {"inertia_3", Num("ball.physical.inertia_3", q.inertia_3)},
                          {"ball_mass", Num("ball.physical.ball_mass", q.ball_mass)},
                          {"radius", Num("ball.physical.radius", q.radius)},
                          {"plate_mass", Num("ball.physical.plate_mass", q.plate_mass)}}}};
    }
    if (p.model.has_inertia())
      return ojson{{"alpha", Num("ball.alpha", p.model.alpha())}, {"beta", Num("ball.beta", p.model.beta())}};
    return ojson{{"lambda", Num("ball.lambda", p.model.lambda())}};
  }

  ojson Plan(const PlanTask& task) const {
    ojson plan;
    plan["path"] = Path(task.path, "plan.path");
    ojson part;
    const PartitionSpec& rule = task.partition;
    part["type"] = ToString(rule);
    if (const auto* e = std::get_if<ExplicitTaus>(&rule)) {
      ojson taus = ojson::array();
      for (double t : e->taus) taus.push_back(Num("plan.partition.taus", t));
      part["taus"] = taus;
    } else if (const auto* u = std::get_if<UniformParameter>(&rule)) {
      part["n"] = u->n;
    } else {
      part["n"] = std::get<UniformArcLength>(rule).n;
    }
    plan["partition"] = part;
    ojson changes = ojson::array();
    for (const EnergyChangeSpec& c : task.energy_changes)
      changes.push_back(ojson{{"index", c.index}, {"factor", Num("plan.energy_changes.factor", c.factor)}});
    plan["energy_changes"] = changes;
    plan["converge_n"] = task.converge_n;
    return plan;
  }

  ojson Isoparallel(const IsoparallelTask& t) const {
    return ojson{{"start", Vec("isoparallel.start", t.start)},
                 {"goal", Vec("isoparallel.goal", t.goal)},
                 {"start_orientation", Mat("isoparallel.start_orientation.matrix", t.start_orientation)},
                 {"goal_orientation", Mat("isoparallel.goal_orientation.matrix", t.goal_orientation)},
                 {"impulses", t.impulses},
                 {"solver", WriteSection(t.solver, "isoparallel.solver")}};
  }

  ojson Steer(const SteerTask& task) const {
    ojson s = ojson{{"goal", Vec("steer.goal", task.goal)},
                    {"goal_orientation", Mat("steer.goal_orientation.matrix", task.goal_orientation)},
                    {"impulses", task.impulses},
                    {"start_at_rest", task.start_at_rest},
                    {"stop_at_goal", task.stop_at_goal},
                    {"objective", ToString(task.objective)}};
    if (const auto& f = task.fewest) s["fewest"] = WriteSection(*f, "steer.fewest");
    return s;
  }

  ojson Shape(const std::string& path, const PlateShape& shape) const {
    if (const auto* d = std::get_if<DiskShape>(&shape))
      return ojson{
          {"type", "disk"}, {"center", Vec(path + ".center", d->center)}, {"radius", Num(path + ".radius", d->radius)}};
    return ojson{{"type", "polygon"}, {"vertices", Points(path + ".vertices", std::get<PolygonShape>(shape).vertices)}};
  }

  // The rig in ball radii (a file in metres is written in radii); unset bounds are left out.
  // RigLimits' field list gives the key order and the scalar limits; its ByHand fields here.
  ojson Rig(const RigLimits& l) const {
    return WriteSection(l, "rig", [&](const std::string& key, ojson* r) {
      if (key == "plate" && l.plate) (*r)["plate"] = Shape("rig.plate", *l.plate);
      if (key == "obstacles" && !l.obstacles.empty()) {
        (*r)["obstacles"] = ojson::array();
        for (std::size_t i = 0; i < l.obstacles.size(); ++i)
          (*r)["obstacles"].push_back(Shape("rig.obstacles[" + std::to_string(i) + "]", l.obstacles[i]));
      }
      if (key == "stroke" && l.stroke) (*r)["stroke"] = Vec("rig.stroke", *l.stroke);
      if (key == "pulse_duration" && !std::isinf(l.max_force))
        (*r)["pulse_duration"] = Num("rig.pulse_duration", l.pulse_duration);
    });
  }

  ojson Expected(const std::map<std::string, ExpectedValue>& expected) const {
    ojson e = ojson::object();
    for (const auto& [name, v] : expected)
      e[name] = ojson{{"value", Num("expected." + name + ".value", v.value)},
                      {"tolerance", Num("expected." + name + ".tolerance", v.tolerance)}};
    return e;
  }

  std::string Document(const Problem& p) const {
    ojson d;
    if (!p.name.empty()) d["name"] = p.name;
    if (!p.description.empty()) d["description"] = p.description;
    d["seed"] = p.seed;
    d["integration"] = WriteSection(p.integration, "integration");
    d["ball"] = Ball(p);
    d["initial"] = ojson{{"theta", Num("initial.theta", p.initial.theta)},
                         {"phi", Num("initial.phi", p.initial.phi)},
                         {"psi", Num("initial.psi", p.initial.psi)},
                         {"mu", Num("initial.mu", p.mu)},
                         {"x0", Vec("initial.x0", p.x0)},
                         {"orientation", Mat("initial.orientation.matrix", p.A0)}};
    if (p.simulate) d["simulate"] = WriteSection(*p.simulate, "simulate");
    if (p.reach)
      d["reach"] = ojson{{"targets", Points("reach.targets", p.reach->targets)},
                         {"horizon_periods", Num("reach.horizon_periods", p.reach->horizon_periods)}};
    if (p.plan) d["plan"] = Plan(*p.plan);
    if (p.isoparallel) d["isoparallel"] = Isoparallel(*p.isoparallel);
    if (p.steer) d["steer"] = Steer(*p.steer);
    if (!p.rig.Empty()) d["rig"] = Rig(p.rig);
    if (!p.expected.empty()) d["expected"] = Expected(p.expected);
    return d.dump(2, ' ', false, ojson::error_handler_t::replace) + "\n";
  }
};

}  // namespace

std::string WriteDocument(const Problem& p) { return Writer().Document(p); }

}  // namespace plateball::internal::problem_io
