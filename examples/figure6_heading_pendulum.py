"""Figure 6: the heading pendulum
==============================

Figure 6 of the paper: along an optimal path of the isoparallel problem the velocity vector
behaves like a nonlinear pendulum, g'' = -G cos(g - g_W) (omega_0^2 = g/R = G). Left: Figure 7's
optimal paths (the shortest three solutions) with their unit velocity vectors; right: the
pendulum's phase portrait (g - g_W, g') of every solution found, oscillating and rotating.
Everything from the library: SolveIsoparallel on problems/figure7.json and the Elastica."""
import math

import numpy as np

import plateball as pb
from gallery_common import PROBLEMS, out_dir_from_argv, plt, save


def make(out_dir):
    problem = pb.load_problem(PROBLEMS / "figure7.json")
    summary = pb.isoparallel(*pb.isoparallel_setup_for(problem))
    fig, (left, right) = plt.subplots(1, 2, figsize=(11, 5.0))
    colours = ["#1f77b4", "#d62728", "#2ca02c"]
    for sol, colour in zip(summary.solutions[:3], colours):
        pts = sol.points(400)
        left.plot(pts[:, 0], pts[:, 1], color=colour, lw=1.4,
                  label=f"length {sol.length:.4f} ({sol.parameters.regime})")
        s = np.linspace(0.0, sol.length, 25)[1:-1]
        el = sol.elastica()
        p = np.array([sol.position_at(a) for a in s])
        g = el.heading(s)
        left.quiver(p[:, 0], p[:, 1], np.cos(g), np.sin(g), color=colour, angles="xy", scale_units="xy",
                    scale=2.5, width=0.004)
    left.plot([0, 3], [0, 3], "ks", ms=5)
    left.annotate("x0", (0, 0), textcoords="offset points", xytext=(-14, -12))
    left.annotate("x1", (3, 3), textcoords="offset points", xytext=(6, 4))
    left.set_aspect("equal", adjustable="datalim")
    left.set_xlabel("x1 (ball radii)")
    left.set_ylabel("x2 (ball radii)")
    left.set_title("optimal paths and their velocity vectors")
    left.legend(loc="upper left", fontsize=8)
    for sol in summary.solutions:
        el = sol.elastica()
        s = np.linspace(0.0, min(sol.length, el.period if el.period > 0 else sol.length), 400)
        angle = np.mod(el.heading(s) - sol.parameters.heading_w + math.pi, 2 * math.pi) - math.pi
        colour = "#1f77b4" if sol.parameters.regime == "oscillating" else "#d62728"
        rate = el.curvature(s) / math.sqrt(el.G)  # g' in units of omega_0 = sqrt(G)
        breaks = np.nonzero(np.abs(np.diff(angle)) > math.pi)[0] + 1  # wrapped at +-pi: no line across
        right.plot(np.insert(angle, breaks, np.nan), np.insert(rate, breaks, np.nan), "-", lw=0.7, color=colour)
    right.plot([], [], "-", lw=2, color="#1f77b4", label="oscillating (libration)")
    right.plot([], [], "-", lw=2, color="#d62728", label="rotating")
    right.set_xlim(-math.pi, math.pi)
    right.set_xticks([-math.pi, -math.pi / 2, 0, math.pi / 2, math.pi])
    right.set_xticklabels(["-π", "-π/2", "0", "π/2", "π"])
    right.set_xlabel("pendulum angle g − g_W (rad)")
    right.set_ylabel("g′ / ω0  (ω0² = G)")
    right.set_title(f"heading pendulum g″ = −G cos(g − g_W): {len(summary.solutions)} solutions")
    right.legend(loc="upper center", bbox_to_anchor=(0.5, -0.13), ncol=2, fontsize=8)
    fig.suptitle("Figure 6: the velocity vector of an isoparallel path behaves like a nonlinear pendulum")
    fig.tight_layout(rect=(0, 0, 1, 0.95))
    return save(fig, out_dir, "figure6_heading_pendulum")


if __name__ == "__main__":
    make(out_dir_from_argv())
