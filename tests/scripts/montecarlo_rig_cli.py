#!/usr/bin/python3
"""`plateball montecarlo` with a rig section plans the nominal path as `plateball plan` does
(PlanImpulsesOnRig): the same rig record, the same refined plan (segments, total time, measured
error, read from `plan`'s own output), and `plateball view` of the study re-runs that plan (its
impulses at plan's times). A plan that cannot meet the limits runs no trial (limits_not_met, exit
4) unless --rig-check-only, which plans the partition as given and runs it. Slack limits change
nothing: the study of problems/plan_rig_circle.json equals that of problems/circle.json once the
records only a rig has are removed. Every output is validated against its schema.

Usage: montecarlo_rig_cli.py PLATEBALL SOURCE_DIR WORKDIR [with-view]. Prints one line per check and "N passed, M failed".
"""
import json
import os
import re
import shutil
import subprocess
import sys

from check_list import Checks


pb, src, work = sys.argv[1], sys.argv[2], sys.argv[3]
WITH_VIEW = sys.argv[4:] == ["with-view"]  # else the view checks are left out
shutil.rmtree(work, ignore_errors=True)
os.makedirs(work)
check = Checks()
BLOCKED = f"{src}/tests/data/plan_rig_blocked.json"  # refined from 64 to 128 segments
PATH_BLOCKED = f"{src}/tests/data/plan_rig_path_blocked.json"  # the path itself enters the obstacle
STUDY = ["--trials", "2", "--strategy", "open_loop", "--noise", "none", "--quiet"]
TIME_TOLERANCE = 1e-12  # the page's impulse times are the plan's, written and read back as JSON doubles


def run(*args):
    r = subprocess.run([pb, *args], capture_output=True, text=True, timeout=120, cwd=src)
    doc = None
    if r.stdout.strip():
        try:
            doc = json.loads(r.stdout)
        except json.JSONDecodeError:
            pass
    return r.returncode, doc, r.stderr


sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from validate_schemas import Schemas  # noqa: E402 (the schemas with their $id store)

SCHEMAS = Schemas(f"{src}/schemas")


def valid(doc, command):
    errors = SCHEMAS.errors(f"output/{command}.schema.json", doc)
    return not errors, "; ".join(errors[:3])


def page_data(html):
    """The page's data: the JSON literal of `const PLATEBALL_DATA = ...;`."""
    text = open(html, encoding="utf-8").read()
    return json.loads(re.search(r"<script>const PLATEBALL_DATA = (.*);</script>", text).group(1))


# ---- honoured: the same refined plan as `plan`
code_p, plan, _ = run("plan", BLOCKED, "--summary-only")
code_m, mc, err = run("montecarlo", BLOCKED, *STUDY, "--out", "-")
check(code_p == 0 and code_m == 0, "plan and montecarlo exit 0", f"{code_p}, {code_m}: {err.strip()}")
if plan and mc:
    check(mc.get("rig") == plan.get("rig"), "montecarlo's rig record equals plan's")
    check(plan["rig"]["points_added"] == 64 and mc["options"]["impulses"] == plan["partition"]["segments"] == 128,
          "the study runs plan's refined partition (128 segments)", str(mc["options"]["impulses"]))
    nominal = mc["nominal"][0]
    check(nominal["total_time"] == plan["total_time"] and nominal["measured_error"] == plan["measured_error"],
          "the nominal plan's total time and measured error are plan's",
          f"{nominal['total_time']} vs {plan['total_time']}")
    check(mc["status"] == "completed" and "rig limits met (active: obstacles[0]" in mc["report"],
          "the study completed, its report says the limits are met", mc["report"][-120:])
    ok, why = valid(mc, "montecarlo")
    check(ok, "honoured study validates against montecarlo.schema.json", why)
    if WITH_VIEW:  # `view` is built where three.js is (web/CMakeLists.txt)
        # The view re-runs the study's nominal plan: its impulses are plan's, at plan's times.
        with open(f"{work}/mc.json", "w") as f:
            json.dump(mc, f)
        code_v, _, err_v = run("view", f"{work}/mc.json", "--html", f"{work}/mc.html")
        check(code_v == 0, "view of the honoured study exits 0", err_v.strip())
        if code_v == 0:
            data = page_data(f"{work}/mc.html")
            _, full, _ = run("plan", BLOCKED)
            times = [s["t_impulse"] for s in full["steps"]]
            shown = [i["t"] for i in data["impulses"]]
            check(len(shown) == len(times) and all(abs(a - b) <= TIME_TOLERANCE for a, b in zip(shown, times)),
                  "the view's impulses are plan's 128, at plan's times", f"{len(shown)} impulses")
            check(any(label == "rig" and value.startswith("limits met (honour)") for label, value in data["facts"]),
                  "the view says the rig's limits are met")

# ---- limits not met: no trial
code, doc, err = run("montecarlo", PATH_BLOCKED, *STUDY)
check(code == 4, "a plan through the obstacle: exit 4", f"{code}: {err.strip()}")
if doc:
    check(doc["status"] == "limits_not_met" and doc["usable"] is False and doc["results"] == []
          and "obstacles[0]" in doc["rig"]["blocking"] and "the path itself enters obstacles[0]" in doc["message"],
          "status limits_not_met, no results, obstacles[0] blocking", doc["report"][:160])
    ok, why = valid(doc, "montecarlo")
    check(ok, "limits_not_met output validates against montecarlo.schema.json", why)
    if WITH_VIEW:  # `view` is built where three.js is (web/CMakeLists.txt)
        # The view shows the refused plan and re-runs no trial (the study ran none).
        with open(f"{work}/refused.json", "w") as f:
            json.dump(doc, f)
        code_v, _, err_v = run("view", f"{work}/refused.json", "--html", f"{work}/refused.html")
        check(code_v == 0, "view of the refused study exits 0", err_v.strip())
        if code_v == 0:
            data = page_data(f"{work}/refused.html")
            facts = dict(data["facts"])
            check(facts.get("trials re-run", "").startswith("none") and not data.get("spread"),
                  "the view of the refused study re-runs no trial", facts.get("trials re-run", "(missing)"))

# ---- --rig-check-only: the partition as given, checked, run all the same
code, doc, err = run("montecarlo", BLOCKED, *STUDY, "--rig-check-only")
check(code == 0, "--rig-check-only: exit 0", f"{code}: {err.strip()}")
if doc:
    check(doc["rig"]["mode"] == "check" and doc["rig"]["check"]["passed"] is False
          and doc["options"]["impulses"] == 64 and doc["status"] == "completed"
          and "rig limits NOT met (--rig-check-only" in doc["report"],
          "--rig-check-only runs the 64 segments as given and says the limits are not met", doc["report"][-160:])
    ok, why = valid(doc, "montecarlo")
    check(ok, "--rig-check-only output validates against montecarlo.schema.json", why)

# ---- the sweep varies n, which the refinement changes: refused
code, _, err = run("montecarlo", BLOCKED, *STUDY, "--sweep-n", "32")
check(code == 3 and "--sweep-n: value 32: with a rig section" in err, "--sweep-n with a rig: exit 3", err.strip())

# ---- slack limits: the study of the circle without a rig, byte for byte
_, free, _ = run("montecarlo", f"{src}/problems/circle.json", *STUDY)
_, slack, _ = run("montecarlo", f"{src}/problems/plan_rig_circle.json", *STUDY)
if free and slack:
    rig = slack.pop("rig", None)
    for d in (free, slack):
        d.pop("problem", None)
    suffix = "; rig limits met"
    report_ok = slack["report"].endswith(suffix)
    slack["report"] = slack["report"][: -len(suffix)] if report_ok else slack["report"]
    check(rig is not None and rig["points_added"] == 0 and rig["points_slid"] == 0 and report_ok
          and "rig" not in free, "slack limits: a rig record that refined and slid nothing")
    check(json.dumps(free, indent=2) == json.dumps(slack, indent=2), "slack limits: the same study as without them")
else:
    check(False, "slack limits: both studies ran")

check.finish()
