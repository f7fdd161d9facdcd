#!/usr/bin/python3
"""The actuator's records in the tools' JSON (tools/common/actuator_json.h, docs/rig.md).

  /usr/bin/python3 tests/scripts/actuator_outputs.py --plateball build/plateball \
      --isoparallel-solve build/isoparallel_solve

Checks, from the repository root, on real outputs:
  1. `plan`, `steer` and `isoparallel_solve --out` with --pulse-duration (and `plan --pulse-error`)
     validate against their schemas;
  2. every reported plate impulse J satisfies the balances of ball and plate recomputed here from the
     reported delta_omega, the axis z of the reported angles and the problem's masses and inertias:
       total angular momentum about the lower contact   2 r e3 x J = [I dw]_h + (M_ball + 4 M_plate) r^2 dw,
       the plate's linear momentum                       J - Q = M_plate * plate_velocity_jump,
       the ball's linear momentum                        Q + G = M_ball r dw x e3,
       the plate's velocity jump                         plate_velocity_jump = 2 r dw x e3 = r * the step's
                                                         normalised plate_velocity_change,
     and the pulse's mean force is J / delta; with --preload the normal loads M_plate g + preload and
     + M_ball g, and the friction needed from the record's own forces;
  3. a lambda-only problem's records are null with the reason "needs ball.physical".
Exits 1 naming the first failure.
"""

import argparse
import json
import math
import os
import subprocess
import sys
import tempfile

import jsonschema

ROOT = os.path.normpath(os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", ".."))
# The balances hold to rounding: J is one 3x3 solve of numbers of order 1e-4 N s.
RELATIVE_TOLERANCE = 1e-9
STANDARD_GRAVITY = 9.80665  # m/s^2, PulseOptions' default


def fail(message):
    print("FAIL: " + message)
    sys.exit(1)


def run(argv, ok=(0,)):
    r = subprocess.run(argv, cwd=ROOT, capture_output=True, text=True, timeout=120)
    if r.returncode not in ok:
        fail(f"{' '.join(argv)}: exit {r.returncode}: {r.stderr.strip()}")
    return r


def validator(rel):
    registry_root = os.path.join(ROOT, "schemas")
    with open(os.path.join(registry_root, rel)) as f:
        schema = json.load(f)
    store = {}
    for dirpath, _, files in os.walk(registry_root):
        for name in files:
            if name.endswith(".json"):
                with open(os.path.join(dirpath, name)) as f:
                    s = json.load(f)
                store[s["$id"]] = s
    resolver = jsonschema.RefResolver.from_schema(schema, store=store)
    return jsonschema.Draft202012Validator(schema, resolver=resolver)


def validate(rel, doc, what):
    errors = sorted(validator(rel).iter_errors(doc), key=lambda e: list(e.path))
    if errors:
        fail(f"{what}: {rel}: {errors[0].message} at {list(errors[0].path)}")


def cross(a, b):
    return [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]]


def close(a, b, scale, what):
    for x, y in zip(a, b):
        if abs(x - y) > RELATIVE_TOLERANCE * scale:
            fail(f"{what}: {a} != {b} (scale {scale})")


def check_record(phys, angles, delta_omega, normalised_plate_change, record, duration, what):
    th, ph = angles["theta"], angles["phi"]
    z = [math.sin(th) * math.cos(ph), math.sin(th) * math.sin(ph), math.cos(th)]
    dw = [delta_omega[0], delta_omega[1], 0.0]
    r, mb, mp = phys["radius"], phys["ball_mass"], phys["plate_mass"]
    i1, i3 = phys["inertia_1"], phys["inertia_3"]
    zdw = sum(a * b for a, b in zip(z, dw))
    i_dw = [i1 * dw[i] + (i3 - i1) * z[i] * zdw for i in range(3)]
    e3 = [0.0, 0.0, 1.0]
    J, Q, G = record["plate_impulse"], record["top_contact_impulse"], record["bottom_contact_impulse"]
    scale = max(abs(v) for v in J + Q + G + [1e-300])
    lhs = [2 * r * v for v in cross(e3, J)][:2]
    rhs = [i_dw[i] + (mb + 4 * mp) * r * r * dw[i] for i in range(2)]
    close(lhs, rhs, scale * r, what + ": angular momentum about the lower contact")
    jump = [2 * r * v for v in cross(dw, e3)]
    close(record["plate_velocity_jump"], jump, max(abs(v) for v in jump + [1e-300]), what + ": plate velocity jump")
    close(record["plate_velocity_jump"], [r * v for v in normalised_plate_change],
          max(abs(v) for v in jump + [1e-300]), what + ": against the step's plate_velocity_change")
    close([J[i] - Q[i] for i in range(3)], [mp * v for v in jump], scale, what + ": the plate's momentum")
    ball = [mb * r * v for v in cross(dw, e3)]
    close([Q[i] + G[i] for i in range(3)], ball, scale, what + ": the ball's momentum")
    close([record["torsional_impulse"]], [(i3 - i1) * zdw * z[2]], scale * r, what + ": torsional impulse")
    if duration:
        close(record["pulse"]["mean_force"], [v / duration for v in J], scale / duration, what + ": mean force")
    return 1


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--plateball", required=True)
    ap.add_argument("--isoparallel-solve", required=True)
    args = ap.parse_args()
    checked = 0
    with tempfile.TemporaryDirectory() as tmp:
        # plan, physical ball, 10 ms pulses: schema and balances of every step.
        doc = json.loads(run([args.plateball, "plan", "problems/circle_physical.json", "--impulses", "16",
                              "--pulse-duration", "0.01"]).stdout)
        validate("output/plan.schema.json", doc, "plan --pulse-duration")
        phys = doc["units"]["physical"]
        for s in doc["steps"]:
            checked += check_record(phys, s["angles_before"], s["delta_omega"], s["plate_velocity_change"],
                                    s["actuator"], 0.01, f"plan steps[{s['k']}]")
        # --preload N: the normal loads M_plate g + N and + M_ball g (standard gravity), the friction needed
        # from the record's own tangential forces and torque.
        doc = json.loads(run([args.plateball, "plan", "problems/circle_physical.json", "--impulses", "16",
                              "--pulse-duration", "0.01", "--preload", "2"]).stdout)
        for s in doc["steps"]:
            p = s["actuator"]["pulse"]
            top, bottom = phys["plate_mass"] * STANDARD_GRAVITY + 2, (phys["plate_mass"] + phys["ball_mass"]) * STANDARD_GRAVITY + 2
            close([p["top_normal_load"], p["bottom_normal_load"]], [top, bottom], bottom, f"preload steps[{s['k']}]: loads")
            close([p["sliding_friction_needed"], p["torsional_friction_needed"]],
                  [max(p["top_tangential_force"] / top, p["bottom_tangential_force"] / bottom),
                   p["torsional_torque"] / (top + bottom)], 1.0, f"preload steps[{s['k']}]: friction needed")
        # plan --pulse-error: the schedule's J equals the step's, its force J / duration.
        doc = json.loads(run([args.plateball, "plan", "problems/circle_physical.json", "--impulses", "16",
                              "--pulse-error", "1e-4"]).stdout)
        validate("output/plan.schema.json", doc, "plan --pulse-error")
        sched = doc["pulse_schedule"]
        if not (sched["within"] and sched["measured_error"] <= 1e-4):
            fail(f"plan --pulse-error 1e-4: schedule not within: {sched['measured_error']}")
        for p, s in zip(sched["pulses"], doc["steps"]):
            close(p["plate_impulse"], s["actuator"]["plate_impulse"], 1e-3, f"pulse_schedule k={p['k']}: J")
            close(p["mean_force"], [v / sched["pulse_duration"] for v in p["plate_impulse"]], 1.0,
                  f"pulse_schedule k={p['k']}: force")
        # isoparallel_solve --out with a physical ball (Figure 7): its plan's steps.
        out = os.path.join(tmp, "iso.json")
        run([args.isoparallel_solve, "tests/data/rig_isoparallel_physical.json", "--pulse-duration", "0.01",
             "--out", out])
        with open(out) as f:
            doc = json.load(f)
        validate("output/isoparallel.schema.json", doc, "isoparallel_solve --out --pulse-duration")
        with open(os.path.join(ROOT, "tests/data/rig_isoparallel_physical.json")) as f:
            phys = json.load(f)["ball"]["physical"]
        for s in doc["plan"]["steps"]:
            checked += check_record(phys, s["angles_before"], s["delta_omega"], s["plate_velocity_change"],
                                    s["actuator"], 0.01, f"isoparallel plan.steps[{s['k']}]")
        # steer --fewest-impulses with a physical ball: the SI values and the units, like exact arrival.
        doc = json.loads(run([args.plateball, "steer", "tests/data/rig_steer_physical.json", "--fewest-impulses",
                              "--max-impulses", "4"]).stdout)
        validate("output/steer.schema.json", doc, "steer --fewest-impulses (physical)")
        radius = doc["units"]["physical"]["radius"]
        for i, imp in enumerate(doc["impulses"]):
            close(imp["si"]["x"], [radius * v for v in imp["x"]], radius, f"fewest impulses[{i}].si.x")
        # lambda-only problems: null with the reason, in plan, steer and the schedule.
        doc = json.loads(run([args.plateball, "plan", "problems/circle.json", "--impulses", "8",
                              "--pulse-error", "1e-3"]).stdout)
        validate("output/plan.schema.json", doc, "plan (lambda only) --pulse-error")
        doc2 = json.loads(run([args.plateball, "steer", "problems/figure7_exact.json", "--pulse-duration", "0.01"],
                              ok=(0, 4)).stdout)
        validate("output/steer.schema.json", doc2, "steer (lambda only) --pulse-duration")
        records = [s["actuator"] for s in doc["steps"]] + [i["actuator"] for i in doc2["impulses"]]
        for a in records:
            if a["plate_impulse"] is not None or a["pulse"] is not None or "needs ball.physical" not in a["reason"] \
                    or "needs ball.physical" not in a["pulse_reason"]:
                fail(f"lambda-only record not null with its reason: {a}")
        for p in doc["pulse_schedule"]["pulses"]:
            if p["plate_impulse"] is not None or "needs ball.physical" not in p["reason"]:
                fail(f"lambda-only schedule pulse not null with its reason: {p}")
    print(f"actuator records checked: {checked} balanced, {len(records)} null with reason")


if __name__ == "__main__":
    main()
