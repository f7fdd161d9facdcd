"""Figure 8: reaching points
=========================

Figure 8 of the paper: reaching points by taking different values of (delta psi)_k; mu = 1,
lambda = 2, theta0 = -pi/3, phi0 = pi/2, psi0 = 0 (problems/figure8_reach.json). Thin lines: the
free motion after the impulse psi -> psi + delta psi for eight values of delta psi (three periods);
thick lines: the earliest solution of Reach for each target of the file."""
import math

import numpy as np

import plateball as pb
from gallery_common import PROBLEMS, out_dir_from_argv, plt, save


def free_path(problem, delta_psi, t_end, n=600):
    a = problem.initial
    motion = pb.FreeMotion(problem.model, (a.theta, a.phi, a.psi + delta_psi), problem.mu, problem.x0,
                           problem.orientation, problem.integration)
    return motion.sample(0.0, t_end, n).x


def make(out_dir):
    problem = pb.load_problem(PROBLEMS / "figure8_reach.json")
    period = 2 * math.pi / math.sqrt(problem.mu)
    fig, ax = plt.subplots(figsize=(8.2, 6.6))
    colours = plt.cm.hsv(np.linspace(0.0, 0.875, 8))
    names = ["0", "π/4", "π/2", "3π/4", "π", "5π/4", "3π/2", "7π/4"]
    for k in range(8):
        x = free_path(problem, k * math.pi / 4, 3 * period)
        ax.plot(x[:, 0], x[:, 1], color=colours[k], lw=0.9, alpha=0.7, label=f"Δψ = {names[k]}, 3 periods")
    for target, colour in zip(problem.reach.targets, ["#1f77b4", "#d62728", "#2ca02c"]):
        s = pb.reach(*pb.reach_setup_for(problem, target))
        e = s.earliest()
        x = free_path(problem, e.delta_psi, e.t)
        ax.plot(x[:, 0], x[:, 1], color=colour, lw=2.4,
                label=f"reach ({target[0]:g}, {target[1]:g}): Δψ = {e.delta_psi:.4f}, t = {e.t:.3f}")
        ax.plot([target[0]], [target[1]], "o", mfc="none", mec=colour, ms=10, mew=2)
    ax.plot([0], [0], "ks", ms=6)
    ax.annotate("x0", (0, 0), textcoords="offset points", xytext=(6, -12))
    ax.set_aspect("equal", adjustable="datalim")
    ax.set_xlabel("x1 (ball radii)")
    ax.set_ylabel("x2 (ball radii)")
    ax.set_title("Figure 8: reaching points with different Δψ\nμ = 1, λ = 2, θ0 = −π/3, φ0 = π/2, ψ0 = 0")
    ax.legend(loc="center left", bbox_to_anchor=(1.01, 0.5), fontsize=8)
    return save(fig, out_dir, "figure8_reach")


if __name__ == "__main__":
    make(out_dir_from_argv())
