#!/usr/bin/env python3
"""`plateball view` of steer results with a rig: the page carries the rig the problem file sets
(shapes in ball radii, also when the file gives metres), the stroke's origin x0 and the verdict of
the result's replay check (margins, active and blocking limits) as the result reports them; strings
of the result stay data (escaped); a malformed rig object is refused naming the field.

Usage: view_rig_cli.py PLATEBALL SOURCE_DIR WORKDIR. Prints one line per check and "N passed, M failed".
"""
import copy
import json
import math
import os
import re
import shutil
import subprocess
import sys

from check_list import Checks

pb, src, work = sys.argv[1], sys.argv[2], sys.argv[3]
shutil.rmtree(work, ignore_errors=True)
os.makedirs(work)
check = Checks()


def run(*args):
    r = subprocess.run([pb, *args], capture_output=True, text=True, timeout=120)
    return r.returncode, r.stderr


def page_data(html):
    """The page's data: the JSON literal of `const PLATEBALL_DATA = ...;` (the escapes are JSON's)."""
    text = open(html, encoding="utf-8").read()
    m = re.search(r"<script>const PLATEBALL_DATA = (.*);</script>", text)
    return text, json.loads(m.group(1))


def shape_in_radii(shape, scale):
    """A shape of the problem file as the page carries it: rectangles as their four corners."""
    if shape["type"] == "disk":
        return {"type": "disk", "center": [scale * c for c in shape["center"]], "radius": scale * shape["radius"]}
    if shape["type"] == "rectangle":
        (x0, y0), (x1, y1) = shape["min"], shape["max"]
        vertices = [[x0, y0], [x1, y0], [x1, y1], [x0, y1]]
    else:
        vertices = shape["vertices"]
    return {"type": "polygon", "vertices": [[scale * c for c in v] for v in vertices]}


def close(a, b, tol):
    if isinstance(a, dict):
        return isinstance(b, dict) and a.keys() == b.keys() and all(close(a[k], b[k], tol) for k in a)
    if isinstance(a, list):
        return isinstance(b, list) and len(a) == len(b) and all(close(x, y, tol) for x, y in zip(a, b))
    if isinstance(a, float) or isinstance(b, float):
        return abs(a - b) <= tol * max(1.0, abs(a))
    return a == b


# Lengths read in metres become radii by one division (rig_reader.cc): to a few ulps.
LENGTH_TOL = 1e-14

# ---------------------------------------------------------------- every kind of shape and the stroke
shapes = os.path.join(src, "tests/data/view_rig_shapes.json")
problem = json.load(open(shapes))
code, err = run("steer", shapes, "--out", f"{work}/shapes.json", "--quiet")
check(code == 0, "steer of the rig problem arrives", err.strip())
code, err = run("view", f"{work}/shapes.json", "--html", f"{work}/shapes.html")
check(code == 0, "view of the rig result", err.strip())
result = json.load(open(f"{work}/shapes.json"))
_, data = page_data(f"{work}/shapes.html")
rig, file_rig = data.get("rig", {}), problem["rig"]
expected = {"plate": shape_in_radii(file_rig["plate"], 1.0),
            "obstacles": [shape_in_radii(o, 1.0) for o in file_rig["obstacles"]],
            "clearance": file_rig["clearance"], "stroke": file_rig["stroke"], "x0": problem["initial"]["x0"]}
check(close(expected, {k: rig.get(k) for k in expected}, 0.0),
      "the page's rig is the problem file's plate (polygon), obstacles (disk, polygon), clearance, stroke and x0",
      json.dumps({k: rig.get(k) for k in expected}))
verdict = result["rig"]
page_check = rig.get("check", {})
check(page_check.get("passed") is verdict["check"]["passed"] is True
      and page_check.get("samples") == verdict["check"]["samples"]
      and dict(page_check.get("margins", [])) == verdict["check"]["margins"]
      and len(page_check.get("margins", [])) == 5
      and page_check.get("active") == verdict["active"] and page_check.get("blocking") == verdict["blocking"]
      and page_check.get("violations") == [] and page_check.get("objective") == verdict["objective"],
      "the page's verdict is the result's replay check: passed, samples, the five margins, active and blocking limits",
      json.dumps(page_check))

# ---------------------------------------------------------------- metres
# The same rig in metres with a physical ball of radius 0.02 m: the page draws it in ball radii.
r = 0.02
physical = copy.deepcopy(problem)
physical["ball"] = {"physical": {"inertia_1": 1.6e-05, "inertia_3": 1.2e-05, "ball_mass": 0.1, "radius": r, "plate_mass": 0.05}}
physical["rig"] = {"length_unit": "m",
                   "plate": {"type": "rectangle", "min": [-2.5 * r, -2.5 * r], "max": [5.5 * r, 5.5 * r]},
                   "obstacles": [{"type": "disk", "center": [0.0, 1.45 * r], "radius": 0.25 * r}],
                   "clearance": 0.1 * r, "stroke": [9.0 * r, 8.0 * r]}
json.dump(physical, open(f"{work}/physical.json", "w"))
run("steer", f"{work}/physical.json", "--out", f"{work}/physical_result.json", "--quiet")
code, err = run("view", f"{work}/physical_result.json", "--html", f"{work}/physical.html")
_, data = page_data(f"{work}/physical.html") if code == 0 else (None, {})
rig = data.get("rig", {})
expected = {"plate": shape_in_radii(physical["rig"]["plate"], 1 / r),
            "obstacles": [shape_in_radii(physical["rig"]["obstacles"][0], 1 / r)],
            "clearance": 0.1, "stroke": [9.0, 8.0]}
check(code == 0 and close(expected, {k: rig.get(k) for k in expected}, LENGTH_TOL),
      "a rig in metres (rectangle plate) is drawn in ball radii, the rectangle as its four corners",
      err.strip() + json.dumps({k: rig.get(k) for k in expected}))

# ---------------------------------------------------------------- a rig of actuator limits only
unreachable = os.path.join(src, "tests/data/rig_unreachable.json")
code, err = run("steer", unreachable, "--out", f"{work}/unreachable.json", "--quiet")
check(code == 4, "steer of the unreachable rig problem: exit 4 (limits not met, closest arrival written)", err.strip())
code, err = run("view", f"{work}/unreachable.json", "--html", f"{work}/unreachable.html")
_, data = page_data(f"{work}/unreachable.html") if code == 0 else (None, {})
rig = data.get("rig", {})
check(code == 0 and "plate" not in rig and "stroke" not in rig and rig.get("obstacles") == []
      and rig.get("check", {}).get("blocking") == ["max_plate_velocity_change"]
      and any(label == "report" and "limits_not_met" in value for label, value in data.get("facts", [])),
      "view of the unreachable result: nothing on the plates, the blocking limit and the status in the panel",
      err.strip() + json.dumps(rig))

# ---------------------------------------------------------------- strings of the result stay data
hostile = copy.deepcopy(result)
name = '</script><script>window.pwned = 1</script><!-- "@DATA@" & \u2028'
hostile["rig"]["check"]["margins"] = {name: -0.5, "__proto__": 1.0}
hostile["rig"]["check"]["violations"] = [name]
hostile["problem"]["file"] = shapes
json.dump(hostile, open(f"{work}/hostile.json", "w"))
code, err = run("view", f"{work}/hostile.json", "--html", f"{work}/hostile.html")
text, data = page_data(f"{work}/hostile.html") if code == 0 else ("", {})
margins = data.get("rig", {}).get("check", {}).get("margins", [])
check(code == 0 and text.count("</script>") == 3 and text.count("<script") == 3 and "<!--" not in text.split("<body>")[1]
      and [name, -0.5] in margins and ["__proto__", 1.0] in margins
      and data["rig"]["check"]["violations"] == [name],
      "margin names and violations with </script>, <!-- and U+2028 are escaped data, shown verbatim, never markup",
      f"{text.count('</script>')} </script>, margins {margins}")

# ---------------------------------------------------------------- a malformed rig object
bad = copy.deepcopy(result)
bad["problem"]["file"] = shapes
bad["rig"]["check"]["passed"] = "yes"
json.dump(bad, open(f"{work}/bad.json", "w"))
code, err = run("view", f"{work}/bad.json", "--html", f"{work}/bad.html")
check(code == 3 and 'rig.check.passed: value "yes": must be true or false' in err and not os.path.exists(f"{work}/bad.html"),
      "a rig verdict that is not true or false: exit 3 naming rig.check.passed", err.strip())
bad["rig"]["check"]["passed"] = True
bad["rig"]["check"]["margins"] = {"plate": "wide"}
json.dump(bad, open(f"{work}/bad.json", "w"))
code, err = run("view", f"{work}/bad.json", "--html", f"{work}/bad.html")
check(code == 3 and 'rig.check.margins.plate: value "wide": must be a finite number' in err,
      "a margin that is not a number: exit 3 naming rig.check.margins.plate", err.strip())

# ---------------------------------------------------------------- a rig beyond what the page can draw
# The page draws coordinates up to 1e6 ball radii (single-precision WebGL): a plate of radius 2e6 is refused.
huge = copy.deepcopy(problem)
huge["rig"] = {"plate": {"type": "disk", "center": [1.5, 1.5], "radius": 2e6}}
json.dump(huge, open(f"{work}/huge.json", "w"))
run("steer", f"{work}/huge.json", "--out", f"{work}/huge_result.json", "--quiet")
code, err = run("view", f"{work}/huge_result.json", "--html", f"{work}/huge.html")
check(code == 3 and "rig shape (plate, obstacles, stroke box)[0]: value 2000001.5: the page draws coordinates up to 1e6" in err,
      "a plate reaching beyond 1e6 ball radii: exit 3 naming the rig shape", err.strip())

check.finish()
