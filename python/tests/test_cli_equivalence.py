"""The Python results equal the CLI's JSON to the last digit on the golden problems in problems/.

Both sides run the same task adapter (task_adapters.h) on the same problem file; the CLI writes
every double in the shortest form that reads back to the same value, so the comparison is exact
equality, with no tolerance.

FIELDS is the one place that names the CLI's JSON fields, in the names of the output contract
(docs/output_contract.md, schema_version 1): each entry is (JSON path, value of the Python
result). In a JSON path "a.b" descends into objects and "a[*]" maps over a list. HEADER is the
self-describing header every document starts with, checked against the problem file.
"""
import numpy as np
import pytest

import plateball as pb


def json_get(doc, path):
    """The value at `path` (see the module doc); KeyError naming the path when it is absent."""
    try:
        return _get(doc, path.split("."))
    except (KeyError, TypeError) as e:
        raise KeyError(f"{path!r} is not in the CLI's document") from e


def _get(node, keys):
    if not keys:
        return node
    key, rest = keys[0], keys[1:]
    if key.endswith("[*]"):
        return [_get(item, rest) for item in node[key[:-3]]]
    return _get(node[key], rest)


def _steps(attr):
    return lambda r: [getattr(s, attr) for s in r.steps]


FIELDS = {
    "simulate": [
        ("period", lambda r: r["motion"].period),
        ("drift_per_period", lambda r: r["motion"].drift_per_period),
        ("mean_velocity", lambda r: r["motion"].mean_velocity),
        ("initial.z", lambda r: r["motion"].start_state.z),
        ("initial.omega", lambda r: r["motion"].start_state.omega),
        ("initial.orientation", lambda r: r["motion"].start_orientation),
        ("samples[*].t", lambda r: r["samples"].t),
        ("samples[*].angles.theta", lambda r: r["samples"].angles[:, 0]),
        ("samples[*].angles.phi", lambda r: r["samples"].angles[:, 1]),
        ("samples[*].angles.psi", lambda r: r["samples"].angles[:, 2]),
        ("samples[*].z", lambda r: r["samples"].z),
        ("samples[*].x", lambda r: r["samples"].x),
        ("samples[*].orientation", lambda r: r["samples"].orientation),
        ("samples[*].omega", lambda r: r["samples"].omega),
        ("samples[*].energy", lambda r: r["samples"].energy),
    ],
    "join": [
        ("status", lambda r: r.status),
        ("usable", lambda r: r.usable),
        ("message", lambda r: r.message),
        ("report", lambda r: r.report),
        ("delta_psi", lambda r: r.delta_psi),
        ("t", lambda r: r.t),
        ("residual", lambda r: r.residual),
        ("iterations", lambda r: r.iterations),
        ("initial_guess_residual", lambda r: r.initial_guess_residual),
        ("jacobian_conditioning", lambda r: r.jacobian_conditioning),
        ("impulse.delta_omega", lambda r: r.impulse.delta_omega),
        ("impulse.plate_velocity_change", lambda r: r.impulse.plate_velocity_change),
        ("arrival.x", lambda r: r.x_after),
        ("arrival.z", lambda r: r.state_after.z),
        ("arrival.omega", lambda r: r.state_after.omega),
        ("arrival.angles.theta", lambda r: r.angles_after.theta),
        ("arrival.angles.psi", lambda r: r.angles_after.psi),
        ("impulse.angles_after.psi", lambda r: r.impulse.after.psi),
    ],
    "reach": [
        ("status", lambda r: r.status),
        ("usable", lambda r: r.usable),
        ("message", lambda r: r.message),
        ("report", lambda r: r.report),
        ("period", lambda r: r.period),
        ("horizon", lambda r: r.horizon),
        ("solutions[*].delta_psi", lambda r: r.delta_psi),
        ("solutions[*].t", lambda r: r.t),
        ("solutions[*].periods", lambda r: [s.periods for s in r.solutions]),
        ("solutions[*].residual", lambda r: [s.residual for s in r.solutions]),
        ("solutions[*].plate_velocity_change", lambda r: [s.impulse.plate_velocity_change for s in r.solutions]),
        ("solutions[*].end.x", lambda r: [s.end.x for s in r.solutions]),
        ("solutions[*].end.orientation", lambda r: [s.end.orientation for s in r.solutions]),
        ("drift_guess_delta_psi", lambda r: r.drift_guess_delta_psi),
    ],
    "plan": [
        ("status", lambda r: r.status),
        ("usable", lambda r: r.usable),
        ("report", lambda r: r.report),
        ("total_time", lambda r: r.total_time),
        ("max_pass_miss", lambda r: r.max_pass_miss),
        ("max_join_residual", lambda r: r.max_join_residual),
        ("measured_error", lambda r: r.measured_error),
        ("polyline_error", lambda r: r.polyline_error),
        ("bounds.a_posteriori", lambda r: r.bounds.a_posteriori),
        ("bounds.theorem_2_6", lambda r: r.bounds.theorem_2_6),
        ("bounds.corollary_3", lambda r: r.bounds.corollary_3),
        ("bounds.constants.K_tilde_p", lambda r: r.bounds.constants.K_tilde_p),
        ("rotation_final.impulsive.matrix", lambda r: r.orientation_impulsive),
        ("rotation_final.planned.matrix", lambda r: r.orientation_planned),
        ("final.omega", lambda r: r.final_state.omega),
        ("steps[*].p_begin", lambda r: r.pass_points),
        ("steps[*].t_impulse", lambda r: r.t_impulse),
        ("steps[*].duration", lambda r: r.durations),
        ("steps[*].delta_psi", lambda r: r.delta_psi),
        ("steps[*].delta_omega", lambda r: r.delta_omega),
        ("steps[*].plate_velocity_change", lambda r: r.plate_velocity_changes),
        ("steps[*].x_end", _steps("x_end")),
        ("steps[*].pass_miss", _steps("pass_miss")),
        ("steps[*].orientation_impulsive", lambda r: r.orientations_impulsive),
        ("steps[*].orientation_planned", _steps("orientation_planned")),
    ],
    "converge": [
        ("rows[*].n", lambda r: r.column("n")),
        ("rows[*].status", lambda r: [row.status for row in r.rows]),
        ("rows[*].message", lambda r: [row.message for row in r.rows]),
        ("rows[*].measured_error", lambda r: r.column("measured_error")),
        ("rows[*].polyline_error", lambda r: r.column("polyline_error")),
        ("rows[*].bounds.a_posteriori", lambda r: r.column("bound")),
        ("rows[*].bounds.theorem_2_6", lambda r: r.column("theorem_2_6")),
        ("rows[*].max_pass_miss", lambda r: r.column("max_pass_miss")),
        ("error_slope", lambda r: r.error_slope),
        ("bound_slope", lambda r: r.bound_slope),
        ("bound_holds", lambda r: r.bound_holds),
        ("report", lambda r: r.report),
    ],
    "isoparallel": [
        ("solver.status", lambda r: r["summary"].status),
        ("solver.method", lambda r: r["summary"].method),
        ("solver.complete", lambda r: r["summary"].complete),
        ("solutions[*].length", lambda r: r["summary"].lengths),
        ("solutions[*].G", lambda r: [s.G for s in r["summary"].solutions]),
        ("solutions[*].energy", lambda r: [s.energy for s in r["summary"].solutions]),
        ("solutions[*].orientation_residual", lambda r: [s.orientation_residual for s in r["summary"].solutions]),
        ("solutions[*].orientation_distance", lambda r: [s.orientation_error for s in r["summary"].solutions]),
        ("optimal_path", lambda r: r["summary"].shortest().points(400)),
        ("plan.status", lambda r: r["plan"].status),
        ("plan.report", lambda r: r["plan"].report),
        ("plan.measured_error", lambda r: r["plan"].measured_error),
        ("plan.bounds.a_posteriori", lambda r: r["plan"].bounds.a_posteriori),
        ("plan.steps[*].delta_psi", lambda r: r["plan"].delta_psi),
        ("plan.steps[*].duration", lambda r: r["plan"].durations),
        ("plan.steps[*].plate_velocity_change", lambda r: r["plan"].plate_velocity_changes),
    ],
    "steer": [
        ("status", lambda r: r.status),
        ("usable", lambda r: r.usable),
        ("report", lambda r: r.report),
        ("total_time", lambda r: r.total_time),
        ("iterations", lambda r: r.iterations),
        ("arrival.x", lambda r: r.x_final),
        ("arrival.position_error", lambda r: r.position_error),
        ("arrival.orientation_error", lambda r: r.orientation_error),
        ("deviation.value", lambda r: r.deviation),
        ("impulses[*].x", lambda r: r.positions),
        ("impulses[*].delta_psi", lambda r: r.delta_psi),
        ("impulses[*].duration", lambda r: r.durations),
        ("impulses[*].plate_velocity_change", lambda r: r.plate_velocity_changes),
        ("impulses[*].p", lambda r: [i.planned_position for i in r.impulses]),
        ("impulses[*].angles_before.theta", lambda r: [i.angles_before.theta for i in r.impulses]),
        ("impulses[*].kind", lambda r: [i.kind for i in r.impulses]),
        ("impulses[*].mu_before", lambda r: [i.mu_before for i in r.impulses]),
        ("impulses[*].mu_after", lambda r: [i.mu_after for i in r.impulses]),
        ("arrival.rotation.matrix", lambda r: r.orientation_final),
        ("paper_plan.orientation_error", lambda r: r.planned_orientation_error),
    ],
    "steer_fewest": [
        ("status", lambda r: r["summary"].status),
        ("usable", lambda r: r["summary"].usable),
        ("message", lambda r: r["summary"].message),
        ("report", lambda r: r["summary"].report),
        ("fewest_impulses", lambda r: r["summary"].fewest),
        ("searched", lambda r: r["summary"].searched),
        ("max_total_time", lambda r: r["summary"].max_total_time),
        ("rollouts", lambda r: r["summary"].rollouts),
        ("start_at_rest", lambda r: r["problem"].start_at_rest),
        ("stop_at_goal", lambda r: r["problem"].stop_at_goal),
        ("goal.x", lambda r: r["problem"].x1),
        ("pareto[*].impulse_count", lambda r: [c.impulses for c in r["summary"].counts]),
        ("pareto[*].reached", lambda r: [c.reached for c in r["summary"].counts]),
        ("pareto[*].starts", lambda r: [c.starts for c in r["summary"].counts]),
        ("pareto[*].arrived", lambda r: [c.arrived for c in r["summary"].counts]),
        ("pareto[*].total_time", lambda r: [c.total_time for c in r["summary"].counts]),
        ("pareto[*].path_length", lambda r: [c.path_length for c in r["summary"].counts]),
        ("pareto[*].position_error", lambda r: [c.position_error for c in r["summary"].counts]),
        ("pareto[*].orientation_error", lambda r: [c.orientation_error for c in r["summary"].counts]),
        ("pareto[*].replay.x", lambda r: [x for x, _ in r["replays"]]),
        ("pareto[*].replay.orientation_error", lambda r: [e for _, e in r["replays"]]),
        ("impulses[*].kind", lambda r: [i.kind for i in r["impulses"]]),
        ("impulses[*].x", lambda r: [i.position for i in r["impulses"]]),
        ("impulses[*].delta_psi", lambda r: [i.delta_psi for i in r["impulses"]]),
        ("impulses[*].duration", lambda r: [i.duration for i in r["impulses"]]),
        ("impulses[*].plate_velocity_change", lambda r: [i.plate_velocity_change for i in r["impulses"]]),
        ("impulses[*].mu_before", lambda r: [i.mu_before for i in r["impulses"]]),
        ("impulses[*].mu_after", lambda r: [i.mu_after for i in r["impulses"]]),
    ],
    "montecarlo": [
        ("status", lambda r: r.status),
        ("usable", lambda r: r.usable),
        ("report", lambda r: r.report),
        ("failed_trials", lambda r: r.failed_trials),
        ("nominal[*].measured_error", lambda r: [i.measured_error for i in r.nominal]),
        ("nominal[*].orientation_error", lambda r: [i.orientation_error for i in r.nominal]),
        ("results[*].strategy", lambda r: [c.strategy for c in r.cells]),
        ("results[*].completed", lambda r: [c.completed for c in r.cells]),
        ("results[*].position_error.median", lambda r: [c.position_error.median for c in r.cells]),
        ("results[*].position_error.max", lambda r: [c.position_error.max for c in r.cells]),
        ("results[*].orientation_error.mean", lambda r: [c.orientation_error.mean for c in r.cells]),
        ("results[*].orientation_error.p95", lambda r: [c.orientation_error.p95 for c in r.cells]),
        ("results[*].total_time.median", lambda r: [c.total_time.median for c in r.cells]),
    ],
}


# The header of every document (output contract, section 1) against the problem file.
HEADER = [
    ("schema_version", lambda p: 1),
    ("version", lambda p: pb.__version__),
    ("problem.name", lambda p: p.name),
    ("model.lambda", lambda p: p.model.lambda_),
    ("integration.absolute_tolerance", lambda p: p.integration.absolute_tolerance),
    ("integration.relative_tolerance", lambda p: p.integration.relative_tolerance),
    ("integration.max_steps", lambda p: p.integration.max_steps),
    ("seed", lambda p: p.seed),
]


def assert_header(doc, problem, command):
    assert doc["command"] == command
    for path, python_value in HEADER:
        assert json_get(doc, path) == python_value(problem), path


def assert_same(doc, result, command):
    """Every FIELDS entry of `command`: the CLI's value == the Python value, exactly."""
    checked = 0
    for path, python_value in FIELDS[command]:
        expected = json_get(doc, path)
        actual = python_value(result)
        if isinstance(expected, (str, bool)) or expected is None:
            assert actual == expected, path
        elif isinstance(expected, list) and expected and all(isinstance(e, str) for e in expected):
            assert list(actual) == expected, path
        else:
            a = np.asarray(actual, dtype=float)
            e = np.asarray(expected, dtype=float)
            assert a.shape == e.shape, f"{path}: shape {a.shape} != {e.shape}"
            assert np.array_equal(a, e), f"{path}: max difference {np.max(np.abs(a - e))}"
        checked += 1
    assert checked == len(FIELDS[command])


@pytest.mark.parametrize("name", ["simulate_example", "circle", "figure8_reach"])
def test_simulate(problems, run_cli, name):
    doc = run_cli("plateball", "simulate", problems / f"{name}.json", "--samples", 9, "--t-end", 7.5)
    problem = pb.load_problem(problems / f"{name}.json")
    assert_header(doc, problem, "simulate")
    motion = pb.free_motion_for(problem)
    assert_same(doc, {"motion": motion, "samples": motion.sample(0.0, 7.5, 9)}, "simulate")


def test_join(problems, run_cli):
    targets = [(0.05, 0.0), (0.0, 0.05), (-0.03, 0.04)]
    doc = run_cli("plateball", "join", problems / "circle.json", "--targets", ";".join(f"{x},{y}" for x, y in targets))
    problem = pb.load_problem(problems / "circle.json")
    assert_header(doc, problem, "join")
    assert len(doc["joins"]) == len(targets)
    for target, entry in zip(targets, doc["joins"]):
        assert_same(entry, pb.join(*pb.join_setup_for(problem, target)), "join")


def test_reach(problems, run_cli):
    doc = run_cli("plateball", "reach", problems / "figure8_reach.json")
    problem = pb.load_problem(problems / "figure8_reach.json")
    assert_header(doc, problem, "reach")
    entries = json_get(doc, "results")
    assert len(entries) == len(problem.reach.targets) == 3
    for target, entry in zip(problem.reach.targets, entries):
        assert_same(entry, pb.reach(*pb.reach_setup_for(problem, target)), "reach")


@pytest.mark.parametrize("name", ["circle", "ellipse", "lemniscate", "piecewise"])
def test_plan(problems, run_cli, name):
    doc = run_cli("plateball", "plan", problems / f"{name}.json")
    problem = pb.load_problem(problems / f"{name}.json")
    assert_header(doc, problem, "plan")
    summary = pb.plan(*pb.plan_setup_for(problem))
    assert summary.status == "success"
    assert_same(doc, summary, "plan")


def test_converge(problems, run_cli):
    doc = run_cli("plateball", "converge", problems / "circle.json", "--n", "16,32,64")
    problem = pb.load_problem(problems / "circle.json")
    assert_header(doc, problem, "converge")
    setup = pb.convergence_setup_for(problem, [16, 32, 64])
    assert_same(doc, pb.converge(setup.problem, setup.options), "converge")


def test_isoparallel(problems, run_cli):
    doc = run_cli("isoparallel_solve", problems / "figure7.json", out_file=True)
    problem = pb.load_problem(problems / "figure7.json")
    assert_header(doc, problem, "isoparallel")
    summary = pb.isoparallel(*pb.isoparallel_setup_for(problem))
    plan = pb.plan_optimal_path(*pb.isoparallel_plan_setup_for(problem, summary.shortest()))
    assert_same(doc, {"summary": summary, "plan": plan}, "isoparallel")


def test_steer(problems, run_cli):
    doc = run_cli("plateball", "steer", problems / "figure7_exact.json")
    problem = pb.load_problem(problems / "figure7_exact.json")
    assert_header(doc, problem, "steer")
    if problem.plan is not None:
        setup = pb.exact_arrival_setup_for(problem)
    else:
        iso = pb.isoparallel(*pb.isoparallel_setup_for(problem))
        setup = pb.exact_arrival_setup_for(problem, iso.shortest())
    summary = pb.steer(setup.problem, setup.options)
    assert_same(doc, summary, "steer")
    replay = pb.replay_exact_arrival(setup.problem, summary.impulses)
    assert np.array_equal(np.asarray(json_get(doc, "replay.x"), dtype=float), replay.x)
    assert json_get(doc, "replay.orientation_error") == replay.orientation_error


def test_steer_fewest(problems, run_cli):
    """`plateball steer` on a file asking for the fewest impulses: the Pareto table and the impulses."""
    doc = run_cli("plateball", "steer", problems / "figure7_fewest.json")
    problem = pb.load_problem(problems / "figure7_fewest.json")
    assert_header(doc, problem, "steer")
    setup = pb.fewest_impulses_setup_for(problem)
    summary = pb.fewest_impulses(*setup)
    replays = []
    for c in summary.counts:
        r = pb.replay_exact_arrival(pb.replay_problem_for(setup.problem, c.impulses), c.plan)
        replays.append((r.x, r.orientation_error))
    fewest = summary.fewest_count
    impulses = list(fewest.plan) + ([fewest.stop] if fewest.stop is not None else [])
    assert_same(doc, {"summary": summary, "problem": setup.problem, "replays": replays, "impulses": impulses},
                "steer_fewest")


def test_roll_segment(run_cli):
    doc = run_cli("plateball", "roll", "--segment", "--points", "0,0;1.2,1.6;2,0.5")
    r = pb.roll([(0, 0), (1.2, 1.6), (2, 0.5)], segment=True)
    assert np.array_equal(np.asarray(json_get(doc, "reorientation.matrix"), dtype=float), r)


def test_montecarlo(problems, run_cli):
    """`plateball montecarlo` with its defaults (open_loop and feedback, impulse_magnitude=1e-3)."""
    doc = run_cli("plateball", "montecarlo", problems / "circle.json", "--trials", 6, "--impulses", 16,
                  "--threads", 2, "--quiet")
    problem = pb.load_problem(problems / "circle.json")
    assert_header(doc, problem, "montecarlo")
    setup = pb.plan_setup_for(problem, 16)
    errors = pb.parse_error_model("impulse_magnitude=1e-3")
    study = pb.MonteCarloProblem(plan=setup.problem, trials=6, seed=problem.seed,
                                 strategies=["open_loop", "feedback"],
                                 scenarios=[pb.MonteCarloScenario(name=str(errors), errors=errors)])
    summary = pb.montecarlo(study, pb.MonteCarloOptions(plan=setup.options, threads=1))
    assert summary.trials("position_error").shape == (12,)
    assert_same(doc, summary, "montecarlo")


def test_montecarlo_on_a_rig_runs_the_rig_plan(problems, run_cli):
    """`plateball montecarlo` with a rig section runs plan_on_rig's plan: the library study given that plan
    (main_plan) has the tool's n, nominal numbers and results."""
    data = problems.parent / "tests" / "data" / "plan_rig_blocked.json"
    doc = run_cli("plateball", "montecarlo", data, "--trials", 2, "--strategy", "open_loop", "--noise",
                  "impulse_magnitude=1e-3", "--threads", 1, "--quiet")
    problem = pb.load_problem(data)
    setup = pb.plan_setup_for(problem)
    honoured = pb.plan_on_rig(setup.problem, problem.rig, problem.physical, setup.options)
    assert honoured.usable and honoured.plan.segments == 128
    assert json_get(doc, "rig.points_added") == honoured.points_added == 64
    errors = pb.parse_error_model("impulse_magnitude=1e-3")
    study = pb.MonteCarloProblem(plan=setup.problem, trials=2, seed=problem.seed, strategies=["open_loop"],
                                 scenarios=[pb.MonteCarloScenario(name=str(errors), errors=errors)],
                                 main_plan=honoured.plan)
    summary = pb.montecarlo(study, pb.MonteCarloOptions(plan=setup.options, threads=1))
    assert summary.nominal[0].n == json_get(doc, "options.impulses") == 128
    assert summary.nominal[0].total_time == doc["nominal"][0]["total_time"]
    medians = [r["position_error"]["median"] for r in doc["results"]]
    assert medians == [summary.cells[0].position_error.median]


def test_montecarlo_cell_without_a_completed_trial_is_none(problems, run_cli):
    """A cell where every trial lost the ball has no distribution: null in the JSON, None here."""
    noise = "impulse_magnitude=0.5,impulse_angle=0.5,energy_loss=0.5,timing=0.1,lambda=0.1,observation=0.1"
    doc = run_cli("plateball", "montecarlo", problems / "circle.json", "--trials", 20, "--strategy", "feedback",
                  "--noise", noise, "--threads", 1, "--quiet")
    problem = pb.load_problem(problems / "circle.json")
    setup = pb.plan_setup_for(problem, 64)
    errors = pb.parse_error_model(noise)
    study = pb.MonteCarloProblem(plan=setup.problem, trials=20, seed=problem.seed, strategies=["feedback"],
                                 scenarios=[pb.MonteCarloScenario(name=str(errors), errors=errors)])
    summary = pb.montecarlo(study, pb.MonteCarloOptions(plan=setup.options, threads=1))
    cell = summary.cells[0]
    assert cell.completed == 0 and doc["results"][0]["completed"] == 0
    assert cell.orientation_error is None and cell.position_error is None
    assert doc["results"][0]["orientation_error"] is None
    assert doc["results"][0]["note"] == "no trial completed"


def test_exact_arrival_iteration_cap_is_the_tools():
    """Python's iteration cap is the tools' 50 (the exact arrival's work bound)."""
    assert pb.ExactArrivalOptions(max_iterations=50).validate() == ""
    assert "max_iterations: value 51" in pb.ExactArrivalOptions(max_iterations=51).validate()


def test_plan_on_a_rig(problems, run_cli):
    """`plateball plan` with a rig section: the library's check of the same plan, margin for margin."""
    doc = run_cli("plateball", "plan", problems / "plan_rig_circle.json", "--summary-only")
    problem = pb.load_problem(problems / "plan_rig_circle.json")
    setup = pb.plan_setup_for(problem)
    plan = pb.plan(setup.problem, setup.options)
    check = pb.check_plan_rig_limits(setup.problem, plan, problem.rig, problem.physical)
    assert check.passed and json_get(doc, "rig.check.passed") and doc["status"] == "success"
    assert check.samples == 64 * len(plan.steps) == json_get(doc, "rig.check.samples")
    for name, margin in check.margins.items():
        assert json_get(doc, "rig.check.margins")[name] == margin
    # An obstacle in the flights' inward bow: the library and the tool both see it.
    problem.rig.obstacles = [pb.DiskShape(center=[-2.0, 0.0], radius=1.998)]
    blocked = pb.check_plan_rig_limits(setup.problem, plan, problem.rig)
    assert not blocked.passed and blocked.violations[0].startswith("obstacles[0] exceeded by ")
    assert blocked.margins["obstacles[0]"] == pytest.approx(-0.0028, abs=1e-4)


def test_plan_honours_a_rig(problems, run_cli):
    """`plateball plan` with an obstacle in the flights' bow: the library's plan_on_rig refines the same
    partition, and the tool's JSON carries its steps, counts, active limits and check."""
    data = problems.parent / "tests" / "data"
    doc = run_cli("plateball", "plan", data / "plan_rig_tick.json")
    problem = pb.load_problem(data / "plan_rig_tick.json")
    setup = pb.plan_setup_for(problem)
    honoured = pb.plan_on_rig(setup.problem, problem.rig, problem.physical, setup.options)
    assert honoured.usable and doc["status"] == "success"
    assert json_get(doc, "rig.mode") == "honour"
    assert json_get(doc, "partition.segments") == honoured.plan.segments == 128
    for key in ("segments_initial", "points_added", "points_removed", "points_slid", "rounds", "active", "blocking"):
        assert json_get(doc, "rig." + key) == getattr(honoured, key), key
    assert honoured.active == ["obstacles[0]", "tick"]
    times = [s["t_impulse"] for s in doc["steps"]]
    assert times == list(honoured.plan.t_impulse)
    assert all(t == round(t / problem.rig.tick) * problem.rig.tick for t in times)
    for name, margin in honoured.check.margins.items():
        assert json_get(doc, "rig.check.margins")[name] == margin
    # The plan as given enters the obstacle and is off the grid.
    given = pb.check_plan_rig_limits(setup.problem, pb.plan(setup.problem, setup.options), problem.rig)
    assert sorted(v.split(" ")[0] for v in given.violations) == ["obstacles[0]", "tick"]


def test_steer_on_a_rig(problems, run_cli):
    """`plateball steer` with a rig section: the same impulses, active limits and check as the library."""
    doc = run_cli("plateball", "steer", problems / "figure7_rig.json")
    problem = pb.load_problem(problems / "figure7_rig.json")
    assert problem.rig.plate is not None and len(problem.rig.obstacles) == 1
    iso = pb.isoparallel(*pb.isoparallel_setup_for(problem))
    choice = pb.choose_isoparallel_reference(iso, problem.rig, iso.shortest().start)
    assert json_get(doc, "reference.limits.solution_index") == choice.index
    assert json_get(doc, "reference.limits.shortest_breaks") == choice.shortest_breaks
    assert pb.path_limit_breaks(pb.optimal_path(iso.shortest()), problem.rig, problem.x0) == choice.shortest_breaks
    setup = pb.exact_arrival_setup_for(problem, iso.solutions[choice.index])
    assert setup.problem.limits.clearance == 0.05
    summary = pb.steer(setup.problem, setup.options)
    assert_same(doc, summary, "steer")
    assert json_get(doc, "rig.active") == summary.limits.active
    assert json_get(doc, "rig.constrained") is True
    check = pb.check_rig_limits(setup.problem, summary)
    assert check.passed and json_get(doc, "rig.check.passed")
    assert json_get(doc, "rig.check.margins.plate") == check.margins["plate"]
    # The free optimum leaves the plate: the check sees it.
    free = setup.problem
    free.limits = pb.RigLimits()
    free_summary = pb.steer(free, setup.options)
    free.limits = problem.rig
    assert not pb.check_rig_limits(free, free_summary).passed
