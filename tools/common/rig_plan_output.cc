#include "common/rig_plan_output.h"

#include <optional>
#include <vector>

#include "common/exact_output.h"
#include "plateball/plan_rig_check.h"
#include "plateball/rig_planner.h"

namespace plateball::tools {
namespace {

// The record of a plan that honoured the rig (PlanImpulsesOnRig).
Json HonouredRigJson(const RigPlanSummary& r) {
  return Json{{"mode", "honour"},
              {"segments_initial", r.segments_initial},
              {"points_added", r.points_added},
              {"points_removed", r.points_removed},
              {"points_slid", r.points_slid},
              {"rounds", r.rounds},
              {"active", r.active},
              {"blocking", r.blocking},
              {"check", RigCheckJson(r.check)}};
}

// " (active: obstacles[0] tick; 64 partition points added, 127 slid onto the tick grid)" (and "N
// removed, " before the slid when the coarsening merged flights), or
// nothing when no limit shaped the plan.
std::string ActiveNote(const RigPlanSummary& r) {
  if (r.active.empty()) return "";
  std::string note = " (active:";
  for (const std::string& a : r.active) note += " " + a;
  note += "; " + std::to_string(r.points_added) + " partition points added, ";
  if (r.points_removed > 0) note += std::to_string(r.points_removed) + " removed, ";
  return note + std::to_string(r.points_slid) + " slid onto the tick grid)";
}

}  // namespace

RigNominal PlanOnRig(const Problem& p, const PlanSetup& setup, bool check_only) {
  RigNominal out;
  if (p.rig.Empty() || check_only) {
    out.plan = PlanImpulses(setup.problem, setup.options);
    if (p.rig.Empty() || !out.plan.IsSolutionUsable()) return out;
    const RigCheck check = CheckPlanRigLimits(setup.problem, out.plan, p.rig, p.physical);
    out.rig = Json{{"mode", "check"}, {"check", RigCheckJson(check)}};
    out.limits_met = check.passed;
    if (!check.passed) {
      out.message = "the plan exceeds the rig's limits (problem file's rig section): ";
      for (std::size_t i = 0; i < check.violations.size(); ++i) out.message += (i ? "; " : "") + check.violations[i];
    }
    return out;
  }
  RigPlanSummary honoured = PlanImpulsesOnRig(setup.problem, p.rig, p.physical, setup.options);
  out.plan = std::move(honoured.plan);
  if (!out.plan.IsSolutionUsable()) return out;
  out.rig = HonouredRigJson(honoured);
  out.limits_met = honoured.IsSolutionUsable();
  if (out.limits_met)
    out.note = ActiveNote(honoured);
  else
    out.message = "the plan cannot meet the rig's limits (problem file's rig section): " + honoured.message;
  return out;
}

bool AddRigRecord(const RigNominal& r, Json* doc) {
  if (r.rig.is_null()) return true;
  (*doc)["rig"] = r.rig;
  if (r.limits_met) {
    (*doc)["report"] = (*doc)["report"].get<std::string>() + "; rig limits met" + r.note;
    return true;
  }
  (*doc)["status"] = "limits_not_met";
  (*doc)["usable"] = false;
  (*doc)["message"] = r.message;
  (*doc)["report"] = "limits_not_met: " + r.message;
  return false;
}

}  // namespace plateball::tools
