#!/usr/bin/python3
"""Slack rig limits change nothing in the path-following plan: `plateball plan` on problems/circle.json
and on problems/plan_rig_circle.json (the same circle on a rig whose limits the plan meets: the
planner honours them by default) write the same JSON, byte for byte, once the records that only a
rig has are removed: the "rig" section, the report's "; rig limits met" and the problem's name and
file. The rig record must say that nothing was refined or slid.
Usage: plan_slack_rig.py PLATEBALL SOURCE_DIR"""
import sys

from json_compare import require_identical, run_json

RIG_SUFFIX = "; rig limits met"


def run(plateball, problem):
    return run_json([plateball, "plan", problem])


def main():
    plateball, src = sys.argv[1], sys.argv[2]
    free = run(plateball, f"{src}/problems/circle.json")
    slack = run(plateball, f"{src}/problems/plan_rig_circle.json")
    for doc in (free, slack):
        doc.pop("problem", None)
    rig = slack.pop("rig", None)
    if "rig" in free or rig is None:
        sys.exit(f"expected a rig record only with the rig: {rig}")
    if (rig["mode"], rig["points_added"], rig["points_slid"], rig["active"], rig["blocking"]) != ("honour", 0, 0, [], []):
        sys.exit(f"slack limits refined or slid the plan: { {k: v for k, v in rig.items() if k != 'check'} }")
    if not slack["report"].endswith(RIG_SUFFIX):
        sys.exit(f"the report does not say the limits are met: {slack['report']}")
    slack["report"] = slack["report"][: -len(RIG_SUFFIX)]
    length = require_identical(free, slack)
    print(f"plan: identical with slack rig limits ({length} characters, {free['partition']['segments']} segments)")


if __name__ == "__main__":
    main()
