"""Shared by the slack-limit tests: run a tool that prints JSON, and compare two documents line by line."""
import json
import subprocess
import sys


def run_json(command):
    """The JSON document the command prints; exits with its stderr when it fails."""
    out = subprocess.run(command, check=False, capture_output=True, text=True)
    if out.returncode != 0:
        sys.exit(f"{' '.join(command[1:])}: exit {out.returncode}: {out.stderr}")
    return json.loads(out.stdout)


def require_identical(free, constrained):
    """Exits naming the first differing line unless both documents print the same; returns the length."""
    a, b = json.dumps(free, indent=2), json.dumps(constrained, indent=2)
    if a != b:
        for i, (x, y) in enumerate(zip(a.splitlines(), b.splitlines())):
            if x != y:
                sys.exit(f"first difference at line {i + 1}:\n  without rig: {x}\n  slack rig:   {y}")
        sys.exit("the documents differ in length")
    return len(a)
