#!/usr/bin/env python3
"""Rerun the certificates that problem files claim, and check them against the files' answers.

    scripts/certify_problems.py [--solver PATH] [--jobs N] [--out-dir DIR] [FILE ...] [-- SOLVER ARGS]

Each FILE runs `isoparallel_solve FILE --certify --threads 1 --quiet --out DIR/NAME.json` plus any
arguments after `--` (e.g. `-- --certify-cap 1.5`), N runs at a time in the order given (give the
longest first), each at its own thread so that its CPU time is its own. Without FILEs: the five
problem files whose shortest path is certified (docs/paper_notes.md, "General targets"), longest
first; together about 212 CPU minutes. The report is a Markdown table: the certificate's status,
the solutions it proved, its boxes and pieces, the run's CPU and wall minutes, and whether it agrees
with the file's `expected.shortest_length`: every proved solution at least that long (within the
tolerance), and one of that length when it lies under the cap.

Exit status: 0 when every certificate is complete and agrees, 1 otherwise, 2 for bad usage.
The solver's JSON (NAME.certificate.json) and its standard output and error (NAME.log) stay in DIR (default: a new
temporary directory, named at the end).
"""
import argparse
import json
import os
import shutil
import sys
import tempfile
import time

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
DEFAULT_FILES = ["problems/isoparallel_t9.json", "problems/isoparallel_t7.json", "problems/isoparallel_t3.json",
                 "problems/isoparallel_rotation.json", "problems/isoparallel_t10.json"]


def parse_args(argv):
    solver_args = []
    if "--" in argv:
        cut = argv.index("--")
        argv, solver_args = argv[:cut], argv[cut + 1:]
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("files", nargs="*", help="problem files (default: the five certified ones)")
    parser.add_argument("--solver", help="isoparallel_solve (default: build/isoparallel_solve, else PATH)")
    parser.add_argument("--jobs", type=int, default=os.cpu_count() or 1, help="runs at a time (default: CPUs)")
    parser.add_argument("--out-dir", help="where the JSON and logs go (default: a new temporary directory)")
    args = parser.parse_args(argv)
    args.solver_args = solver_args
    if args.jobs < 1:
        parser.error(f"--jobs: value {args.jobs}: must be at least 1")
    if not args.files:
        args.files = [os.path.join(ROOT, f) for f in DEFAULT_FILES]
    for f in args.files:
        if not os.path.isfile(f):
            parser.error(f"problem file {f}: not found")
    names = [os.path.splitext(os.path.basename(f))[0] for f in args.files]
    if len(set(names)) != len(names):
        parser.error("problem files: two share a name, so their outputs would collide")
    args.solver = args.solver or next((p for p in [os.path.join(ROOT, "build", "isoparallel_solve"),
                                                   shutil.which("isoparallel_solve")] if p and os.path.isfile(p)), None)
    if not args.solver or not os.access(args.solver, os.X_OK):
        parser.error(f"--solver: {args.solver or 'isoparallel_solve'}: not an executable (build it or give --solver)")
    return args


def start(args, path, out_dir):
    name = os.path.splitext(os.path.basename(path))[0]
    out, log = os.path.join(out_dir, name + ".certificate.json"), os.path.join(out_dir, name + ".log")
    argv = [args.solver, path, "--certify", "--threads", "1", "--quiet", "--out", out] + args.solver_args
    actions = [(os.POSIX_SPAWN_OPEN, 1, log, os.O_WRONLY | os.O_CREAT | os.O_TRUNC, 0o644),
               (os.POSIX_SPAWN_DUP2, 1, 2)]
    pid = os.posix_spawn(args.solver, argv, os.environ, file_actions=actions)
    return pid, {"file": path, "out": out, "log": log, "start": time.monotonic()}


def last_line(path):
    with open(path, errors="replace") as f:
        lines = [l.strip() for l in f if l.strip()]
    return lines[-1] if lines else "(no output)"


def read_problem(path):
    """The problem file's JSON, or {} when it is not JSON (the solver's log then names the error)."""
    try:
        with open(path) as f:
            return json.load(f)
    except ValueError:
        return {}


def judge(run, problem):
    """The row's fields and whether the certificate is complete and agrees with the file."""
    if run["code"] not in (0, 7) or not os.path.isfile(run["out"]):
        return {"status": f"failed (exit {run['code']}): {last_line(run['log'])}"}, False
    with open(run["out"]) as f:
        cert = json.load(f).get("certificate")
    if cert is None:
        return {"status": "no certificate (an identity target needs none)"}, False
    lengths = sorted(s["length"] for s in cert["solutions"])
    row = {"status": cert["status"], "lengths": lengths, "boxes": cert["boxes"], "cap": cert["length_cap"],
           "closed": sum(p["closed"] for p in cert["pieces"]), "pieces": len(cert["pieces"])}
    expected = problem.get("expected", {}).get("shortest_length")
    if expected is None:
        row["check"] = "no expected value"
        return row, cert["complete"]
    value, tol = expected["value"], expected.get("tolerance", 1e-7)
    shorter = [l for l in lengths if l < value - tol]
    if shorter:
        row["check"] = f"DISAGREES: proved {shorter[0]:.9f} < expected {value}"
    elif value <= cert["length_cap"] and not any(abs(l - value) <= tol for l in lengths):
        row["check"] = f"DISAGREES: none of length {value} up to {cert['length_cap']:.9g}"
    else:
        row["check"] = "agrees" if value <= cert["length_cap"] else f"agrees (none up to {cert['length_cap']:.9g})"
    return row, cert["complete"] and row["check"].startswith("agrees")


def shown(path):
    """The path from the repository's root when it lies inside it, else as given."""
    inside = os.path.relpath(os.path.abspath(path), ROOT)
    return path if inside.startswith("..") else inside


def report(runs):
    print("| problem | certificate | proved solutions | boxes | pieces closed | CPU min | wall min | expected shortest |")
    print("|---|---|---|---|---|---|---|---|")
    for run in runs:
        row = run["row"]
        lengths = ", ".join(f"{l:.9f}" for l in row.get("lengths", [])) or "none"
        boxes = f"{row['boxes']:,}" if "boxes" in row else "-"
        pieces = f"{row['closed']}/{row['pieces']}" if "pieces" in row else "-"
        print(f"| {shown(run['file'])} | {row['status']} | {lengths} | {boxes} | {pieces} | "
              f"{run['cpu'] / 60:.1f} | {run['wall'] / 60:.1f} | {row.get('check', '-')} |")


def main(argv):
    args = parse_args(argv)
    out_dir = args.out_dir or tempfile.mkdtemp(prefix="certify_problems_")
    os.makedirs(out_dir, exist_ok=True)
    pending, running, done = list(args.files), {}, []
    while pending or running:
        while pending and len(running) < args.jobs:
            pid, run = start(args, pending.pop(0), out_dir)
            running[pid] = run
            print(f"certify_problems: started {shown(run['file'])}", file=sys.stderr, flush=True)
        pid, status, usage = os.wait4(-1, 0)
        run = running.pop(pid)
        run.update(code=os.waitstatus_to_exitcode(status), cpu=usage.ru_utime + usage.ru_stime,
                   wall=time.monotonic() - run["start"])
        run["row"], run["ok"] = judge(run, read_problem(run["file"]))
        print(f"certify_problems: {shown(run['file'])}: {run['row']['status']}, {run['cpu'] / 60:.1f} CPU min",
              file=sys.stderr, flush=True)
        done.append(run)
    done.sort(key=lambda r: args.files.index(r["file"]))
    report(done)
    print(f"\noutputs and logs: {out_dir}")
    return 0 if all(r["ok"] for r in done) else 1


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
