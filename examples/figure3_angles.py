"""Figure 3: the angles of the free motion
=======================================

Figure 3 of the paper: solutions of (19)-(21) for mu = 1, lambda = 1/2, psi(t0) = 0, phi(t0) = 0,
theta(t0) = m pi/24 (m = 1, ..., 12): theta(t), phi(t), psi(t) and the contact point x(t) on the
plate, integrated by the library (IntegrateAngleForm, with x' = (omega_2, -omega_1))."""
import math

import numpy as np

import plateball as pb
from gallery_common import out_dir_from_argv, plt, save


def make(out_dir):
    model = pb.BallModel(0.5)
    times = np.linspace(0.0, 4 * math.pi, 600)  # two periods 2 pi / sqrt(mu)
    fig, axes = plt.subplots(2, 2, figsize=(10, 7.2))
    colours = plt.cm.plasma(np.linspace(0.0, 0.9, 12))
    for m in range(1, 13):
        r = pb.integrate_angle_form(model, (m * math.pi / 24, 0.0, 0.0), 1.0, (0.0, 0.0), times)
        for k, ax in enumerate(axes.flat[:3]):
            ax.plot(r.t, r.angles[:, k], color=colours[m - 1], lw=1.1, label=f"m = {m}")
        axes[1, 1].plot(r.x[:, 0], r.x[:, 1], color=colours[m - 1], lw=1.1)
    for ax, name in zip(axes.flat[:3], ["θ", "φ", "ψ"]):
        ax.set_xlabel("t")
        ax.set_ylabel(f"{name} (rad)")
        ax.set_xlim(0, times[-1])
    axes[0, 0].axhline(math.pi / 2, color="grey", lw=0.8, ls=":")
    axes[1, 1].plot([0], [0], "ko", ms=4)
    axes[1, 1].set_aspect("equal", adjustable="datalim")
    axes[1, 1].set_xlabel("x1 (ball radii)")
    axes[1, 1].set_ylabel("x2 (ball radii)")
    axes[1, 1].set_title("contact point x(t), t ≤ 4π")
    handles, labels = axes[0, 0].get_legend_handles_labels()
    fig.legend(handles, labels, loc="center right", fontsize=8, title="θ(t0) = mπ/24")
    fig.suptitle("Figure 3: solutions of (19)-(21), μ = 1, λ = 1/2, φ(t0) = ψ(t0) = 0")
    fig.tight_layout(rect=(0, 0, 0.88, 0.96))
    return save(fig, out_dir, "figure3_angles")


if __name__ == "__main__":
    make(out_dir_from_argv())
