#!/usr/bin/python3
"""Slack rig limits change nothing in the fewest-impulse search: `plateball steer` on
problems/figure7_fewest.json and on tests/data/figure7_fewest_slack_rig.json (the same problem on a
rig whose limits every arrival meets) write the same JSON, byte for byte, once the records that
only a rig has ("rig" at the top and in each Pareto row) and the problem's name and file are removed.
Usage: fewest_slack_rig.py PLATEBALL SOURCE_DIR"""
import sys

from json_compare import require_identical, run_json


def run(plateball, problem):
    return run_json([plateball, "steer", problem, "--max-impulses", "3"])


def strip(doc):
    doc.pop("problem", None)
    rig = doc.pop("rig", None)
    for row in doc["pareto"]:
        row.pop("rig", None)
    return rig


def main():
    plateball, src = sys.argv[1], sys.argv[2]
    free = run(plateball, f"{src}/problems/figure7_fewest.json")
    slack = run(plateball, f"{src}/tests/data/figure7_fewest_slack_rig.json")
    rig = strip(slack)
    if strip(free) is not None or rig is None or rig["constrained_solves"] != 0:
        sys.exit(f"expected a rig record only with the rig and no constrained solve: {rig}")
    length = require_identical(free, slack)
    print(f"fewest search: identical with slack rig limits ({length} characters, fewest {free['fewest_impulses']})")


if __name__ == "__main__":
    main()
