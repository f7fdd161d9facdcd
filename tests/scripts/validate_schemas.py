#!/usr/bin/python3
"""Validates plateball's JSON against its schemas (schemas/, draft 2020-12; docs/output_contract.md).

  /usr/bin/python3 tests/scripts/validate_schemas.py --plateball build/plateball \
      --isoparallel-solve build/isoparallel_solve

Checks, from the repository root:
  1. every schema is a valid draft 2020-12 schema;
  2. every problem file of problems/ (the golden problems) and the test data files validate against
     the input schemas;
  3. every output the tools produce on problems/*.json validates against its command's schema;
  4. every example shown in the README and the pages moved from it (docs/getting_started, tutorials, guide) (a "$ plateball ..." block): the command is run, its JSON
     validates, and every line the README shows is a line of the real output, in order;
  5. negative checks: broken outputs and broken problem files are rejected by the schemas, and the
     broken problem files by the tools' reader too (exit code 3).
Prints the counts; exits 1 on the first class of failure with every failing document named.
Debian's python3-jsonschema (scripts/setup.sh) provides jsonschema.
"""
import argparse
import copy
import glob
import json
import os
import re
import shlex
import subprocess
import sys
import tempfile

try:
    import jsonschema
except ImportError:
    sys.exit("validate_schemas.py: python3-jsonschema is missing (bash scripts/setup.sh installs it)")

ROOT = os.path.normpath(os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", ".."))


class Schemas:
    def __init__(self, directory):
        self.by_path = {}
        store = {}
        for path in sorted(glob.glob(os.path.join(directory, "**", "*.schema.json"), recursive=True)):
            with open(path) as f:
                schema = json.load(f)
            jsonschema.Draft202012Validator.check_schema(schema)
            rel = os.path.relpath(path, directory)
            self.by_path[rel] = schema
            store[schema["$id"]] = schema
        self.store = store

    def validator(self, rel):
        schema = self.by_path[rel]
        resolver = jsonschema.RefResolver(schema["$id"], schema, store=self.store)
        return jsonschema.Draft202012Validator(schema, resolver=resolver)

    def errors(self, rel, doc):
        return [f"{'/'.join(map(str, e.absolute_path)) or '(document)'}: {e.message[:200]}"
                for e in self.validator(rel).iter_errors(doc)]


class Run:
    def __init__(self, args, schemas):
        self.args = args
        self.schemas = schemas
        self.valid = 0
        self.rejected = 0
        self.failures = []

    def expect_valid(self, rel, doc, what):
        errors = self.schemas.errors(rel, doc)
        if errors:
            self.failures.append(f"{what}: not valid against {rel}: " + "; ".join(errors[:3]))
        else:
            self.valid += 1

    def expect_invalid(self, rel, doc, what):
        if self.schemas.errors(rel, doc):
            self.rejected += 1
        else:
            self.failures.append(f"negative check {what}: accepted by {rel}")

    def tool(self, argv, ok_codes=(0,)):
        """Runs a tool from the repository root; returns its standard output."""
        exe = {"plateball": self.args.plateball, "isoparallel_solve": self.args.isoparallel_solve}[argv[0]]
        r = subprocess.run([exe] + argv[1:], cwd=ROOT, capture_output=True, text=True, timeout=300)
        if r.returncode not in ok_codes:
            self.failures.append(f"{' '.join(argv)}: exit {r.returncode}: {r.stderr.strip()[:300]}")
            return None
        return r.stdout

    def output(self, argv, ok_codes=(0,)):
        text = self.tool(argv, ok_codes)
        if text is None:
            return None
        try:
            doc = json.loads(text)
        except json.JSONDecodeError as e:
            self.failures.append(f"{' '.join(argv)}: output is not JSON: {e}")
            return None
        self.expect_valid(f"output/{doc.get('command', '?')}.schema.json", doc, " ".join(argv))
        return doc


def check_inputs(run):
    problems = sorted(glob.glob(os.path.join(ROOT, "problems", "*.json")))
    for path in problems:
        with open(path) as f:
            run.expect_valid(os.path.join("input", "problem.schema.json"), json.load(f), os.path.relpath(path, ROOT))
    with open(os.path.join(ROOT, "tests", "data", "roll_samples.json")) as f:
        run.expect_valid(os.path.join("input", "samples.schema.json"), json.load(f), "tests/data/roll_samples.json")
    return problems


def rig_built(run):
    """`plateball rig` exists only where MuJoCo was found (cmake/PlateballMujoco.cmake)."""
    r = subprocess.run([run.args.plateball, "rig", "--help"], cwd=ROOT, capture_output=True, text=True, timeout=60)
    return r.returncode == 0


def check_rig(run, rel, tmp):
    """The MuJoCo twin's replay (standard output), export (the schedule beside the MJCF) and closed loop
    of a plan."""
    plan = os.path.join(tmp, "rig_plan.json")
    if run.tool(["plateball", "plan", rel, "--impulses", "16", "--out", plan]) is None:
        return
    run.output(["plateball", "rig", "replay", plan])
    mjcf = os.path.join(tmp, "rig.xml")
    if run.output(["plateball", "rig", "export", plan, "--mjcf", mjcf, "--pulse-duration", "0.01"]) is not None:
        with open(os.path.join(tmp, "rig.pulses.json")) as f:
            run.expect_valid("output/rig_export.schema.json", json.load(f), f"plateball rig export {rel}")
    run.output(["plateball", "rig", "replay", plan, "--pulse-duration", "0.01", "--pulse-causal"])
    # The controller's loop with the twin as its plant (a coarse tick: the shape, not the numbers).
    run.output(["plateball", "rig", "loop", rel, "--impulses", "16", "--tick", "1e-3", "--dt", "1e-3",
                "--noise", "impulse_magnitude=0.01"])


def check_tool_outputs(run, problems):
    """Every command that applies to a problem file, on every problem file (small sizes: this is a
    check of the shapes, the numbers are the other tests')."""
    with tempfile.TemporaryDirectory() as tmp:
        for path in problems:
            rel = os.path.relpath(path, ROOT)
            with open(path) as f:
                p = json.load(f)
            run.output(["plateball", "simulate", rel, "--samples", "3"])
            run.output(["plateball", "join", rel, "--targets", "0.05,0;0,0.05"], ok_codes=(0, 4))
            if "reach" in p:
                run.output(["plateball", "reach", rel], ok_codes=(0, 4))
            if "plan" in p:
                run.output(["plateball", "plan", rel], ok_codes=(0, 4))
                run.output(["plateball", "roll", rel])
                explicit = p["plan"].get("partition", {}).get("type") == "explicit"
                if not explicit:
                    run.output(["plateball", "converge", rel, "--impulses", "8,16"], ok_codes=(0, 4))
            if "steer" in p:
                run.output(["plateball", "steer", rel], ok_codes=(0, 4))
            if "plan" in p and "physical" in p.get("ball", {}) and rig_built(run):
                check_rig(run, rel, tmp)
            if "isoparallel" in p:
                out = os.path.join(tmp, "iso.json")
                # 64 starts keep the shooting problems short; the shape does not depend on it.
                if run.tool(["isoparallel_solve", rel, "--starts", "64", "--out", out], ok_codes=(0, 4)) is not None:
                    with open(out) as f:
                        doc = json.load(f)
                    run.expect_valid("output/isoparallel.schema.json", doc, f"isoparallel_solve {rel} --out")
        # The variants of the outputs: timings, --exact, --orientation, the points forms.
        run.output(["plateball", "converge", "problems/circle.json", "--impulses", "8,16", "--timings"])
        run.output(["plateball", "isoparallel", "--exact"])
        # --certify with a budget of one box per piece: the certificate section of an incomplete one.
        run.output(["plateball", "isoparallel", "problems/isoparallel_rotation.json", "--certify", "--certify-budget",
                    "1", "--quiet"], ok_codes=(7,))
        # A complete one (a lower bound, 1 s): every piece closed, its resolved volume a fraction in
        # [0, 1] (a sum of box shares that rounding once took past 1, and to NaN on an empty window).
        run.output(["plateball", "isoparallel", "--goal", "0.2,0", "--goal-orientation",
                    '{"axis_angle": {"axis": [0, 0, 1], "angle": 3}}', "--certify", "--certify-length", "0.25",
                    "--quiet"])
        run.output(["plateball", "roll", "--points", "0,0;1,0.5;2,0", "--orientation", '{"quaternion": [1, 0, 0, 0]}'])
        run.output(["plateball", "roll", "--samples-file", "tests/data/roll_samples.json"])
        # identify: a track that identifies lambda (its fitted_problem is a problem file) and one that does not.
        doc = run.output(["plateball", "identify", "tests/data/identify_track.csv"])
        if doc is not None:
            run.expect_valid(os.path.join("input", "problem.schema.json"), doc["fitted_problem"],
                             "identify tests/data/identify_track.csv: fitted_problem")
        run.output(["plateball", "identify", "tests/data/identify_straight.csv"])
        # A track of eight flights between known impulses: the impulses, delta_psi errors, 14 parameters.
        with open(os.path.join(ROOT, "tests", "data", "identify_impulses_track.csv")) as track:
            impulses = [line for line in track if line.startswith("#")][-1].lstrip("# ").strip()
        run.output(["plateball", "identify", "tests/data/identify_impulses_track.csv", "--impulses", impulses, "--no-profile"])
        run.output(["plateball", "identify", "tests/data/identify_spin_track.csv", "--no-profile"])
        # Measured orientations (the frame fitted: chi, fit.orientation, the orientation in fitted_problem) and body rates.
        doc = run.output(["plateball", "identify", "tests/data/identify_orientation_track.csv", "--no-profile"])
        if doc is not None:
            run.expect_valid(os.path.join("input", "problem.schema.json"), doc["fitted_problem"],
                             "identify tests/data/identify_orientation_track.csv: fitted_problem")
        run.output(["plateball", "identify", "tests/data/identify_imu_track.csv", "--no-profile"])
        run.output(["plateball", "steer", "problems/figure7_exact.json", "--summary-only"])
        run.output(["plateball", "montecarlo", "problems/circle.json", "--impulses", "8", "--trials", "2", "--quiet",
                    "--strategy", "open_loop,feedback", "--noise", "timing=1e-3", "--noise", "pulse_duration=0.05",
                    "--sweep-n", "16", "--timings"])
        # A cell without a completed trial (null distributions) and a sweep row without data (missing).
        run.output(["plateball", "montecarlo", "problems/circle.json", "--impulses", "16", "--trials", "3", "--quiet",
                    "--strategy", "open_loop,feedback", "--sweep-n", "32,64", "--noise",
                    "impulse_magnitude=0.5,impulse_angle=0.5,energy_loss=0.5,timing=0.1,lambda=0.1,observation=0.1"])
        # With a rig section: the nominal plan honoured (the rig record), refused (limits_not_met) and as given.
        run.output(["plateball", "montecarlo", "tests/data/plan_rig_blocked.json", "--trials", "2", "--quiet",
                    "--strategy", "open_loop", "--noise", "none"])
        run.output(["plateball", "montecarlo", "tests/data/plan_rig_path_blocked.json", "--trials", "2", "--quiet"],
                   ok_codes=(4,))
        run.output(["plateball", "montecarlo", "tests/data/plan_rig_blocked.json", "--trials", "2", "--quiet",
                    "--strategy", "open_loop", "--noise", "none", "--rig-check-only"])
        if rig_built(run):
            run.output(["plateball", "rig", "loop", "tests/data/rig_loop_rig.json", "--tick", "1e-3", "--dt", "1e-3"])


def readme_examples(text):
    """(command, shown lines) of every indented "$ COMMAND" block of the README."""
    examples = []
    lines = text.splitlines()
    i = 0
    while i < len(lines):
        m = re.match(r"^    \$ (.*)$", lines[i])
        i += 1
        if not m:
            continue
        shown = []
        while i < len(lines) and lines[i].startswith("    ") and not lines[i].startswith("    $ "):
            shown.append(lines[i][4:])
            i += 1
        examples.append((m.group(1), shown))
    return examples


# The README and the site's pages that hold examples moved from it (getting started, tutorials, the
# user guide): each "$ plateball ..." block is checked wherever it now lives.
EXAMPLE_PAGES = ["README.md", "docs/getting_started/*.md", "docs/tutorials/*.md", "docs/guide/*.md"]


def check_readme(run):
    examples = []
    for pattern in EXAMPLE_PAGES:
        for path in sorted(glob.glob(os.path.join(ROOT, pattern))):
            with open(path) as f:
                examples += readme_examples(f.read())
    for command, shown in examples:
        first = shlex.split(command.split("|")[0])
        first[0] = {"plateball": "plateball", "build/plateball": "plateball"}.get(first[0], first[0])
        if first[0] != "plateball":
            continue
        if first[1:2] == ["rig"] and not rig_built(run):
            continue  # the MuJoCo twin is not in this build (sanitizer builds leave it out)
        doc_text = run.tool(first, ok_codes=(0, 4))
        if doc_text is None:
            continue
        if first[1:2] != ["converge"] or "csv" not in first:
            try:
                doc = json.loads(doc_text)
                run.expect_valid(f"output/{doc['command']}.schema.json", doc, "README: " + command)
            except (json.JSONDecodeError, KeyError) as e:
                run.failures.append(f"README: {command}: output is not a JSON document: {e}")
        shell = re.sub(r"^(build/)?plateball", run.args.plateball, command)
        real = subprocess.run(["bash", "-o", "pipefail", "-c", shell], cwd=ROOT, capture_output=True,
                              text=True, timeout=300).stdout.splitlines()
        at = 0
        for line in shown:
            if line.strip() == "...":
                continue
            while at < len(real) and real[at] != line:
                at += 1
            if at == len(real):
                run.failures.append(f"README: {command}: the shown line {line!r} is not in the output (in order)")
                break
            at += 1
    return len(examples)


def broken_outputs(doc):
    """(what, broken copy) pairs of a valid output document."""
    def edit(f):
        d = copy.deepcopy(doc)
        f(d)
        return d
    out = [("no schema_version", edit(lambda d: d.pop("schema_version"))),
           ("schema_version 2", edit(lambda d: d.update(schema_version=2))),
           ("unknown top-level key", edit(lambda d: d.update(unexpected=1))),
           ("problem without name", edit(lambda d: d["problem"].pop("name"))),
           ("seed negative", edit(lambda d: d.update(seed=-1))),
           ("command of another document", edit(lambda d: d.update(command="roll" if d["command"] != "roll" else "plan")))]
    if "initial" in doc:
        out.append(("flat angles in initial", edit(lambda d: d["initial"].update(theta=d["initial"]["angles"]["theta"]))))
        out.append(("a number as text", edit(lambda d: d["initial"].update(mu="1.0"))))
    if "samples" in doc:
        out.append(("matrix with two rows", edit(lambda d: d["samples"][0].update(orientation=d["samples"][0]["orientation"][:2]))))
    if "status" in doc:
        out.append(("no usable", edit(lambda d: d.pop("usable"))))
        out.append(("status not a word", edit(lambda d: d.update(status="Not Run"))))
    if "rotation_final" in doc:
        out.append(("old name orientation", edit(lambda d: d.update(orientation=d.pop("rotation_final")))))
    return out


def broken_problems():
    base = {"ball": {"lambda": 2}, "initial": {"theta": 1, "phi": 0, "psi": 0, "mu": 1}}
    def edit(f):
        d = copy.deepcopy(base)
        f(d)
        return d
    return [("mu negative", edit(lambda d: d["initial"].update(mu=-1))),
            ("no ball", edit(lambda d: d.pop("ball"))),
            ("unknown key", edit(lambda d: d.update(colour="red"))),
            ("two ball forms", edit(lambda d: d["ball"].update(alpha=1, beta=1))),
            ("lambda out of range", edit(lambda d: d["ball"].update({"lambda": 1e4}))),
            ("two orientation forms", edit(lambda d: d["initial"].update(orientation={"quaternion": [1, 0, 0, 0], "matrix": [[1, 0, 0], [0, 1, 0], [0, 0, 1]]}))),
            ("samples a fraction", edit(lambda d: d.update(simulate={"samples": 2.5}))),
            ("x0 beyond 1e6", edit(lambda d: d["initial"].update(x0=[2e6, 0]))),
            ("explicit partition with n", edit(lambda d: d.update(plan={"path": {"type": "line", "from": [0, 0], "to": [1, 0]},
                                                                        "partition": {"type": "explicit", "n": 4, "taus": [0, 1]}}))),
            ("circle with a scale", edit(lambda d: d.update(plan={"path": {"type": "circle", "center": [0, 0], "radius": 1,
                                                                           "tau_begin": 0, "tau_end": 1, "scale": 2}}))),
            ("steer with 2 impulses", edit(lambda d: d.update(steer={"goal": [1, 1], "impulses": 2}))),
            ("rig plate of negative radius", edit(lambda d: d.update(rig={"plate": {"type": "disk", "center": [0, 0], "radius": -1}}))),
            ("rig obstacle of an unknown type", edit(lambda d: d.update(rig={"obstacles": [{"type": "ring", "center": [0, 0]}]}))),
            ("rig max_force without pulse_duration", edit(lambda d: d.update(rig={"max_force": 10}))),
            ("steer objective unknown", edit(lambda d: d.update(steer={"goal": [1, 1], "objective": "energy"}))),
            ("seed a string", edit(lambda d: d.update(seed="1")))]


def check_negative(run, samples):
    for doc in samples:
        for what, broken in broken_outputs(doc):
            run.expect_invalid(f"output/{doc['command']}.schema.json", broken, f"{doc['command']}: {what}")
    with tempfile.TemporaryDirectory() as tmp:
        for what, broken in broken_problems():
            run.expect_invalid(os.path.join("input", "problem.schema.json"), broken, "problem: " + what)
            # The reader agrees: the tools reject the same file with exit code 3.
            path = os.path.join(tmp, "broken.json")
            with open(path, "w") as f:
                json.dump(broken, f)
            r = subprocess.run([run.args.plateball, "simulate", path, "--samples", "2"], capture_output=True, text=True, timeout=60)
            if r.returncode != 3:
                run.failures.append(f"negative check problem: {what}: the reader gave exit {r.returncode}, not 3")
    for what, broken in [("one point", [[0, 0]]), ("three coordinates", {"points": [[0, 0, 0], [1, 1, 1]]}),
                         ("unknown key", {"points": [[0, 0], [1, 1]], "closed": True})]:
        run.expect_invalid(os.path.join("input", "samples.schema.json"), broken, "samples: " + what)


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--plateball", required=True)
    parser.add_argument("--isoparallel-solve", required=True)
    parser.add_argument("--schemas", default=os.path.join(ROOT, "schemas"))
    args = parser.parse_args()
    args.plateball = os.path.abspath(args.plateball)
    args.isoparallel_solve = os.path.abspath(args.isoparallel_solve)
    schemas = Schemas(args.schemas)
    run = Run(args, schemas)
    problems = check_inputs(run)
    inputs_valid = run.valid
    check_tool_outputs(run, problems)
    outputs_valid = run.valid - inputs_valid
    examples = check_readme(run)
    readme_valid = run.valid - inputs_valid - outputs_valid
    samples = [json.loads(run.tool(argv)) for argv in (
        ["plateball", "simulate", "problems/simulate_example.json", "--samples", "3"],
        ["plateball", "plan", "problems/circle.json", "--summary-only"],
        ["plateball", "join", "--targets", "0.05,0"],
        ["plateball", "roll", "--segment", "--points", "0,0;1.2,1.6"],
        ["plateball", "steer", "problems/figure7_exact.json", "--summary-only"])]
    check_negative(run, samples)
    print(f"schemas: {len(schemas.by_path)}; valid documents: {run.valid} ({inputs_valid} input files, "
          f"{outputs_valid} tool outputs, {readme_valid} README examples of {examples} shown); "
          f"broken documents rejected: {run.rejected}")
    if run.failures:
        print("\n".join("FAIL: " + f for f in run.failures))
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
