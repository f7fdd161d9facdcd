#!/usr/bin/env python3
"""ctest: scripts/certify_problems.py on a lower-bound certificate (tests/data/isoparallel_lower_bound.json
with `-- --certify-length 0.25`: 0.2 away and 3 rad about e3, no path is shorter than 3, so the
certificate closes with no solution in 584,592 boxes): exit 0 and its row when it is complete and
agrees with the file's expected shortest; exit 1 when the budget leaves it incomplete, or when the
file expects a shortest path (0.24) under the cap that the certificate proved empty; exit 2 naming
a missing file."""
import json
import os
import subprocess
import sys
import tempfile

SCRIPT = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "scripts", "certify_problems.py")
DATA = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "data", "isoparallel_lower_bound.json")


def run(solver, files, out_dir, *solver_args, jobs=1):
    argv = [sys.executable, SCRIPT, "--solver", solver, "--jobs", str(jobs), "--out-dir", out_dir, *files]
    p = subprocess.run(argv + ["--", "--certify-length", "0.25", *solver_args], capture_output=True, text=True)
    return p.returncode, p.stdout + p.stderr


def expect(condition, what, output):
    if not condition:
        print(f"FAIL: {what}\n{output}")
        sys.exit(1)


def main():
    solver = sys.argv[1]
    with tempfile.TemporaryDirectory() as tmp:
        code, out = run(solver, [DATA], tmp)
        expect(code == 0, f"a complete, agreeing certificate exits 0 (got {code})", out)
        expect("| complete | none | 584,592 | 10/10 |" in out and "agrees (none up to 0.25)" in out,
               "the row names the certificate, its boxes and the check", out)
        with open(DATA) as f:
            problem = json.load(f)
        problem["expected"]["shortest_length"]["value"] = 0.24
        wrong = os.path.join(tmp, "expects_0_24.json")
        with open(wrong, "w") as f:
            json.dump(problem, f)
        code, out = run(solver, [wrong, DATA], tmp, jobs=2)
        expect(code == 1, f"a certificate that contradicts the file exits 1 (got {code})", out)
        expect("DISAGREES: none of length 0.24 up to 0.25" in out and out.count("| complete |") == 2,
               "both rows, the contradiction named", out)
        code, out = run(solver, [DATA], tmp, "--certify-budget", "1")
        expect(code == 1 and "| incomplete |" in out, f"an incomplete certificate exits 1 (got {code})", out)
        code, out = run(solver, [os.path.join(tmp, "missing.json")], tmp)
        expect(code == 2 and "missing.json: not found" in out, f"a missing file exits 2 (got {code})", out)
    print("certify_problems.py: 4 runs as expected")


if __name__ == "__main__":
    main()
