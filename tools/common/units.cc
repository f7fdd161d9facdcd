#include "common/units.h"

#include <cmath>
#include <map>
#include <stdexcept>
#include <string>

#include "common/invalid_input.h"
#include "common/number_format.h"

namespace plateball::tools {
namespace {

enum class Dimension { kTime, kLength, kVelocity };

const std::map<std::string, Dimension>& Dimensions() {
  static const std::map<std::string, Dimension> kTable = {{"t", Dimension::kTime},
                                                          {"t_impulse", Dimension::kTime},
                                                          {"duration", Dimension::kTime},
                                                          {"total_time", Dimension::kTime},
                                                          {"period", Dimension::kTime},
                                                          {"t_end", Dimension::kTime},
                                                          {"horizon", Dimension::kTime},
                                                          {"x", Dimension::kLength},
                                                          {"x0", Dimension::kLength},
                                                          {"x_end", Dimension::kLength},
                                                          {"p", Dimension::kLength},
                                                          {"p_begin", Dimension::kLength},
                                                          {"p_end", Dimension::kLength},
                                                          {"target", Dimension::kLength},
                                                          {"goal", Dimension::kLength},
                                                          {"start", Dimension::kLength},
                                                          {"length", Dimension::kLength},
                                                          {"distance", Dimension::kLength},
                                                          {"position_error", Dimension::kLength},
                                                          {"drift_per_period", Dimension::kLength},
                                                          {"plate_velocity_change", Dimension::kVelocity},
                                                          {"mean_velocity", Dimension::kVelocity}};
  return kTable;
}

// A number or an array of numbers scaled by `factor`; null for anything else.
Json Scaled(const Json& v, double factor) {
  if (v.is_number()) return v.get<double>() * factor;
  if (!v.is_array() || v.empty()) return nullptr;
  Json out = Json::array();
  for (const Json& e : v) {
    if (!e.is_number()) return nullptr;
    out.push_back(e.get<double>() * factor);
  }
  return out;
}

void AddSi(Json* j, const PhysicalScales& s) {
  if (j->is_array()) {
    for (Json& e : *j) AddSi(&e, s);
    return;
  }
  if (!j->is_object()) return;
  Json si = Json::object();
  for (auto it = j->begin(); it != j->end(); ++it) {
    if (it.key() == "samples" || it.key() == "units" || it.key() == "si") continue;
    const auto d = Dimensions().find(it.key());
    if (d != Dimensions().end()) {
      const double f = d->second == Dimension::kTime     ? s.time_s
                       : d->second == Dimension::kLength ? s.length_m
                                                         : s.velocity_m_per_s;
      if (Json v = Scaled(it.value(), f); !v.is_null()) si[it.key()] = std::move(v);
    }
    AddSi(&it.value(), s);
  }
  if (!si.empty()) (*j)["si"] = std::move(si);
}

}  // namespace

namespace {

// The kinetic energy mu (I1 + M r^2) / 2 in joules; refused (exit 3, naming initial.mu) when it overflows.
double KineticEnergyOf(const Problem& problem) {
  const PhysicalParameters& q = *problem.physical;
  const double energy = 0.5 * problem.mu * (q.inertia_1 + q.EffectiveMass() * q.radius * q.radius);  // docs/units.md
  if (!std::isfinite(energy))
    ThrowInvalidInput("initial.mu",
                      FormatNumber(problem.mu),
                      "with ball.physical the kinetic energy mu (I1 + M r^2) / 2 = " + FormatNumber(energy) +
                          " J is not finite; reduce initial.mu or the inertias");
  return energy;
}

}  // namespace

std::optional<PhysicalScales> ScalesOf(const Problem& problem) {
  if (!problem.physical) return std::nullopt;
  PhysicalScales s;
  s.length_m = problem.physical->radius;
  s.velocity_m_per_s = problem.physical->radius;
  return s;
}

void AddPhysicalUnits(const Problem& problem, Json* doc) {
  const std::optional<PhysicalScales> s = ScalesOf(problem);
  if (!s) return;
  AddSi(doc, *s);
  const PhysicalParameters& q = *problem.physical;
  (*doc)["units"] = Json{
      {"physical",
       Json{{"inertia_1", q.inertia_1},
            {"inertia_3", q.inertia_3},
            {"ball_mass", q.ball_mass},
            {"radius", q.radius},
            {"plate_mass", q.plate_mass}}},
      {"normalisation", "I1 = 1, r = 1, time unchanged (section 2.1); mu in s^-2; see docs/units.md"},
      {"scales", Json{{"length_m", s->length_m}, {"time_s", s->time_s}, {"velocity_m_per_s", s->velocity_m_per_s}}},
      {"kinetic_energy_J", KineticEnergyOf(problem)}};
}

}  // namespace plateball::tools
