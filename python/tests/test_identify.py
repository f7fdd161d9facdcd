"""identify(t, xy, ...): lambda, mu and the state fitted to a track given as NumPy arrays. The
tracks come from the library's own free motion (pb.simulate), with seeded noise; the CLI's
answer on the same example track is the reference of the binding."""
import json
import math
import os
import subprocess

import numpy as np
import pytest

import plateball as pb

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))


def track(lambda_=1.3, mu=4.0, angles=(0.8, 0.3, 0.2), periods=2.0, n=300, sigma=0.0, seed=1):
    motion, traj = pb.simulate(model=pb.BallModel(lambda_), angles=angles, mu=mu,
                               t_end=periods * 2 * math.pi / math.sqrt(mu), samples=n)
    rng = np.random.default_rng(seed)
    return np.asarray(traj.t), np.asarray(traj.x) + sigma * rng.standard_normal((n, 2))


def test_noiseless_track_recovers_lambda_and_mu():
    t, xy = track()
    s = pb.identify(t, xy, profile_interval=False)
    assert s.status == "identified" and s.usable
    assert abs(s.lambda_ - 1.3) < 1e-8 and abs(s.mu - 4.0) < 1e-8
    assert s.fitted.shape == (300, 2)
    assert np.max(np.abs(s.fitted - xy)) < 1e-9


def test_noisy_track_with_sigma_has_an_interval_around_lambda():
    t, xy = track(sigma=0.005, seed=3)
    s = pb.identify(t, xy, sigma=np.full(len(t), 0.005))
    low, high = s.lambda_interval
    assert s.status == "identified" and low < s.lambda_ < high and not s.sigma_estimated
    assert abs(s.lambda_ - 1.3) < 4 * s.standard_errors[0]
    assert s.interval_method == "profile"


def test_straight_track_does_not_identify_lambda():
    # w = phi - psi = pi/2: v0 = 0, a straight line at speed sqrt(mu) for every lambda.
    t, xy = track(lambda_=1.7, angles=(0.9, 0.4, 0.4 - math.pi / 2), sigma=0.003)
    s = pb.identify(t, xy)
    assert s.status == "lambda_not_identified" and not s.usable and "lambda" in s.unidentified
    assert s.straight_path and "not identifiable from the contact track alone" in s.message
    # The track fixes the path's speed sqrt(mu) = 2 (the chord of the fitted path over the span;
    # noise 0.003 on a chord of ~12 radii); mu itself only within its standard error, since near
    # lambda = 1 every state rolls on a straight line too.
    speed = np.linalg.norm(s.fitted[-1] - s.fitted[0]) / (t[-1] - t[0])
    assert abs(speed - 2.0) < 2e-3
    assert abs(s.mu - 4.0) < 4 * s.standard_errors[1]


def test_bad_input_raises_value_error_naming_the_row():
    t, xy = track(n=20)
    t[5] = t[4]
    with pytest.raises(ValueError, match=r"^t\[5\]: value .*: duplicate time"):
        pb.identify(t, xy)
    with pytest.raises(ValueError, match=r"xy: .*must have shape \(n, 2\)"):
        pb.identify(np.arange(10.0), np.zeros((10, 3)))
    with pytest.raises(ValueError, match=r"t \(rows\): value 3: too few samples"):
        pb.identify(np.arange(3.0), np.zeros((3, 2)))
    with pytest.raises(TypeError, match="unexpected keyword argument 'lambda_guess'"):
        pb.identify(np.arange(10.0), np.zeros((10, 2)), lambda_guess=1.0)


def test_the_binding_gives_the_cli_answer_on_the_example_track():
    cli = os.environ.get("PLATEBALL_CLI")
    if not cli:
        pytest.skip("PLATEBALL_CLI not set")
    path = os.path.join(ROOT, "tests", "data", "identify_track.csv")
    doc = json.loads(subprocess.run([cli, "identify", path], check=True, capture_output=True, text=True).stdout)
    data = np.loadtxt(path, delimiter=",", comments="#", skiprows=3)
    s = pb.identify(data[:, 0], data[:, 1:3])
    assert s.status == doc["status"]
    # The CSV's numbers read by C++ strtod and NumPy are the same doubles: the same fit to the digit.
    assert s.lambda_ == doc["fit"]["lambda"] and s.mu == doc["fit"]["mu"]
    assert s.lambda_interval == (doc["fit"]["lambda_interval"]["low"], doc["fit"]["lambda_interval"]["high"])


def impulse_track():
    """The example track of eight flights between known impulses (the circle plan, noise 0.002)."""
    path = os.path.join(ROOT, "tests", "data", "identify_impulses_track.csv")
    with open(path) as f:
        impulses = [float(v) for v in [line for line in f if line.startswith("#")][-1].lstrip("# ").split(",")]
    data = np.loadtxt(path, delimiter=",", comments="#", skiprows=5)
    return path, data[:, 0], data[:, 1:3], np.asarray(impulses)


def test_impulses_at_known_times_give_lambda_and_each_delta_psi():
    _, t, xy, impulses = impulse_track()
    s = pb.identify(t, xy, impulse_times=impulses, profile_interval=False)
    assert s.status == "identified"
    # The plan's values (problems/circle.json with n = 8): lambda = 2 and the first delta psi.
    assert abs(s.lambda_ - 2.0) < 4 * s.standard_errors[0]
    assert abs(s.delta_psi[0] - 0.7486843166879056) < 4 * s.standard_errors[7]
    assert len(s.delta_psi) == 7 and len(s.standard_errors) == 14 and s.correlation.shape == (14, 14)
    assert list(s.impulse_times) == list(impulses)
    assert [f.t_start for f in s.flights] == [t[0]] + list(impulses)
    # Each flight starts at the sample at its impulse (noise 0.002): x is continuous across it.
    for f in s.flights[1:]:
        assert np.min(np.linalg.norm(xy - f.x, axis=1)) < 0.01


def test_bad_impulse_times_raise_value_error_naming_the_field():
    _, t, xy, impulses = impulse_track()
    with pytest.raises(ValueError, match=r"^impulse_times\[1\]: value .*: impulse times must be strictly increasing"):
        pb.identify(t, xy, impulse_times=impulses[::-1])
    with pytest.raises(ValueError, match=r"^impulse_times\[0\]: value 99: must be inside the track"):
        pb.identify(t, xy, impulse_times=[99.0])
    with pytest.raises(ValueError, match=r"impulse_times: .*must be 1-dimensional"):
        pb.identify(t, xy, impulse_times=np.zeros((2, 2)))


def test_the_binding_gives_the_cli_answer_on_the_impulse_track():
    cli = os.environ.get("PLATEBALL_CLI")
    if not cli:
        pytest.skip("PLATEBALL_CLI not set")
    path, t, xy, impulses = impulse_track()
    doc = json.loads(subprocess.run([cli, "identify", path, "--no-profile", "--impulses", ",".join(repr(v) for v in impulses)],
                                    check=True, capture_output=True, text=True).stdout)
    s = pb.identify(t, xy, impulse_times=impulses, profile_interval=False)
    assert s.lambda_ == doc["fit"]["lambda"]
    assert list(s.delta_psi) == [i["delta_psi"] for i in doc["fit"]["impulses"]]


def test_a_measured_spin_identifies_lambda_on_a_straight_track():
    # tests/data/identify_spin_track.csv: lambda = 1, a straight contact path; the axial spin
    # v0 = <omega, z> (an IMU's rate about the symmetry axis) shows v0 != 0.
    data = np.loadtxt(os.path.join(ROOT, "tests", "data", "identify_spin_track.csv"), delimiter=",", comments="#", skiprows=4)
    t, xy, sigma, spin, sigma_spin = data[:, 0], data[:, 1:3], data[:, 3], data[:, 4], data[:, 5]
    alone = pb.identify(t, xy, sigma=sigma, profile_interval=False)
    assert alone.status == "lambda_not_identified" and alone.straight_path
    s = pb.identify(t, xy, sigma=sigma, spin=spin, sigma_spin=sigma_spin, profile_interval=False)
    assert s.status == "identified" and abs(s.lambda_ - 1.0) < 4 * s.standard_errors[0]
    assert len(s.fitted_spin) == len(t) and abs(s.spin_rms_residual - 0.002) < 5e-4
    with pytest.raises(ValueError, match=r"^sigma_spin \(rows\): value 0"):
        pb.identify(t, xy, sigma=sigma, spin=spin)


def quaternions(rotations):
    """Unit quaternions (w, x, y, z), w >= 0, of an (n, 3, 3) array of rotations (Shepperd's method
    on the trace branch: every rotation here turns by less than pi)."""
    r = np.asarray(rotations)
    w = 0.5 * np.sqrt(1.0 + np.trace(r, axis1=1, axis2=2))
    q = np.stack([w, (r[:, 2, 1] - r[:, 1, 2]) / (4 * w), (r[:, 0, 2] - r[:, 2, 0]) / (4 * w),
                  (r[:, 1, 0] - r[:, 0, 1]) / (4 * w)], axis=1)
    return q / np.linalg.norm(q, axis=1)[:, None]


def frame_track(periods=0.15, n=60):
    motion, traj = pb.simulate(model=pb.BallModel(1.3), angles=(0.8, 0.3, 0.2), mu=4.0,
                               t_end=periods * math.pi, samples=n)
    rates = np.einsum("nji,nj->ni", np.asarray(traj.orientation), np.asarray(traj.omega))  # A^T omega
    return np.asarray(traj.t), np.asarray(traj.x), quaternions(traj.orientation), rates


def test_orientations_identify_lambda_and_the_frame_on_a_short_flight():
    t, xy, q, _ = frame_track()
    s = pb.identify(t, xy, orientation=q, profile_interval=False)
    assert s.status == "identified" and s.frame_fitted
    assert abs(s.lambda_ - 1.3) < 1e-8
    assert s.parameters[7] == "chi" and len(s.standard_errors) == 8
    assert s.fitted_orientation.shape == (60, 4)
    assert np.max(np.abs(s.fitted_orientation - q)) < 1e-8
    assert np.max(np.abs(np.asarray(s.orientation) - q[0])) < 1e-8
    # The same positions alone: lambda not identified on 0.15 period (noise 0.002 on both).
    rng = np.random.default_rng(5)
    noisy = xy + 0.002 * rng.standard_normal(xy.shape)
    contact = pb.identify(t, noisy, sigma=np.full(len(t), 0.002))
    assert contact.status == "lambda_not_identified"


def test_body_rates_identify_lambda():
    t, xy, _, rates = frame_track()
    rng = np.random.default_rng(6)
    sigma = np.full(len(t), 0.002)
    s = pb.identify(t, xy + 0.002 * rng.standard_normal(xy.shape), sigma=sigma,
                    body_rate=rates + 0.002 * rng.standard_normal(rates.shape), sigma_body_rate=sigma)
    low, high = s.lambda_interval
    assert s.status == "identified" and low < 1.3 < high
    assert s.fitted_body_rate.shape == (60, 3) and s.body_rate_rms_residual < 0.004


def test_bad_orientation_raises_value_error_naming_the_row():
    t, xy, q, rates = frame_track(n=20)
    with pytest.raises(ValueError, match=r"^orientation: value \(array of shape not \(n, 4\)\)"):
        pb.identify(t, xy, orientation=q[:, :3])
    q[2] *= 1.01
    with pytest.raises(ValueError, match=r"^orientation\[2\]: value .*not a unit quaternion \(w, x, y, z\): norm 1.01"):
        pb.identify(t, xy, orientation=q)
    with pytest.raises(ValueError, match=r"give either spin or body_rate, not both"):
        pb.identify(t, xy, sigma=np.ones(20), spin=np.zeros(20), sigma_spin=np.ones(20), body_rate=rates,
                    sigma_body_rate=np.ones(20))
