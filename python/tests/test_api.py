"""The binding's shape: keywords and objects, errors as ValueError with the library's message,
status words, NumPy results, the GIL released during solves."""
import json
import math
import threading

import numpy as np
import pytest

import plateball as pb


def test_keywords_and_objects_give_the_same_join():
    problem = pb.JoinProblem(model=pb.BallModel(2.0), start=(math.pi / 3, 0.4, 0.1), target=(0.05, 0.0))
    a = pb.join(problem, pb.JoinOptions(max_iterations=30))
    b = pb.join(model=pb.BallModel(2.0), start=(math.pi / 3, 0.4, 0.1), target=(0.05, 0.0), max_iterations=30)
    assert (a.delta_psi, a.t, a.status) == (b.delta_psi, b.t, b.status)
    assert a.report == "Join: converged, delta_psi = 1.35775, t = 0.0527666, residual = 4.80812e-14, iterations = 0"


def test_invalid_values_raise_value_error_with_the_library_message():
    with pytest.raises(ValueError, match=r"^mu: value -1: must be finite and > 0$"):
        pb.join(mu=-1.0, target=(0.05, 0.0))
    with pytest.raises(ValueError, match=r"max_iterations: value 0"):
        pb.join(target=(0.05, 0.0), max_iterations=0)
    with pytest.raises(ValueError, match=r"^x.json: initial.mu: value -1: must be > 0"):
        pb.parse_problem('{"ball": {"lambda": 1}, "initial": {"theta": 1, "phi": 0, "psi": 0, "mu": -1}}', "x.json")
    with pytest.raises(ValueError, match=r"radius: value 0"):
        pb.plan(path=pb.SmoothCurve.circle((0, 0), 0.0, 0.0, 1.0))


def test_unreadable_file_and_unknown_keyword():
    with pytest.raises(pb.ProblemFileReadError, match="cannot open"):
        pb.load_problem("/nonexistent/problem.json")
    assert issubclass(pb.ProblemFileReadError, OSError)
    with pytest.raises(TypeError, match="unexpected keyword argument 'targte'"):
        pb.join(targte=(1, 0))
    with pytest.raises(TypeError, match="unexpected keyword argument 'n'"):
        pb.JoinOptions(n=3)


def test_status_words_and_summary_shape():
    s = pb.join(target=(0.0, 0.0))
    assert s.status == "target_equals_start" and not s.usable
    far = pb.join(model=pb.BallModel(2.0), start=(math.pi / 3, 0.4, 0.1), target=(5.0, 0.0))
    assert far.status == "target_beyond_local_radius" and far.message
    unreachable = pb.reach(model=pb.BallModel(2.0), start=(math.pi / 2, 0.0, 0.0), target=(1e3, 0.0),
                           horizon_periods=0.5)
    assert unreachable.status == "unreachable_within_horizon"
    with pytest.raises(RuntimeError):
        unreachable.earliest()
    # Arcs of length ~0.6: more than the one integration step allowed.
    starved = pb.plan(path=pb.SmoothCurve.line((0, 0), (8, 0)), integration=pb.IntegrationOptions(max_steps=1))
    assert starved.status == "integration_failure" and not starved.usable and starved.message


def test_plan_arrays(problems):
    problem = pb.load_problem(problems / "circle.json")
    s = pb.plan(*pb.plan_setup_for(problem, 16))
    assert s.pass_points.shape == (16, 2) and s.delta_omega.shape == (16, 3)
    assert s.orientations_impulsive.shape == (16, 3, 3)
    traj = s.trajectory(problem.model, samples_per_arc=10)
    assert traj.x.shape == (161, 2) and traj.orientation.shape == (161, 3, 3)
    assert traj.t[-1] == pytest.approx(s.total_time, rel=1e-14)
    assert np.allclose(traj.orientation[-1], s.orientation_impulsive, atol=1e-10)
    with pytest.raises(ValueError, match="samples_per_arc: value 0"):
        s.trajectory(problem.model, samples_per_arc=0)


def test_problem_round_trip(problems):
    problem = pb.load_problem(problems / "figure7.json")
    text = pb.write_problem_json(problem)
    again = pb.parse_problem(text, "again.json")
    assert pb.write_problem_json(again) == text
    assert problem.isoparallel.impulses == 12 and problem.plan is None


def test_solves_release_the_gil(problems):
    """A Python thread keeps running while another thread is inside a solve."""
    setup = pb.isoparallel_setup_for(pb.load_problem(problems / "figure7.json"))
    done = threading.Event()
    result = {}

    def solve():
        result["summary"] = pb.isoparallel(setup.problem, setup.options)
        done.set()

    worker = threading.Thread(target=solve)
    worker.start()
    ticks = 0
    while not done.is_set():
        ticks += 1
    worker.join()
    assert result["summary"].status == "solved"
    assert ticks > 1000


def test_helper_counts_are_checked():
    line = pb.SmoothCurve.line((0.0, 0.0), (2.0, 0.0))
    assert np.array_equal(line.points(3), [[0.0, 0.0], [1.0, 0.0], [2.0, 0.0]])
    with pytest.raises(ValueError, match=r"^n: value 1: must be in \[2, 1000000\]$"):
        line.points(1)
    with pytest.raises(ValueError, match=r"^samples: value 1: must be in \[2, "):
        pb.FreeMotion(pb.BallModel(1.0), (1.0, 0.0, 0.0), 1.0).sample(0.0, 1.0, 1)


def test_load_problem_refuses_a_non_path_and_parse_problem_has_the_file_limit(problems):
    with pytest.raises(TypeError, match=r"load_problem\(\): path: value None"):
        pb.load_problem(None)
    text = (problems / "simulate_example.json").read_text()
    assert pb.parse_problem(text).name == pb.load_problem(problems / "simulate_example.json").name
    # The same 16 MiB limit as a problem file read by the tools, here on a string: exactly the
    # limit parses, one byte more is refused.
    assert pb.MAX_PROBLEM_FILE_BYTES == 16 * 2**20
    padding = pb.MAX_PROBLEM_FILE_BYTES - len(text.encode())
    assert pb.parse_problem(text + " " * padding).name == pb.parse_problem(text).name
    with pytest.raises(ValueError, match="16 MiB limit of a problem file"):
        pb.parse_problem(text + " " * (padding + 1))


def test_limits_are_the_readers():
    """plateball.MAX_... hold the numbers the reader applies: one past each is refused."""
    base = {"ball": {"lambda": 1}, "initial": {"theta": 1.0, "phi": 0, "psi": 0, "mu": 1}}
    at = dict(base, simulate={"samples": pb.MAX_SAMPLES})
    assert pb.parse_problem(json.dumps(at)).simulate.samples == 100000
    over = dict(base, simulate={"samples": pb.MAX_SAMPLES + 1})
    with pytest.raises(ValueError, match=r"simulate\.samples: value 100001: must be <= 100000"):
        pb.parse_problem(json.dumps(over))
    deep = dict(base, plan={"path": {"type": "line", "from": [0, 0], "to": [1, 0]},
                            "partition": {"n": pb.MAX_PARTITION_STEPS + 1}})
    with pytest.raises(ValueError, match=r"plan\.partition\.n: value 10001: must be <= 10000"):
        pb.parse_problem(json.dumps(deep))


def test_messages_name_the_python_argument_and_the_value(problems):
    """Each message names the argument or attribute as the call spells it, never a variable of the
    library ("y[5]", "orientation[2].w", "b", "partition (uniform_parameter, n = 1)[1]")."""
    t = np.linspace(0.0, 10.0, 40)
    xy = np.c_[np.cos(t), np.sin(t)]
    bad = xy.copy()
    bad[5, 1] = np.inf
    with pytest.raises(ValueError, match=r"^xy\[5\]\[1\]: value inf: must be finite$"):
        pb.identify(t, bad)
    with pytest.raises(ValueError, match=r"^xy \(rows\): value 39: must have one row per time \(40\)$"):
        pb.identify(t, xy[1:])
    quaternions = np.tile([1.0, 0.0, 0.0, 0.0], (40, 1))
    quaternions[2, 0] = np.nan
    with pytest.raises(ValueError, match=r"^orientation\[2\]\[0\]: value nan: must be finite$"):
        pb.identify(t, xy, sigma=np.full(40, 0.01), orientation=quaternions, sigma_orientation=np.ones(40))
    # A spline whose chord overflows: the point, not the integration's end "b".
    with pytest.raises(ValueError, match=r"^points\[1\]: value \(1e\+300, 1\): too far from sample point 0 \(the distance overflows"):
        pb.roll([(0.0, 0.0), (1e300, 1.0)])
    with pytest.raises(ValueError, match=r"^points\[1\]: value \(0, 0\): repeats the previous sample point$"):
        pb.roll([(0.0, 0.0), (0.0, 0.0)])
    # One step around the closed circle: start and end coincide, the fault of the n given.
    circle = pb.load_problem(problems / "circle.json")
    with pytest.raises(ValueError, match=r"^n: value 1: partition points 0 and 1 are [0-9.e-]+ apart on the plate"):
        pb.plan_setup_for(circle, 1)
    setup = pb.plan_setup_for(circle, 16)
    with pytest.raises(ValueError, match=r"^partition\.n: value 1: partition points 0 and 1 are "):
        pb.plan(setup.problem, setup.options, partition=[pb.UniformParameter(n=1)])
    with pytest.raises(ValueError, match=r"^sweep_n\[1\]: value 1: partition points 0 and 1 are "):
        pb.montecarlo(plan=setup.problem, sweep_n=[8, 1], scenarios=[pb.MonteCarloScenario("none")])
    with pytest.raises(ValueError, match=r"^ns\[0\]: value 1: partition points 0 and 1 are "):
        pb.convergence_setup_for(circle, [1, 2])
    with pytest.raises(ValueError, match=r"^<python>: orientation: value 'x': malformed JSON at line 1, column 1"):
        pb.parse_orientation("x")
    with pytest.raises(ValueError, match=r"^--noise timing: value 0\.5: must be a number in \[0, 0\.1\]$"):
        pb.parse_error_model("timing=0.5", "--noise")


def test_wrong_type_names_the_keyword_and_the_value():
    with pytest.raises(TypeError, match=r"^JoinOptions\(\): max_iterations: value 'x': must be int$"):
        pb.JoinOptions(max_iterations="x")
    with pytest.raises(TypeError, match=r"^join\(\): max_iterations: value 'x': must be int$"):
        pb.join(target=(0.05, 0.0), max_iterations="x")
    with pytest.raises(TypeError, match=r"^identify\(\): radius: value 'r': must be float$"):
        pb.identify(np.linspace(0.0, 1.0, 10), np.zeros((10, 2)), radius="r")


def test_montecarlo_scenario_positional_as_in_the_readme():
    errors = pb.ErrorModel(timing=1e-3)
    s = pb.MonteCarloScenario("late", errors=errors)
    assert s.name == "late" and s.errors.timing == 1e-3
    assert pb.MonteCarloScenario("plain").errors.timing == 0.0
    assert pb.MonteCarloScenario(name="kw").name == "kw"


def test_montecarlo_inputs_are_words_and_checked():
    p = pb.MonteCarloProblem(strategies=["feedback_exact", "open_loop"])
    assert p.strategies == ["feedback_exact", "open_loop"]
    with pytest.raises(ValueError, match="strategies: value"):
        pb.MonteCarloProblem(strategies=["bogus"])
    with pytest.raises(ValueError, match="noise"):
        pb.parse_error_model("impulse_magnitude=2")
    assert str(pb.parse_error_model("timing=1e-4")).startswith("timing")
    pulses = pb.parse_error_model("pulse_duration=0.05,pulse_causal=1")
    assert (pulses.pulse_duration, pulses.pulse_causal) == (0.05, 1.0)
    with pytest.raises(ValueError, match="noise.pulse_causal: value 0.5"):
        pb.parse_error_model("pulse_causal=0.5")


def test_fewest_impulses_keywords_errors_and_words():
    with pytest.raises(ValueError, match=r"max_impulses: value 0"):
        pb.fewest_impulses(max_impulses=0)
    with pytest.raises(TypeError, match="unexpected keyword argument 'goal'"):
        pb.fewest_impulses(goal=(1, 0))
    # One impulse from the vertical axis rolls straight and turns the ball by the length rolled:
    # (3, 3) with the identity is out of reach, the closest arrival is reported.
    miss = pb.fewest_impulses(model=pb.BallModel(2.0), initial=pb.AngleState(0.0, 0.0, 0.0), x1=(3.0, 3.0),
                              max_impulses=1, pareto_counts=1, starts=4)
    assert (miss.status, miss.usable, miss.fewest, miss.fewest_count) == ("not_found", False, 0, None)
    assert len(miss.counts) == 1 and not miss.counts[0].reached and miss.counts[0].position_error > 0.1
    p = pb.FewestImpulsesProblem(x1=(1.5, 0.0), start_at_rest=True, stop_at_goal=True)
    assert (p.start_at_rest, p.stop_at_goal, list(p.x1)) == (True, True, [1.5, 0.0])


def test_steer_from_rest_and_stop_at_goal():
    """The exact arrival's start from rest and stop at the goal: impulse kinds and energies as the tool
    writes them (0 -> mu at the start, mu -> 0 at the goal), replayed independently to the goal."""
    p = pb.ExactArrivalProblem(start_at_rest=True, stop_at_goal=True, impulses=4)
    assert (p.start_at_rest, p.stop_at_goal) == (True, True)
    s = pb.steer(p, pb.ExactArrivalOptions())
    assert s.status == "arrived"
    assert [i.kind for i in s.impulses] == ["start"] + ["energy_preserving"] * 3
    assert [(i.mu_before, i.mu_after) for i in s.impulses] == [(0.0, 1.0)] + [(1.0, 1.0)] * 3
    assert (s.stop.kind, s.stop.mu_before, s.stop.mu_after) == ("stop", 1.0, 0.0)
    replay = pb.replay_exact_arrival(p, s.impulses)
    assert np.allclose(replay.x, [1.0, 0.0], atol=1e-12, rtol=0) and replay.orientation_error < 1e-10
    assert np.allclose(s.stop.position, [1.0, 0.0], atol=1e-12, rtol=0)
    assert pb.steer(impulses=4).stop is None


def test_exact_arrival_is_steer_under_the_cpp_name():
    """exact_arrival() (C++ SolveExactArrival) and its alias steer() (the CLI command) solve the same."""
    a, b = pb.exact_arrival(impulses=4), pb.steer(impulses=4)
    assert a.status == b.status == "arrived"
    assert np.array_equal(a.positions, b.positions) and np.array_equal(a.delta_psi, b.delta_psi)


def test_problems_share_one_start_state():
    """The start state is bound once (StartMotion, StartState): every problem that starts a ball has
    its attributes, with the same defaults; Problem.initial_angles is an alias of initial."""
    for cls in (pb.ExactArrivalProblem, pb.FewestImpulsesProblem, pb.Problem):
        assert issubclass(cls, pb.StartState)
        assert cls().x0.tolist() == [0.0, 0.0]
    for cls in (pb.ExactArrivalProblem, pb.FewestImpulsesProblem, pb.Problem, pb.PlanProblem):
        assert issubclass(cls, pb.StartMotion)
        assert tuple(cls().initial) == tuple(pb.StartMotion().initial)
        assert cls().mu == 1.0 and cls().model.lambda_ == 1.0
        assert np.array_equal(cls().orientation, np.eye(3))
    p = pb.Problem(initial_angles=pb.AngleState(0.1, 0.2, 0.3))
    assert tuple(p.initial) == (0.1, 0.2, 0.3)
    p.initial = pb.AngleState(0.4, 0.5, 0.6)
    assert tuple(p.initial_angles) == (0.4, 0.5, 0.6)


def test_certificate_proves_a_lower_bound_and_says_which_piece_stays_open():
    # 3 rad about e3 and 0.2 away: rolling turns the ball by at most the length rolled, so no
    # solution is shorter than 3; the certificate up to 0.25 closes every piece and proves none.
    summary = pb.isoparallel(goal=(0.2, 0.0), goal_orientation=pb.exp_so3(np.array([0.0, 0.0, 3.0])), starts=64)
    c = pb.certify_isoparallel(summary, length_cap=0.25, threads=2)
    assert (c.status, c.complete, c.usable, c.message) == ("complete", True, True, "")
    assert c.solutions == [] and c.solver_unproved == [] and c.missed_by_solver == 0
    assert len(c.pieces) == 10 and all(p.closed for p in c.pieces)
    assert c.boxes == sum(p.boxes for p in c.pieces) == 584592  # as `isoparallel_solve --certify-length 0.25`
    assert c.report.startswith("Isoparallel certificate: complete, length cap 0.25, 0 solution(s) proved")
    small = pb.certify_isoparallel(summary, pb.IsoparallelCertificateOptions(length_cap=0.25, max_boxes=50))
    assert small.status == "incomplete" and not small.usable
    assert small.message.startswith("not closed: ") and "budget exhausted" in small.message
    with pytest.raises(ValueError, match=r"max_boxes: value 0"):
        pb.certify_isoparallel(summary, max_boxes=0)
    with pytest.raises(TypeError, match="cap"):
        pb.certify_isoparallel(summary, cap=2.0)
