"""Figure 2: the phase portrait of (22)-(23)
=========================================

Figure 2 of the paper: solutions of (22)-(23), theta' = -b sin w, w' = -b cos(theta) cos(w)/sin(theta),
for mu = 1, theta(t0) = m pi/24, w(t0) = n pi, in the (w, theta) plane. The dashed lines are the
singularities theta = 0, pi of the spherical coordinates.

The curves are integrated by the library (IntegrateAngleForm, eqs. (19)-(21); w = phi - psi obeys
(22)-(23) for every lambda) over one period of the closed form of the appendix (AppendixSolution)."""
import math

import numpy as np

import plateball as pb
from gallery_common import out_dir_from_argv, plt, save


def make(out_dir):
    model = pb.BallModel(1.0)
    fig, ax = plt.subplots(figsize=(7.5, 5.0))
    colours = plt.cm.viridis(np.linspace(0.05, 0.95, 11))
    for n in (-1, 0, 1):
        for m in range(1, 12):
            angles = pb.AngleState(m * math.pi / 24, n * math.pi, 0.0)
            period = pb.AppendixSolution(model, angles, 1.0).period
            r = pb.integrate_angle_form(model, angles, 1.0, (0.0, 0.0), np.linspace(0.0, period, 400))
            theta, w = r.angles[:, 0], r.angles[:, 1] - r.angles[:, 2]
            ax.plot(w, theta, color=colours[m - 1], lw=1.2, label=f"m = {m}" if n == 0 else None)
        ax.plot([n * math.pi], [math.pi / 2], "o", color="black", ms=4)
    for theta in (0.0, math.pi):
        ax.axhline(theta, color="black", ls="--", lw=1.0)
    ax.set_xlim(-1.5 * math.pi, 1.5 * math.pi)
    ax.set_ylim(-0.15, math.pi + 0.15)
    ax.set_xticks(np.arange(-1.5, 1.51, 0.5) * math.pi)
    ax.set_xticklabels(["-3π/2", "-π", "-π/2", "0", "π/2", "π", "3π/2"])
    ax.set_yticks([0, math.pi / 4, math.pi / 2, 3 * math.pi / 4, math.pi])
    ax.set_yticklabels(["0", "π/4", "π/2", "3π/4", "π"])
    ax.set_xlabel("w = φ − ψ (rad)")
    ax.set_ylabel("θ (rad)")
    ax.set_title("Figure 2: solutions of (22)-(23), μ = 1, θ(t0) = mπ/24, w(t0) = nπ")
    ax.legend(loc="center left", bbox_to_anchor=(1.01, 0.5), fontsize=8, title="θ(t0) = mπ/24")
    return save(fig, out_dir, "figure2_phase_portrait")


if __name__ == "__main__":
    make(out_dir_from_argv())
