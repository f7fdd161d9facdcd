"""Ctrl-C during a long solve: the solver checks Python's signal handlers from its progress hook on
the calling thread, abandons the work, and KeyboardInterrupt is raised from the call (instead of
the work running to its end with the signal pending)."""
import os
import signal
import threading
import time

import plateball as pb
import pytest

# The interrupted calls below would run for minutes; each must end within this many seconds of
# SIGINT (one start of the search or one trial per thread, plus the unwinding).
LATENCY = 5.0


def interrupted_after(delay, call):
    """Runs call() with SIGINT sent to this process after `delay` s; returns the seconds from the
    signal to the KeyboardInterrupt."""
    assert signal.getsignal(signal.SIGINT) is signal.default_int_handler
    sent = []
    timer = threading.Timer(delay, lambda: (sent.append(time.monotonic()), os.kill(os.getpid(), signal.SIGINT)))
    timer.start()
    try:
        with pytest.raises(KeyboardInterrupt):
            call()
        return time.monotonic() - sent[0]
    finally:
        timer.cancel()


def test_ctrl_c_abandons_the_fewest_impulse_search():
    # A goal no count up to 20 reaches quickly: 10^4 starts per count would take many minutes.
    latency = interrupted_after(0.5, lambda: pb.fewest_impulses(
        model=pb.BallModel(1.7), x1=(40.0, 25.0), max_impulses=20, pareto_counts=1, starts=10000,
        adaptive_starts=10000))
    assert latency < LATENCY


def test_ctrl_c_abandons_monte_carlo_on_every_thread(problems):
    problem = pb.load_problem(problems / "circle.json")
    setup = pb.plan_setup_for(problem, 64)
    errors = pb.parse_error_model("impulse_magnitude=1e-3")
    study = pb.MonteCarloProblem(plan=setup.problem, trials=100000, seed=1, strategies=["feedback"],
                                 scenarios=[pb.MonteCarloScenario(name="e", errors=errors)])
    latency = interrupted_after(0.5, lambda: pb.montecarlo(study, pb.MonteCarloOptions(plan=setup.options, threads=2)))
    assert latency < LATENCY
    # The module still works after an interrupted call.
    study.trials = 2
    assert pb.montecarlo(study, pb.MonteCarloOptions(plan=setup.options, threads=2)).usable


def test_ctrl_c_stops_every_piece_of_the_certificate(problems):
    # The rotation problem's certificate at 1.0001 x its shortest length: 209M boxes, minutes of CPU.
    setup = pb.isoparallel_setup_for(pb.load_problem(problems / "isoparallel_rotation.json"))
    summary = pb.isoparallel(setup.problem, setup.options)
    assert summary.usable
    latency = interrupted_after(0.5, lambda: pb.certify_isoparallel(summary, cap_factor=1.0, threads=2))
    assert latency < LATENCY
    # The module still works after an interrupted call.
    assert pb.certify_isoparallel(summary, length_cap=summary.solutions[0].length, max_boxes=50).status == "incomplete"
