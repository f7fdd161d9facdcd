"""The controller's binding: a dry run from the contact point alone follows the circle's plan to
its goal, and bad measurements and arguments are statuses or ValueErrors naming the field."""
import math

import numpy as np
import pytest

import plateball as pb

TICK = 1e-3
# One Euler step of the contact point per tick errs by ~|x''| dt^2 / 2; the join corrects it at each
# impulse, so the end is within a tick's travel (|x'| <= 1.5) of the goal.
GOAL_TOLERANCE = 1.5 * TICK


def pb_path(relative):
    import pathlib
    return str(pathlib.Path(__file__).resolve().parents[2] / relative)


@pytest.fixture(scope="module")
def plan():
    s = pb.plan_setup_for(pb.load_problem(pb_path("problems/circle.json")), 32)
    return pb.make_nominal_plan(s.problem, s.options)


def test_a_dry_run_from_the_contact_point_reaches_the_goal(plan):
    assert plan.status == "success" and plan.impulses == 32
    c = pb.Controller(plan, pb.ControllerOptions(tick_period=TICK))
    out = c.update(0.0, plan.pass_points[0])
    impulses = int(out.impulse)
    assert out.status == "ok" and out.impulse and out.impulse_index == 0
    assert out.next_impulse_tick == round(out.at_next_impulse.tick)
    for tick in range(1, 30000):
        w = out.now.state.omega
        out = c.update(tick * TICK, out.now.x + TICK * np.array([w[1], -w[0]]))
        impulses += int(out.impulse)
        if out.status != "ok":
            break
    assert out.status == "done"
    assert impulses == 32
    assert abs(tick * TICK - plan.total_time) <= TICK
    assert np.linalg.norm(out.now.x - plan.goal) < GOAL_TOLERANCE


def test_bad_measurements_are_statuses_and_bad_arguments_value_errors(plan):
    c = pb.Controller(plan, pb.ControllerOptions(tick_period=TICK))
    out = c.update(0.0, np.array([math.nan, 0.0]))
    assert out.status == "measurement_rejected" and "not finite" in out.reason
    assert c.update(math.inf, plan.pass_points[0]).status == "time_out_of_order"
    with pytest.raises(ValueError, match="orientation"):
        c.update(0.0, plan.pass_points[0], orientation=np.eye(3))
    with pytest.raises(ValueError, match="tick_period: value 0"):
        pb.Controller(plan, pb.ControllerOptions(tick_period=0.0))
    with pytest.raises(ValueError, match="strategy"):
        pb.ControllerOptions(strategy="open_loop_please")
    assert "strategy" in pb.ControllerOptions(strategy="open_loop").validate()
