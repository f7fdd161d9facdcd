"""Convergence: the error against the number of impulses
=====================================================

The convergence chart (section 2.3, Theorem 2.6 / Corollary 3): the measured error
``||A(T) - A~_n||``, the polyline's error, the reported a-posteriori bound and Theorem 2.6's bound
against the number n of impulses, for one lap of the circle of problems/circle.json; the fitted
log-log slope of the error is -2."""
import numpy as np

import plateball as pb
from gallery_common import PROBLEMS, out_dir_from_argv, plt, save


def make(out_dir):
    problem = pb.load_problem(PROBLEMS / "circle.json")
    ns = [16, 32, 64, 128, 256, 512, 1024]
    setup = pb.convergence_setup_for(problem, ns)
    study = pb.converge(setup.problem, setup.options)
    n = study.column("n")
    fig, ax = plt.subplots(figsize=(7.0, 5.2))
    series = [("measured_error", "measured error ||A(T) − Ã_n||", "o-", "#d62728"),
              ("polyline_error", "polyline error ||A(T) − Ā_n||", "s-", "#ff7f0e"),
              ("bound", "a-posteriori bound (reported)", "^--", "#1f77b4"),
              ("theorem_2_6", "Theorem 2.6 bound", "v:", "#2ca02c")]
    for column, label, style, colour in series:
        ax.loglog(n, study.column(column), style, color=colour, label=label, ms=5)
    fit = study.column("measured_error")[0] * (n / n[0]) ** study.error_slope
    ax.loglog(n, fit, "-", color="grey", lw=0.8, label=f"fit: slope {study.error_slope:.3f}")
    ax.set_xlabel("impulses n")
    ax.set_ylabel("orientation error (operator norm)")
    ax.set_xticks(ns)
    ax.set_xticklabels([str(v) for v in ns])
    ax.minorticks_off()
    ax.set_title("Convergence on the circle (T2): error O(1/n²), bound holds on every n"
                 if study.bound_holds else "Convergence on the circle (T2)")
    ax.legend(loc="lower left", fontsize=8)
    return save(fig, out_dir, "convergence_chart")


if __name__ == "__main__":
    make(out_dir_from_argv())
