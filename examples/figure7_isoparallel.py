"""Figure 7: the isoparallel path and its impulses
===============================================

Figure 7 of the paper: approximating a solution of the isoparallel problem. The ball goes from
(0, 0) to (3, 3) and the resulting rotation is the identity (problems/figure7.json: lambda = 2,
mu = 1, 12 impulses). Dashed: the optimal curve; solid: the impulsive approximation (every free arc
re-integrated from its impulse); dots: where the impulses act."""
import plateball as pb
from gallery_common import PROBLEMS, out_dir_from_argv, plt, save


def make(out_dir):
    problem = pb.load_problem(PROBLEMS / "figure7.json")
    summary = pb.isoparallel(*pb.isoparallel_setup_for(problem))
    best = summary.shortest()
    plan = pb.plan_optimal_path(*pb.isoparallel_plan_setup_for(problem, best))
    traj = plan.trajectory(problem.model, samples_per_arc=40, integration=problem.integration)
    path = best.points(400)
    fig, ax = plt.subplots(figsize=(6.6, 6.0))
    ax.plot(path[:, 0], path[:, 1], "--", color="#1f77b4", lw=1.6, label=f"optimal curve (length {best.length:.4f})")
    ax.plot(traj.x[:, 0], traj.x[:, 1], "-", color="#d62728", lw=1.4,
            label=f"impulsive approximation ({plan.segments} impulses)")
    ax.plot(plan.pass_points[:, 0], plan.pass_points[:, 1], "o", color="#d62728", ms=4, label="impulses")
    ax.plot([0, 3], [0, 3], "ks", ms=6)
    ax.annotate("start (0, 0)", (0, 0), textcoords="offset points", xytext=(8, -12))
    ax.annotate("goal (3, 3)", (3, 3), textcoords="offset points", xytext=(8, 0))
    ax.set_aspect("equal", adjustable="datalim")
    ax.set_xlabel("x1 (ball radii)")
    ax.set_ylabel("x2 (ball radii)")
    ax.set_title(f"Figure 7: isoparallel path and impulsive approximation\n"
                 f"||A(T) − Ã_n|| = {plan.measured_error:.3g} ≤ bound {plan.bounds.a_posteriori:.3g}")
    ax.legend(loc="upper center", bbox_to_anchor=(0.5, -0.1), ncol=2, fontsize=8)
    return save(fig, out_dir, "figure7_isoparallel")


if __name__ == "__main__":
    make(out_dir_from_argv())
