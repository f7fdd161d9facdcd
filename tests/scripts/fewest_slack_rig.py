#!/usr/bin/python3
"""Slack rig limits change nothing in the fewest-impulse search: `plateball steer` on
problems/figure7_fewest.json and on tests/data/figure7_fewest_slack_rig.json (the same problem on a
rig whose limits every arrival meets) write the same JSON, byte for byte, once the records that
only a rig has ("rig" at the top and in each Pareto row) and the problem's name and file are removed.
Usage: fewest_slack_rig.py PLATEBALL SOURCE_DIR"""
import json
import subprocess
import sys


def run(plateball, problem):
    out = subprocess.run([plateball, "steer", problem, "--max-impulses", "3"], check=False,
                         capture_output=True, text=True)
    if out.returncode != 0:
        sys.exit(f"{problem}: exit {out.returncode}: {out.stderr}")
    return json.loads(out.stdout)


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
    a, b = json.dumps(free, indent=2), json.dumps(slack, indent=2)
    if a != b:
        for i, (x, y) in enumerate(zip(a.splitlines(), b.splitlines())):
            if x != y:
                sys.exit(f"first difference at line {i + 1}:\n  without rig: {x}\n  slack rig:   {y}")
        sys.exit("the documents differ in length")
    print(f"fewest search: identical with slack rig limits ({len(a)} characters, fewest {free['fewest_impulses']})")


if __name__ == "__main__":
    main()
