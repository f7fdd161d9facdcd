// `plateball isoparallel`: the isoparallel problem (section 2.2) and its impulsive approximation
// (Figure 7), the same code as `isoparallel_solve` (tools/common/isoparallel_command.h); the JSON
// goes to standard output (or --out), the report to standard error.
#include <memory>

#include "common/command_registry.h"
#include "common/isoparallel_command.h"

namespace plateball::tools {
namespace {

std::function<int()> SetupIsoparallel(CLI::App& sub) {
  auto o = std::make_shared<IsoparallelCliOptions>();
  o->program = "plateball isoparallel";
  o->tool = "plateball";
  o->json_to_stdout = true;
  AddIsoparallelOptions(sub, *o);
  sub.footer(
      "Finds every shortest path from isoparallel.start to isoparallel.goal whose rolling turns\n"
      "start_orientation into goal_orientation (up to 3x the shortest), then follows the shortest with\n"
      "--impulses energy-preserving impulses. Without a problem file: the built-in Figure 7 problem.\n"
      "The initial section gives psi and mu; --theta, --phi, --x0, --orientation are not used (the start\n"
      "orientation fixes the axis). Prints JSON (docs/output_contract.md); the report goes to standard error.\n"
      "Example: plateball isoparallel problems/figure7.json --impulses 24 --svg figure7.svg\n"
      "         plateball isoparallel --goal 2,1 --goal-orientation '{\"axis_angle\": {\"axis\": [0,0,1], \"angle\": "
      "1.2}}'\n"
      "Exit codes: 0 solved and planned, 2 usage, 3 invalid input, 4 no solution (or the plan failed),\n"
      "5 unreadable/unwritable file.");
  return [o] { return RunIsoparallel(*o); };
}

const CommandRegistrar kRegistrar{
    {"isoparallel",
     "the isoparallel problem: shortest path for a prescribed reorientation, and its impulses (Figure 7)",
     SetupIsoparallel}};

}  // namespace
}  // namespace plateball::tools
