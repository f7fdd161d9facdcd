"""plateball: impulsive control of a symmetric ball rolling without sliding or spinning.

A thin Python binding of the C++ library (pybind11). Every solver is one call that takes its
problem and options either as objects or as keyword arguments (a keyword names a field of the
problem or of the options; unknown keywords are a TypeError), and returns the library's summary
with NumPy arrays for trajectories, orientations and impulses, the same status words
("converged", "success", ...) and messages as the tools. Invalid input raises ValueError with the
library's message (FIELD: value V: what). The solvers release the GIL. For example::

    import plateball as pb
    s = pb.join(model=pb.BallModel(2.0), start=(1.0471975511965976, 0.4, 0.1), target=(0.05, 0))
    s.status, s.delta_psi, s.t

    problem = pb.read_problem_file("problems/circle.json")
    plan = pb.plan(*pb.plan_setup_for(problem))        # what `plateball plan` runs
"""

import functools
import os
import re
import sys

from ._build_info import PYTHON_EXECUTABLE as _BUILT_FOR, PYTHON_VERSION as _BUILT_VERSION


def _interpreter_error(reason):
    here = f"{sys.executable} (Python {sys.version_info[0]}.{sys.version_info[1]}.{sys.version_info[2]})"
    return ImportError(f"plateball: the compiled module was built for {_BUILT_FOR} (Python {_BUILT_VERSION}), "
                       f"this interpreter is {here}: {reason}. Run it with {_BUILT_FOR}, or build the module "
                       f"for this interpreter (cmake -DPython_EXECUTABLE={sys.executable}, or "
                       f"{sys.executable} -m pip install . --no-build-isolation)")


# A different minor version cannot load the extension at all (its ABI tag differs): say so first.
if tuple(sys.version_info[:2]) != tuple(int(v) for v in _BUILT_VERSION.split(".")[:2]):
    raise _interpreter_error("the Python versions differ")
try:
    from ._plateball import *  # noqa: F401,F403
except ImportError as _error:  # same version, other interpreter: e.g. without Debian's NumPy
    raise _interpreter_error(f"importing the extension failed ({_error})") from _error
from ._plateball import (__version__, _certify_isoparallel, _converge, _isoparallel, _join, _plan, _plan_optimal_path,  # noqa: F401
                         _reach, _steer, _fewest_impulses, _identify, ConvergenceOptions, ConvergenceProblem,
                         ExactArrivalOptions, ExactArrivalProblem, FewestImpulsesOptions, FewestImpulsesProblem,
                         IdentifyOptions, IsoparallelCertificateOptions, IsoparallelOptions, IsoparallelPlanProblem,
                         IsoparallelProblem,
                         JoinOptions, JoinProblem, MonteCarloOptions, MonteCarloProblem, PlanOptions, PlanProblem,
                         ReachOptions, ReachProblem, _montecarlo)


@functools.lru_cache(maxsize=None)
def _fields(cls):
    return frozenset(k for k in dir(cls) if not k.startswith("_"))


def _set(caller, target, key, value):
    """setattr naming the keyword and the value when the type is wrong (pybind11's setter names neither)."""
    try:
        setattr(target, key, value)
    except TypeError as error:
        # A field property's "CLASS.FIELD: value V: must be TYPE", or pybind11's signature.
        expected = re.search(r": must be ([^\n]*)$", str(error)) or re.search(r"arg0: (.*?)\) ->", str(error))
        raise TypeError(f"{caller}(): {key}: value {value!r}: "
                        + (f"must be {expected.group(1)}" if expected else "has the wrong type")) from None


def _solve(native, problem_type, options_type, problem, options, kwargs):
    """Builds the problem and options from objects and/or keywords, then calls the solver."""
    if not kwargs and problem is not None and options is not None:
        return native(problem, options)
    problem = problem_type() if problem is None else problem
    options = options_type() if options is None else options
    problem_fields, options_fields = _fields(problem_type), _fields(options_type)
    for key, value in kwargs.items():
        if key in problem_fields:
            _set(native.__name__.lstrip('_'), problem, key, value)
        elif key in options_fields:
            _set(native.__name__.lstrip('_'), options, key, value)
        else:
            raise TypeError(f"{native.__name__.lstrip('_')}(): unexpected keyword argument '{key}' "
                            f"(not a field of {problem_type.__name__} or {options_type.__name__})")
    return native(problem, options)


def join(problem=None, options=None, **kwargs):
    """Join x0 to a close target with one energy-preserving impulse (Lemma 2.1): a JoinSummary."""
    return _solve(_join, JoinProblem, JoinOptions, problem, options, kwargs)


def reach(problem=None, options=None, **kwargs):
    """Every (delta_psi, t) reaching a distant target within the horizon (section 2.3): a ReachSummary."""
    return _solve(_reach, ReachProblem, ReachOptions, problem, options, kwargs)


def plan(problem=None, options=None, **kwargs):
    """Follow a planned path with impulses (section 2.3, Theorems 2.5/2.6): a PlanSummary."""
    return _solve(_plan, PlanProblem, PlanOptions, problem, options, kwargs)


def converge(problem=None, options=None, **kwargs):
    """Plans for several partition sizes and the log-log slopes (Corollary 3): a ConvergenceStudy."""
    return _solve(_converge, ConvergenceProblem, ConvergenceOptions, problem, options, kwargs)


def isoparallel(problem=None, options=None, **kwargs):
    """Shortest paths with a given reorientation (section 2.2): an IsoparallelSummary."""
    return _solve(_isoparallel, IsoparallelProblem, IsoparallelOptions, problem, options, kwargs)


def certify_isoparallel(summary, options=None, **kwargs):
    """The certificate of an isoparallel summary of a general target: every solution up to the cap
    proved, or the piece of parameter space that did not close (an IsoparallelCertificate; minutes
    at the shortest length). Keywords: the fields of IsoparallelCertificateOptions. Ctrl-C stops every
    piece within about a thousand boxes and raises KeyboardInterrupt."""
    options = IsoparallelCertificateOptions() if options is None else options
    fields = _fields(IsoparallelCertificateOptions)
    for key, value in kwargs.items():
        if key not in fields:
            raise TypeError(f"certify_isoparallel(): unexpected keyword argument '{key}' "
                            f"(not a field of IsoparallelCertificateOptions)")
        _set("certify_isoparallel", options, key, value)
    return _certify_isoparallel(summary, options)


def plan_optimal_path(problem=None, options=None, **kwargs):
    """The impulsive approximation of an isoparallel solution (Figure 7): a PlanSummary."""
    return _solve(_plan_optimal_path, IsoparallelPlanProblem, PlanOptions, problem, options, kwargs)


def exact_arrival(problem=None, options=None, **kwargs):
    """Exact arrival at (x1, A1) with n impulses closest to a reference path (C++ SolveExactArrival,
    `plateball steer`): an ExactArrivalSummary."""
    return _solve(_steer, ExactArrivalProblem, ExactArrivalOptions, problem, options, kwargs)


def steer(problem=None, options=None, **kwargs):
    """The same call as exact_arrival(), under the name of the `plateball steer` command (kept)."""
    return exact_arrival(problem, options, **kwargs)


def identify(t, xy, sigma=None, options=None, impulse_times=None, spin=None, sigma_spin=None, orientation=None,
             sigma_orientation=None, body_rate=None, sigma_body_rate=None, **kwargs):
    """Fits lambda, mu and the state at t[0] to a track of the contact point: t (n,), xy (n, 2),
    sigma (n,) or None (estimated); impulse_times (m,) or None: known energy-preserving impulses
    between the flights (one delta psi fitted per impulse, lambda and mu shared); spin (n,) and
    sigma_spin (n,) or None: a measured axial spin v0 (an IMU's rate about the symmetry axis;
    needs sigma given); orientation (n, 4) or None: measured unit quaternions (w, x, y, z) of the
    body-to-world rotation (norm within 1e-5 of 1), sigma_orientation (n,) their noise in rad
    (with sigma, or neither: one common sigma); body_rate (n, 3) and sigma_body_rate (n,) or None:
    an IMU's three rates A^T omega in the body frame (needs sigma; not with spin). Orientations and
    body rates fit the frame too (the parameter chi) and identify lambda even on a short flight.
    Keywords name
    fields of IdentifyOptions (radius, guess, ...). Returns IdentifySummary (status "identified",
    "lambda_not_identified", "no_fit", "failed")."""
    options = IdentifyOptions() if options is None else options
    fields = _fields(IdentifyOptions)
    for key, value in kwargs.items():
        if key not in fields:
            raise TypeError(f"identify(): unexpected keyword argument '{key}'")
        _set("identify", options, key, value)
    return _identify(t, xy, sigma, impulse_times, spin, sigma_spin, orientation, sigma_orientation, body_rate,
                     sigma_body_rate, options)


def fewest_impulses(problem=None, options=None, **kwargs):
    """The fewest impulses that reach (x1, A1) exactly, with the Pareto table of impulse count
    against total time: a FewestImpulsesSummary."""
    return _solve(_fewest_impulses, FewestImpulsesProblem, FewestImpulsesOptions, problem, options, kwargs)


def montecarlo(problem=None, options=None, **kwargs):
    """A plan executed under errors by each strategy, many seeded trials: a MonteCarloSummary."""
    return _solve(_montecarlo, MonteCarloProblem, MonteCarloOptions, problem, options, kwargs)


def simulate(model=None, angles=None, mu=1.0, x0=(0.0, 0.0), orientation=None, t_end=10.0, samples=101,
             integration=None, problem=None):
    """The free rolling sampled at `samples` equal steps on [0, t_end] (what `plateball simulate` prints):
    returns (FreeMotion, Trajectory). With `problem` (a Problem), its ball, initial state, integration
    and simulate section are used, as the tool does."""
    if problem is not None:
        motion = free_motion_for(problem)
        task = problem.simulate if problem.simulate is not None else SimulateTask()
        return motion, motion.sample(0.0, task.t_end, task.samples)
    import numpy as np
    motion = FreeMotion(model if model is not None else BallModel(1.0),
                        AngleState(*angles) if angles is not None else StartMotion().initial,
                        mu, np.asarray(x0, dtype=float),
                        np.eye(3) if orientation is None else np.asarray(orientation, dtype=float),
                        integration if integration is not None else IntegrationOptions())
    return motion, motion.sample(0.0, t_end, samples)


def roll(points, segment=False, integration=None):
    """The reorientation R = A(end) A(start)^-1 of rolling along planar points: the polyline
    (segment=True, exact) or their natural cubic spline (`plateball roll --points`)."""
    import numpy as np
    pts = [np.asarray(p, dtype=float) for p in points]
    if segment:
        return roll_along_polyline(pts)
    return roll_along_samples(pts, integration if integration is not None else IntegrationOptions())


def load_problem(path):
    """Reads a problem file with the library's reader (same checks and messages as the tools; at
    most MAX_PROBLEM_FILE_BYTES bytes, as parse_problem and the tools' standard input).

    path: a str or os.PathLike; anything else raises TypeError (str(None) would name a file "None")."""
    if not isinstance(path, (str, os.PathLike)):
        raise TypeError("load_problem(): path: value " + repr(path) + ": must be a str or os.PathLike")
    return read_problem_file(os.fspath(path))
